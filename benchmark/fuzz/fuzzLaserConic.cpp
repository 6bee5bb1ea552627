/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzLaserConic.cpp
  \brief libFuzzer target for vpLaserConicPose: arbitrary camera and laser parameters, arbitrary
  point sets, every method and RANSAC setting. Invalid input may throw a vpException; anything else
  (crash, sanitizer report, hang, a non-finite plane or attitude returned as success, another
  exception type) is a failure.
*/
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "fuzzInput.h"

namespace
{
//! Applies fuzzed settings; returns whether the covariance was requested.
bool configure(FuzzedDataProvider &fdp, vpLaserConicPose &estimator)
{
  if (fdp.ConsumeIntegralInRange<int>(0, 7) != 0) {
    const double px = vspFuzz::consumeDouble(fdp), py = vspFuzz::consumeDouble(fdp);
    const double u0 = vspFuzz::consumeDouble(fdp), v0 = vspFuzz::consumeDouble(fdp);
    vpCameraParameters cam(px, py, u0, v0);
    if (fdp.ConsumeBool()) {
      const double kud = vspFuzz::consumeDouble(fdp), kdu = vspFuzz::consumeDouble(fdp);
      cam.initPersProjWithDistortion(px, py, u0, v0, kud, kdu);
    }
    estimator.setCameraParameters(cam);
  }
  if (fdp.ConsumeIntegralInRange<int>(0, 7) != 0) {
    const double openingAngle = vspFuzz::consumeDouble(fdp);
    estimator.setLaser(openingAngle, vspFuzz::consumePose(fdp));
  }
  if (fdp.ConsumeBool()) {
    estimator.setRansacThreshold(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    estimator.setRansacMaxTrials(fdp.ConsumeIntegralInRange<int>(-2, 300)); // bounded: no hang on purpose
  }
  if (fdp.ConsumeBool()) {
    estimator.setRansacProbability(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    estimator.setRansacSeed(fdp.ConsumeIntegral<unsigned int>());
  }
  if (fdp.ConsumeBool()) {
    estimator.setLocalOptimisation(fdp.ConsumeBool());
  }
  if (fdp.ConsumeBool()) {
    estimator.setScaleAdaptive(fdp.ConsumeBool());
  }
  if (fdp.ConsumeBool()) {
    estimator.setFinalFit(static_cast<vpLaserConicPose::vpLaserConicFinalFit>(fdp.ConsumeIntegralInRange<int>(0, 3)));
  }
  if (fdp.ConsumeBool()) {
    estimator.setArcCoverageThreshold(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    estimator.setRansacNbInliersToReachConsensus(fdp.ConsumeIntegralInRange<unsigned int>(0, 400));
  }
  const bool covariance = fdp.ConsumeBool();
  estimator.setCovarianceComputation(covariance);
  return covariance;
}

void run(FuzzedDataProvider &fdp)
{
  vpLaserConicPose estimator;
  bool covarianceRequested = false; // the default, kept when a setting before it is refused
  try {
    covarianceRequested = configure(fdp, estimator);
  } catch (const vpException &) {
    // A refused setting: go on, the estimator must then refuse to compute or use its defaults.
  }
  const auto method = static_cast<vpLaserConicPose::vpLaserConicMethod>(fdp.ConsumeIntegralInRange<int>(0, 3));
  std::vector<vpImagePoint> points(fdp.ConsumeIntegralInRange<size_t>(0, 300));
  // Either independent arbitrary points, or small perturbations of a base point (near-degenerate sets).
  const bool clustered = fdp.ConsumeBool();
  const double baseU = vspFuzz::consumeDouble(fdp), baseV = vspFuzz::consumeDouble(fdp);
  for (vpImagePoint &p : points) {
    if (clustered) {
      p.set_ij(baseV + fdp.ConsumeFloatingPointInRange<double>(-1.0, 1.0),
               baseU + fdp.ConsumeFloatingPointInRange<double>(-1.0, 1.0));
    } else {
      p.set_ij(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp));
    }
  }
  vpPlane plane;
  if (!estimator.computePlane(points, method, plane)) {
    return;
  }
  if (!std::isfinite(plane.getA()) || !std::isfinite(plane.getB()) || !std::isfinite(plane.getC()) ||
      !std::isfinite(plane.getD())) {
    vspFuzz::fail("computePlane returned true with a non-finite plane");
  }
  const double norm =
      std::sqrt(plane.getA() * plane.getA() + plane.getB() * plane.getB() + plane.getC() * plane.getC());
  if (!(std::abs(norm - 1.0) < 1e-6)) {
    vspFuzz::fail("computePlane returned true with a plane whose normal is not unit");
  }
  if (!std::isfinite(estimator.getAltitude()) || !std::isfinite(estimator.getRoll()) ||
      !std::isfinite(estimator.getPitch())) {
    vspFuzz::fail("computePlane returned true with a non-finite altitude or attitude");
  }
  for (unsigned int i : estimator.getRansacInlierIndex()) {
    if (i >= points.size()) {
      vspFuzz::fail("inlier index out of range");
    }
  }
  if (estimator.getStatus() != vpLaserConicPose::STATUS_OK) {
    vspFuzz::fail("computePlane returned true without STATUS_OK");
  }
  if (!covarianceRequested)
    return; // getCovarianceMatrix() then throws notComputedError (tested in testLaserConicPose)
  const vpMatrix C = estimator.getCovarianceMatrix();
  if (C.getRows() != 3 || C.getCols() != 3) {
    vspFuzz::fail("covariance of the wrong size");
  }
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      // NaN marks a covariance that could not be computed; a finite one must be symmetric.
      if (std::isfinite(C[i][j]) && std::isfinite(C[j][i]) &&
          !(std::abs(C[i][j] - C[j][i]) <= 1e-9 * (std::abs(C[i][j]) + 1e-300))) {
        vspFuzz::fail("covariance not symmetric");
      }
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return vspFuzz::runInput(data, size, run); }
