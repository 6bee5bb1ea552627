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
