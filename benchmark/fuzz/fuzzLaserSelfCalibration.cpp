/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzLaserSelfCalibration.cpp
  \brief libFuzzer target for vpLaserConicSelfCalibration, the field calibration from ordinary frames: arbitrary
  camera, initial laser, scale constraints and limits, then a few frames of arbitrary or clustered points (with or
  without a rough plane). A refused setting or frame may throw a vpException; anything else (crash, sanitizer
  report, hang), a success with a laser that is not a finite rigid pose or an opening angle outside (0, pi), or a
  failure without its reason, is a failure.
*/
#include <cmath>
#include <vector>

#include <visp3/core/vpPlane.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>

#include "fuzzInput.h"

namespace
{
//! Applies fuzzed settings, each on its own (vspFuzz::maybeApply()): a refused one leaves the default.
void configure(FuzzedDataProvider &fdp, vpLaserConicSelfCalibration &selfcal)
{
  vspFuzz::maybeApply(fdp, [&] {
    const double px = vspFuzz::consumeDouble(fdp), py = vspFuzz::consumeDouble(fdp);
    selfcal.setCameraParameters(vpCameraParameters(px, py, vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp)));
  });
  vspFuzz::maybeApply(fdp, [&] { selfcal.setLaser(vspFuzz::consumeDouble(fdp), vspFuzz::consumePose(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { selfcal.setApexDistance(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { selfcal.setMaxFrames(fdp.ConsumeIntegralInRange<unsigned int>(0, 50)); });
  vspFuzz::maybeApply(fdp, [&] { selfcal.setMaxAngularStdDeviation(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { selfcal.setMaxRmsPixels(vspFuzz::consumeDouble(fdp)); });
  selfcal.setApexHeld(fdp.ConsumeBool());
  selfcal.setOpeningAngleEstimation(fdp.ConsumeBool());
}

//! Points of one frame: arbitrary, or a noisy circle of arbitrary centre and radius (near a trace's shape).
std::vector<vpImagePoint> framePoints(FuzzedDataProvider &fdp)
{
  std::vector<vpImagePoint> points(fdp.ConsumeIntegralInRange<size_t>(0, 60));
  const bool ring = fdp.ConsumeBool();
  const double u0 = vspFuzz::consumeDouble(fdp), v0 = vspFuzz::consumeDouble(fdp), r = vspFuzz::consumeDouble(fdp);
  for (size_t k = 0; k < points.size(); ++k) {
    if (ring) {
      const double a = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(points.size());
      points[k].set_uv(u0 + r * std::cos(a) + fdp.ConsumeFloatingPointInRange<double>(-1.0, 1.0),
                       v0 + r * std::sin(a) + fdp.ConsumeFloatingPointInRange<double>(-1.0, 1.0));
    } else
      points[k].set_uv(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp));
  }
  return points;
}

void addFrames(FuzzedDataProvider &fdp, vpLaserConicSelfCalibration &selfcal)
{
  const int frames = fdp.ConsumeIntegralInRange<int>(0, 6);
  for (int k = 0; k < frames; ++k) {
    try {
      const std::vector<vpImagePoint> points = framePoints(fdp);
      unsigned int index = 0;
      if (fdp.ConsumeBool())
        index = selfcal.addFrame(points, vpPlane(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp),
                                                 vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp)));
      else
        index = selfcal.addFrame(points);
      if (fdp.ConsumeBool())
        selfcal.setKnownAltitude(index, vspFuzz::consumeDouble(fdp));
    } catch (const vpException &) {
      // A frame (or its altitude) refused with a clear error: the others go on.
    }
  }
}

void run(FuzzedDataProvider &fdp)
{
  vpLaserConicSelfCalibration selfcal;
  configure(fdp, selfcal);
  addFrames(fdp, selfcal);
  vpHomogeneousMatrix cMl;
  double openingAngle = 0.0;
  if (!selfcal.compute(cMl, openingAngle)) {
    if (selfcal.getStatus() == vpLaserConicSelfCalibration::STATUS_OK)
      vspFuzz::fail("compute() failed with STATUS_OK");
    if (vpLaserConicSelfCalibration::getStatusMessage(selfcal.getStatus()).empty())
      vspFuzz::fail("a failure without its reason");
    return;
  }
  if (selfcal.getStatus() != vpLaserConicSelfCalibration::STATUS_OK)
    vspFuzz::fail("compute() succeeded without STATUS_OK");
  if (!vspFuzz::isFiniteRigid(cMl))
    vspFuzz::fail("compute() succeeded with a laser pose that is not a finite rigid transformation");
  if (!(openingAngle > 0.0 && openingAngle < M_PI))
    vspFuzz::fail("compute() succeeded with an opening angle outside (0, pi)");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return vspFuzz::runInput(data, size, run); }
