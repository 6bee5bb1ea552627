/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file vspBenchUtils.h
  \brief Small helpers shared by the benchmark and stress programs: a median-of-batches timer (Google
  Benchmark), a sink that keeps results alive, seeded random rotations.
*/
#ifndef VSP_BENCH_UTILS_H
#define VSP_BENCH_UTILS_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vspBench
{
/*!
  Accumulates a value computed from every result so that the optimiser cannot drop the timed call.
  The global is volatile: a store to it is an observable side effect. A non-finite value (a failed solve of
  one of the gravity peers) counts as 1, so that the printed sum stays a number.
*/
inline volatile double g_sink = 0.0;
inline void consume(double v) { g_sink = g_sink + (std::isfinite(v) ? v : 1.0); }

/*!
  Median time per batch divided by \e nInstances, in nanoseconds: \e batch runs as one Google
  Benchmark with \e repetitions repetitions lasting about \e minSeconds in all (CPU time of the
  benchmark thread, median aggregate). Defined in benchmark/peers/benchTimer.cpp (bench-peers links
  Google Benchmark; the stress programs do not use it).
*/
double medianNsPerBatch(const std::function<void()> &batch, int nInstances, int repetitions, double minSeconds);

/*!
  Median time per call (thread CPU time), in nanoseconds, of \e call(i) for i in [0, nInstances): one batch runs every
  instance once (so that the branch predictor cannot learn a single input); Google Benchmark repeats the
  batch (after its own warm-up) \e repetitions times for about \e minSeconds in all, and the median batch
  time divided by the batch size is returned. The median resists the occasional preemption by the
  other processes of a shared machine.
*/
template <typename Call>
double medianNsPerCall(Call &&call, int nInstances, int repetitions = 15, double minSeconds = 0.3)
{
  for (int i = 0; i < nInstances; ++i) { // warm-up: caches, lazy initialisations, page faults
    call(i);
  }
  return medianNsPerBatch(
      [&call, nInstances]() {
        for (int i = 0; i < nInstances; ++i) {
          call(i);
        }
      },
      nInstances, repetitions, minSeconds);
}

/*!
  CPU time of the calling thread, nanoseconds (a monotonic wall clock where the system has no per-thread
  clock). Defined in benchmark/peers/benchTimer.cpp.
*/
double threadCpuNs();

//! A ratio of two times measured in interleaved rounds: the median over the rounds and its quartiles.
struct RatioRounds
{
  double median = -1.0, lowQuartile = -1.0, highQuartile = -1.0; //!< negative when not measured
  int rounds = 0;
};

/*!
  Ratio of the time of \e ours() to that of \e peer(), measured in \e rounds rounds that each time one call of
  \e peer() and \e oursRepeat calls of \e ours() back to back (thread CPU time; which of the two comes first
  alternates from round to round), the median of the rounds' ratios and its quartiles. A load on the shared
  machine that lasts seconds then slows both sides of a ratio alike, where two medians taken seconds apart
  (Google Benchmark's, as in the tables) each see their own share of it. \e oursRepeat makes both sides of a
  round last about as long. Each side runs once untimed before it is timed in a round: the caches hold what
  it reads, as when Google Benchmark repeats one function (the other side would otherwise have evicted it,
  which costs a memory-bound function that reads a few of the frame's pixels more than one that streams
  through all of them).
*/
template <typename Ours, typename Peer>
RatioRounds interleavedRatio(Ours &&ours, Peer &&peer, int rounds, int oursRepeat)
{
  std::vector<double> ratios;
  ratios.reserve(static_cast<size_t>(rounds));
  const int repeat = std::max(1, oursRepeat);
  const auto run = [&ours, &peer](bool oursSide, int times) {
    for (int k = 0; k < times; ++k)
      oursSide ? ours() : peer();
  };
  for (int r = 0; r < rounds; ++r) {
    double oursNs = 0.0, peerNs = 0.0;
    for (int side = 0; side < 2; ++side) {
      const bool oursNow = (side == 0) == (r % 2 == 0);
      run(oursNow, 1); // untimed: the caches warmed (see above)
      const double start = threadCpuNs();
      run(oursNow, oursNow ? repeat : 1);
      (oursNow ? oursNs : peerNs) = threadCpuNs() - start;
    }
    if (peerNs > 0.0)
      ratios.push_back(oursNs / repeat / peerNs);
  }
  RatioRounds result;
  result.rounds = static_cast<int>(ratios.size());
  if (ratios.empty())
    return result;
  std::sort(ratios.begin(), ratios.end());
  const auto at = [&ratios](double q) { return ratios[static_cast<size_t>(std::lround(q * (ratios.size() - 1)))]; };
  result.median = at(0.5);
  result.lowQuartile = at(0.25);
  result.highQuartile = at(0.75);
  return result;
}

//! Human-readable duration from nanoseconds ("85 ns", "17.3 us", "1.21 ms").
inline std::string formatNs(double ns)
{
  char buf[64];
  if (ns < 1e3) {
    std::snprintf(buf, sizeof(buf), "%.0f ns", ns);
  } else if (ns < 1e6) {
    std::snprintf(buf, sizeof(buf), "%.3g us", ns * 1e-3);
  } else {
    std::snprintf(buf, sizeof(buf), "%.3g ms", ns * 1e-6);
  }
  return buf;
}

//! Uniformly distributed rotation (normalised Gaussian quaternion).
template <typename Rng> Eigen::Matrix3d randomRotation(Rng &rng)
{
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  q.normalize();
  return q.toRotationMatrix();
}

//! Uniformly distributed unit vector.
template <typename Rng> Eigen::Vector3d randomUnitVector(Rng &rng)
{
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d v(gauss(rng), gauss(rng), gauss(rng));
  while (v.norm() < 1e-3) {
    v = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  }
  return v.normalized();
}

//! Angle (rad) of the rotation R1^T R2, robust near 0.
inline double rotationAngleBetween(const Eigen::Matrix3d &R1, const Eigen::Matrix3d &R2)
{
  const Eigen::Matrix3d D = R1.transpose() * R2;
  const Eigen::Vector3d axisSin(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * axisSin.norm(), 0.5 * (D.trace() - 1.0));
}

} // namespace vspBench

#endif
