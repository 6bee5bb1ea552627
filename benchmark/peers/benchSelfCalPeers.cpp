/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file benchSelfCalPeers.cpp
  \brief Rows of the peer benchmark for the laser self-calibration from ground frames and the drift
  test: vpLaserConicSelfCalibration on 20 frames of 1000 points against cv::fitEllipse on the same
  frames (the free conic fit every frame needs anyway), vpLaserConicDriftMonitor::addFrame() against one
  cv::fitEllipse.
*/
#include <vector>

#include <opencv2/imgproc.hpp>

#include "benchTable.h"
#include "vspBenchUtils.h"

#ifdef VSP_HAVE_LASER_CONIC
#include <random>

#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpLaserConicDriftMonitor.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "../../example/laser_conic/laserRigSetup.h"

namespace
{
//! \e n frames of 1000 trace points (0.5 px) at roll and pitch within +-15 degrees, altitude 0.8-1.3 m.
std::vector<std::vector<vpImagePoint> > flightFrames(unsigned int seed, unsigned int n)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> tilt(-vpMath::rad(15.0), vpMath::rad(15.0)), alt(0.8, 1.3);
  vpLaserConicSimulator sim;
  sim.setCamera(vspLaserRig::camera(), vspLaserRig::kWidth, vspLaserRig::kHeight);
  sim.setLaser(vpMath::rad(vspLaserRig::kOpeningAngleDeg), vspLaserRig::laserPose());
  sim.setSeed(seed);
  std::vector<std::vector<vpImagePoint> > frames;
  while (frames.size() < n) {
    sim.setGroundPose(vspLaserRig::groundPose(alt(rng), tilt(rng), tilt(rng)));
    std::vector<vpImagePoint> points = sim.addNoise(sim.tracePoints(1000), 0.5);
    if (points.size() >= 900)
      frames.push_back(points);
  }
  return frames;
}

std::vector<cv::Point2f> toCv(const std::vector<vpImagePoint> &points)
{
  std::vector<cv::Point2f> out;
  for (const vpImagePoint &p : points)
    out.emplace_back(static_cast<float>(p.get_u()), static_cast<float>(p.get_v()));
  return out;
}

} // namespace
#endif

void runSelfCalibrationBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick)
{
#ifdef VSP_HAVE_LASER_CONIC
  const std::vector<std::vector<vpImagePoint> > frames = flightFrames(seed, 20);
  std::vector<std::vector<cv::Point2f> > cvFrames;
  for (const std::vector<vpImagePoint> &f : frames)
    cvFrames.push_back(toCv(f));
  // The laser known to about 1 degree and 5 mm; the apex distance by a ruler.
  const vpHomogeneousMatrix guess =
      vspLaserRig::laserPose() * vpHomogeneousMatrix(0.004, -0.003, 0.0, vpMath::rad(0.7), vpMath::rad(-0.7), 0.0);
  const double apexDistance = vspLaserRig::laserPose().getTranslationVector().frobeniusNorm();
  int ok = 0, runs = 0;
  const double selfcalNs = vspBench::medianNsPerCall(
      [&](int) {
        vpLaserConicSelfCalibration selfcal;
        selfcal.setCameraParameters(vspLaserRig::camera());
        selfcal.setLaser(vpMath::rad(vspLaserRig::kOpeningAngleDeg), guess);
        selfcal.setApexDistance(apexDistance);
        for (const std::vector<vpImagePoint> &f : frames)
          selfcal.addFrame(f);
        vpHomogeneousMatrix cMl;
        double A = 0.0;
        ok += selfcal.compute(cMl, A) ? 1 : 0;
        ++runs;
        vspBench::consume(cMl[0][3]);
      },
      1, quick ? 3 : 5, quick ? 1.0 : 3.0);
  const double fitNs = vspBench::medianNsPerCall(
      [&](int) {
        for (const std::vector<cv::Point2f> &f : cvFrames)
          vspBench::consume(cv::fitEllipse(f).angle);
      },
      1, 5, 0.3);
  targets.selfCalibration20 = selfcalNs;

  vpLaserConicDriftMonitor monitor;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> rms(0.49, 0.52);
  std::vector<double> constrained(1024), freeRms(1024);
  for (size_t i = 0; i < constrained.size(); ++i) {
    freeRms[i] = rms(rng);
    constrained[i] = freeRms[i] * 1.002;
  }
  const double driftNs = vspBench::medianNsPerCall(
      [&](int i) {
        vspBench::consume(monitor.addFrame(constrained[static_cast<size_t>(i)], freeRms[static_cast<size_t>(i)], 1000));
      },
      static_cast<int>(constrained.size()), 5, 0.2);
  const double oneFitNs = fitNs / cvFrames.size();
  targets.driftPerFrame = driftNs;

  BenchTable table;
  table.title = "Laser self-calibration from ground frames";
  table.ratioHeader = "Ratio to cv::fitEllipse";
  table.note = "20 frames of 1000 trace points (0.5 px noise, roll and pitch within +-15 deg, 0.8-1.3 m), laser "
               "guess 1 deg / 5 mm off, apex distance given; one core. Ratio to 20 cv::fitEllipse (the free conic fit "
               "of the same frames). Drift test: vpLaserConicDriftMonitor::addFrame(), window of 20 frames, ratio to "
               "one cv::fitEllipse on 1000 points. Self-calibrations that succeeded: " +
               std::to_string(ok) + "/" + std::to_string(runs) + ".";
  table.rows.push_back(benchRow("self-calibration, 20 frames", "ours vpLaserConicSelfCalibration::compute", selfcalNs,
                                fitNs, true, static_cast<double>(ok) / runs));
  table.rows.push_back(benchRow("self-calibration, 20 frames", "OpenCV cv::fitEllipse x 20", fitNs, fitNs));
  table.rows.push_back(
      benchRow("drift test, one frame", "ours vpLaserConicDriftMonitor::addFrame", driftNs, oneFitNs, true));
  table.rows.push_back(benchRow("drift test, one frame", "OpenCV cv::fitEllipse (1000 points)", oneFitNs, oneFitNs));
  tables.push_back(table);
#else
  (void)tables;
  (void)targets;
  (void)seed;
  (void)quick;
#endif
}
