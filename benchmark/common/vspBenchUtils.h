/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file vspBenchUtils.h
  \brief Small helpers shared by the benchmark and stress programs: a median-of-batches timer, a
  sink that keeps results alive, seeded random rotations and a tiny command-line reader.
*/
#ifndef VSP_BENCH_UTILS_H
#define VSP_BENCH_UTILS_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <time.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vspBench
{
/*!
  Accumulates a value computed from every result so that the optimiser cannot drop the timed call.
  The global is volatile: a store to it is an observable side effect.
*/
inline volatile double g_sink = 0.0;
inline void consume(double v) { g_sink = g_sink + v; }

/*!
  CPU time of the calling thread, in seconds. The benchmarks use it rather than the wall clock:
  on a shared machine the wall clock also counts the time the thread waits for a core, the thread
  CPU time does not (cache pollution by the other processes remains, hence the median).
*/
inline double threadCpuSeconds()
{
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/*!
  Median time per call (thread CPU time), in nanoseconds, of \e call(i) for i in [0, nInstances): one batch runs every
  instance once (so that the branch predictor cannot learn a single input), the batch is repeated
  until it has run \e repetitions times and at least \e minSeconds in total, and the median batch
  time divided by the batch size is returned. The median resists the occasional preemption by the
  other processes of a shared machine.
*/
template <typename Call> double medianNsPerCall(Call &&call, int nInstances, int repetitions = 15, double minSeconds = 0.3)
{
  for (int i = 0; i < nInstances; ++i) { // warm-up: caches, lazy initialisations, page faults
    call(i);
  }
  std::vector<double> perCall;
  double total = 0.0;
  while (static_cast<int>(perCall.size()) < repetitions || (total < minSeconds && perCall.size() < 10000)) {
    const double start = threadCpuSeconds();
    for (int i = 0; i < nInstances; ++i) {
      call(i);
    }
    const double seconds = threadCpuSeconds() - start;
    total += seconds;
    perCall.push_back(seconds * 1e9 / nInstances);
  }
  std::nth_element(perCall.begin(), perCall.begin() + perCall.size() / 2, perCall.end());
  return perCall[perCall.size() / 2];
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

//! Minimal "--name value" reader: the value after \e name, or \e fallback when absent.
inline std::string argValue(int argc, char **argv, const char *name, const std::string &fallback)
{
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) {
      return argv[i + 1];
    }
  }
  return fallback;
}

//! True when the flag \e name is on the command line.
inline bool hasFlag(int argc, char **argv, const char *name)
{
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) {
      return true;
    }
  }
  return false;
}
} // namespace vspBench

#endif
