/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzLaserFilter.cpp
  \brief libFuzzer target for vpLaserConicFilter, the IMU-rate fusion a flight loop runs: arbitrary settings,
  then a stream of IMU samples, frames and missing frames whose times mostly advance (late, early, repeated
  or arbitrary now and then) and whose values are arbitrary (NaN, infinities, huge, plausible). A refused
  setting may throw a vpException; anything else (crash, sanitizer report, hang), a sample or frame with a
  non-finite value that is taken, or an initialised filter whose state or covariance is not finite, is a
  failure.
*/
#include <cmath>

#include <visp3/laser_conic/vpLaserConicFilter.h>

#include "fuzzInput.h"

namespace
{
//! Applies fuzzed settings, each on its own (vspFuzz::maybeApply()): a refused one leaves the default.
void configure(FuzzedDataProvider &fdp, vpLaserConicFilter &filter)
{
  vspFuzz::maybeApply(fdp, [&] {
    filter.setImuNoise(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp),
                       vspFuzz::consumeDouble(fdp));
  });
  vspFuzz::maybeApply(fdp, [&] {
    filter.setInitialUncertainty(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp));
  });
  vspFuzz::maybeApply(fdp, [&] {
    filter.setImuToCameraRotation(vpRotationMatrix(vspFuzz::consumePose(fdp).getRotationMatrix()));
  });
  vspFuzz::maybeApply(fdp, [&] { filter.setGravityNorm(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] {
    filter.setMaxLatency(vspFuzz::consumeDouble(fdp), fdp.ConsumeIntegralInRange<unsigned int>(0, 300));
  });
  vspFuzz::maybeApply(fdp, [&] { filter.setMaxImuGap(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setGateProbability(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setStepFrames(fdp.ConsumeIntegralInRange<unsigned int>(0, 10)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setMinStepHeight(vspFuzz::consumeDouble(fdp)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setMaxRejections(fdp.ConsumeIntegralInRange<unsigned int>(0, 100)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setInitialisationFrames(fdp.ConsumeIntegralInRange<unsigned int>(0, 10)); });
  vspFuzz::maybeApply(fdp, [&] { filter.setPredictionTimeout(vspFuzz::consumeDouble(fdp)); });
}

//! The next time: usually a small step forward (an IMU at 100-1000 Hz, frames a few samples late), sometimes
//! the same, earlier or arbitrary.
double nextTime(FuzzedDataProvider &fdp, double t)
{
  switch (fdp.ConsumeIntegralInRange<int>(0, 7)) {
  case 0:
    return vspFuzz::consumeDouble(fdp);
  case 1:
    return t - fdp.ConsumeFloatingPointInRange<double>(0.0, 0.2);
  case 2:
    return t;
  default:
    return t + fdp.ConsumeFloatingPointInRange<double>(0.0, 0.02);
  }
}

//! A value near \e typical (a hovering drone's), or an arbitrary one.
double value(FuzzedDataProvider &fdp, double typical)
{
  return fdp.ConsumeIntegralInRange<int>(0, 3) == 0 ? vspFuzz::consumeDouble(fdp)
                                                    : typical + fdp.ConsumeFloatingPointInRange<double>(-0.5, 0.5);
}

bool allFinite(const double *v, int n)
{
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

void addImu(FuzzedDataProvider &fdp, vpLaserConicFilter &filter, double t)
{
  const double gyro[3] = {value(fdp, 0.0), value(fdp, 0.0), value(fdp, 0.0)};
  const double acc[3] = {value(fdp, 0.0), value(fdp, 0.0), value(fdp, -9.81)};
  const vpLaserConicFilter::vpImuStatus status = filter.addImu(t, gyro, acc);
  if (status == vpLaserConicFilter::IMU_OK && !(std::isfinite(t) && allFinite(gyro, 3) && allFinite(acc, 3)))
    vspFuzz::fail("addImu took a sample with a non-finite value");
}

void addFrame(FuzzedDataProvider &fdp, vpLaserConicFilter &filter, double t)
{
  const double pose[3] = {value(fdp, 1.5), value(fdp, 0.0), value(fdp, 0.0)};
  vpMatrix covariance(3, 3);
  const double sd = fdp.ConsumeBool() ? vspFuzz::consumeDouble(fdp) : 0.01;
  for (unsigned int i = 0; i < 3; ++i)
    covariance[i][i] = sd * sd;
  if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0)
    covariance[fdp.ConsumeIntegralInRange<unsigned int>(0, 2)][fdp.ConsumeIntegralInRange<unsigned int>(0, 2)] =
        vspFuzz::consumeDouble(fdp);
  const vpLaserConicFilter::vpFrameStatus status = filter.addFrame(t, pose[0], pose[1], pose[2], covariance);
  const bool taken = status == vpLaserConicFilter::FRAME_ACCEPTED || status == vpLaserConicFilter::FRAME_INITIALISED ||
                     status == vpLaserConicFilter::FRAME_GROUND_STEP;
  bool finite = std::isfinite(t) && allFinite(pose, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      finite = finite && std::isfinite(covariance[i][j]);
  if (taken && !finite)
    vspFuzz::fail("addFrame took a frame with a non-finite value");
}

//! An initialised filter's outputs: a finite state and a finite covariance with a non-negative diagonal.
void checkOutputs(const vpLaserConicFilter &filter)
{
  if (!filter.isInitialised())
    return;
  const vpColVector x = filter.getState();
  const vpMatrix P = filter.getStateCovarianceMatrix();
  for (unsigned int i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]))
      vspFuzz::fail("an initialised filter's state is not finite");
    if (!std::isfinite(P[i][i]) || P[i][i] < 0.0)
      vspFuzz::fail("an initialised filter's covariance has a diagonal entry that is not finite or negative");
  }
}

void run(FuzzedDataProvider &fdp)
{
  vpLaserConicFilter filter;
  configure(fdp, filter);
  double t = fdp.ConsumeFloatingPointInRange<double>(0.0, 100.0);
  const int events = fdp.ConsumeIntegralInRange<int>(0, 400);
  for (int k = 0; k < events && fdp.remaining_bytes() > 0; ++k) {
    const int kind = fdp.ConsumeIntegralInRange<int>(0, 15);
    const double when = nextTime(fdp, t);
    if (kind < 10) {
      addImu(fdp, filter, when);
      if (std::isfinite(when) && when > t)
        t = when;
    } else if (kind < 14)
      addFrame(fdp, filter, when - fdp.ConsumeFloatingPointInRange<double>(0.0, 0.06));
    else if (kind == 14)
      filter.addMissingFrame(when);
    else
      filter.reset();
    checkOutputs(filter);
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return vspFuzz::runInput(data, size, run); }
