/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchFilterPeers.cpp
  \brief vpLaserConicFilter beside the per-frame estimator: one IMU propagation, one frame update (30 ms
  late: update at the exposure time and re-propagation of the newer samples), one GP-3 frame, and the
  heap allocations of the filter per sample, counted by the replaceable global operator new of this program.
*/
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "benchTable.h"
#include "vspBenchUtils.h"

#ifdef VSP_HAVE_LASER_CONIC
#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpLaserConicFilter.h>
#include <visp3/laser_conic/vpLaserConicImuSimulator.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>
#endif

namespace
{
std::atomic<long> g_allocations(0);
}

// Every allocation of the program goes through these: the count around a loop of filter calls is the
// number of heap allocations those calls made.
void *operator new(std::size_t size)
{
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void *p = std::malloc(size ? size : 1))
    return p;
  throw std::bad_alloc();
}
void *operator new[](std::size_t size) { return operator new(size); }
void operator delete(void *p) noexcept { std::free(p); }
void operator delete[](void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }
void operator delete[](void *p, std::size_t) noexcept { std::free(p); }

#ifdef VSP_HAVE_LASER_CONIC
namespace
{
const double kDt = 1.0 / 200.0;

//! IMU readings of a camera at rest looking down (seeded noise), precomputed.
struct ImuStream
{
  std::vector<double> gyro, acc;
  explicit ImuStream(int n, unsigned int seed) : gyro(3 * n), acc(3 * n)
  {
    vpLaserConicImuSimulator imu;
    imu.setSeed(seed);
    for (int i = 0; i < n; ++i) {
      const double w[3] = {0.0, 0.0, 0.0}; // at rest: every frame below agrees with the prediction
      const double f[3] = {0.0, 0.0, -9.80665};
      imu.measure(kDt, w, f, &gyro[3 * i], &acc[3 * i]);
    }
  }
};

//! A filter initialised and tracking, with its stream at sample \e next.
struct RunningFilter
{
  vpLaserConicFilter filter;
  vpMatrix cov = vpMatrix(3, 3);
  int next = 0;
  double t = 0.0, frameT = 0.0;
  RunningFilter(const ImuStream &s)
  {
    cov.eye();
    cov[0][0] = 1e-6;
    cov[1][1] = cov[2][2] = 1e-6;
    for (int i = 0; i < 400; ++i)
      step(s);
  }
  void imu(const ImuStream &s)
  {
    const int i = next++ % static_cast<int>(s.gyro.size() / 3);
    filter.addImu(t, &s.gyro[3 * i], &s.acc[3 * i]);
    t += kDt;
  }
  //! Seven IMU samples (35 ms), then the frame exposed 30 ms before the last one.
  void step(const ImuStream &s)
  {
    for (int k = 0; k < 7; ++k)
      imu(s);
    frameT = t - kDt - 0.03;
    filter.addFrame(frameT, 1.0, 0.0, 0.0, cov);
  }
};

//! Median time of one GP-3 frame (120 and 1000 trace points, 0.5 px noise) with its covariance.
double gp3FrameNs(unsigned int points, unsigned int seed, bool quick)
{
  vpLaserConicSimulator sim;
  const vpCameraParameters cam(800, 800, 800, 600);
  const vpHomogeneousMatrix cMl(0.1, 0.02, 0, 0, vpMath::rad(3), 0);
  sim.setCamera(cam, 1600, 1200);
  sim.setLaser(vpMath::rad(34), cMl);
  sim.setSeed(seed);
  sim.setGroundPose(vpHomogeneousMatrix(0, 0, 1.0, vpMath::rad(8), vpMath::rad(-5), 0));
  std::vector<std::vector<vpImagePoint> > frames;
  for (int i = 0; i < (quick ? 8 : 32); ++i)
    frames.push_back(sim.addNoise(sim.tracePoints(points), 0.5));
  vpLaserConicPose pose;
  pose.setCameraParameters(cam);
  pose.setLaser(vpMath::rad(34), cMl);
  pose.setCovarianceComputation(true);
  pose.setRansacThreshold(1.5);
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpPlane plane;
        pose.computePlane(frames[i], vpLaserConicPose::GP3, plane);
        vspBench::consume(pose.getAltitude());
      },
      static_cast<int>(frames.size()), quick ? 5 : 15, quick ? 0.1 : 0.3);
}
} // namespace

void runFilterBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick)
{
  const ImuStream stream(4096, seed);
  const int reps = quick ? 5 : 15;
  const double minSeconds = quick ? 0.1 : 0.3;

  RunningFilter a(stream);
  const double propagate = vspBench::medianNsPerCall([&](int) { a.imu(stream); }, 1000, reps, minSeconds);
  RunningFilter b(stream), c(stream);
  const double cycle = vspBench::medianNsPerCall([&](int) { b.step(stream); }, 200, reps, minSeconds);
  const double imuOnly = vspBench::medianNsPerCall(
      [&](int) {
        for (int k = 0; k < 7; ++k)
          c.imu(stream);
      },
      200, reps, minSeconds);
  const double update = cycle - imuOnly;

  RunningFilter d(stream);
  const long before = g_allocations.load();
  const int cycles = 2000;
  int accepted = 0;
  for (int i = 0; i < cycles; ++i) {
    d.step(stream);
    accepted += d.filter.getLastFrameStatus() == vpLaserConicFilter::FRAME_ACCEPTED;
  }
  const double perSample = double(g_allocations.load() - before) / (8.0 * cycles);

  const double gp3Small = gp3FrameNs(120, seed, quick), gp3Large = gp3FrameNs(1000, seed, quick);

  BenchTable table;
  table.title = "Circular laser in flight: IMU-rate filter beside the per-frame estimator";
  table.note = "vpLaserConicFilter (10 states) at 200 Hz; a frame update is the update at the exposure time 30 ms "
               "back plus the re-propagation of the 6 newer IMU samples (timed as 7 samples + 1 frame minus 7 "
               "samples). Heap allocations per filter call: " +
               std::to_string(perSample) + " (counted by the program's operator new over " +
               std::to_string(8 * cycles) + " calls); " + std::to_string(accepted) + " of " + std::to_string(cycles) +
               " frames accepted.";
  table.ratioHeader = "Ratio to one IMU propagation";
  table.rows.push_back(benchRow("IMU sample", "ours vpLaserConicFilter::addImu", propagate, propagate, true));
  table.rows.push_back(benchRow("frame, 30 ms late", "ours vpLaserConicFilter::addFrame", update, propagate, true));
  table.rows.push_back(
      benchRow("frame, 120 trace points", "ours vpLaserConicPose GP3 + covariance", gp3Small, propagate, true));
  table.rows.push_back(
      benchRow("frame, 1000 trace points", "ours vpLaserConicPose GP3 + covariance", gp3Large, propagate, true));
  tables.push_back(table);
  targets.filterPropagate = propagate;
  targets.filterUpdate = update;
  targets.filterAllocationsPerSample = perSample;
}
#else
void runFilterBenchmarks(std::vector<BenchTable> &, BenchTargets &, unsigned int, bool) {}
#endif
