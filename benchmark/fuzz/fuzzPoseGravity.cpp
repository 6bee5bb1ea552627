/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzPoseGravity.cpp
  \brief libFuzzer target for vpPoseGravity: arbitrary gravity vectors, any number of arbitrary
  points, every method, the candidates and the refinement. Invalid input may throw a vpException;
  anything else (crash, sanitizer report, hang, a non-finite or non-rigid pose returned as success,
  another exception type) is a failure.
*/
#include <cmath>

#include <visp3/pose_gravity/vpPoseGravity.h>

#include "fuzzInput.h"

namespace
{
vpColVector consumeGravity(FuzzedDataProvider &fdp)
{
  // Mostly 3-vectors; sometimes another size, which must be refused cleanly.
  const unsigned int size = fdp.ConsumeIntegralInRange<int>(0, 15) == 0 ? fdp.ConsumeIntegralInRange<unsigned int>(0, 5)
                                                                        : 3;
  vpColVector g(size);
  for (unsigned int i = 0; i < size; ++i) {
    g[i] = vspFuzz::consumeDouble(fdp);
  }
  return g;
}

void configure(FuzzedDataProvider &fdp, vpPoseGravity &pose)
{
  if (fdp.ConsumeBool()) {
    pose.setCameraGravity(consumeGravity(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setObjectGravity(consumeGravity(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setRansacThreshold(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setRansacMaxTrials(fdp.ConsumeIntegralInRange<int>(-2, 300)); // bounded: a fuzz run must not hang on purpose
  }
  if (fdp.ConsumeBool()) {
    pose.setRansacProbability(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setRansacSeed(fdp.ConsumeIntegral<unsigned int>());
  }
  if (fdp.ConsumeBool()) {
    pose.setImageStdDev(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setGravityStdDev(vspFuzz::consumeDouble(fdp));
  }
  // The checks and robust settings (appended so that the existing corpus keeps its meaning).
  if (fdp.ConsumeBool()) {
    pose.setRansacNbInliersToReachConsensus(fdp.ConsumeIntegralInRange<unsigned int>(0, 50));
    pose.setRansacFilterFlag(fdp.ConsumeBool() ? vpPoseGravity::NO_FILTER : vpPoseGravity::PREFILTER_DEGENERATE_POINTS);
    pose.setP3PPairRule(fdp.ConsumeBool() ? vpPoseGravity::P3P_WIDEST_PAIR : vpPoseGravity::P3P_BEST_THIRD_POINT);
    pose.setCovarianceComputation(fdp.ConsumeBool());
    pose.setRefineLoss(static_cast<vpPoseGravity::vpRobustLoss>(fdp.ConsumeIntegralInRange<int>(0, 2)),
                       vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setRansacSignificance(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setConsistencyThreshold(vspFuzz::consumeDouble(fdp));
  }
  if (fdp.ConsumeBool()) {
    pose.setCameraGravityStdDev(vspFuzz::consumeDouble(fdp));
  }
}

void addPoints(FuzzedDataProvider &fdp, vpPoseGravity &pose)
{
  const int n = fdp.ConsumeIntegralInRange<int>(0, 40);
  for (int i = 0; i < n; ++i) {
    vpPoint P(vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp), vspFuzz::consumeDouble(fdp));
    P.set_x(vspFuzz::consumeDouble(fdp));
    P.set_y(vspFuzz::consumeDouble(fdp));
    pose.addPoint(P);
  }
}

void run(FuzzedDataProvider &fdp)
{
  vpPoseGravity pose;
  try {
    configure(fdp, pose);
  } catch (const vpException &) {
    // A refused setting: keep going with the defaults to reach the solvers anyway.
  }
  addPoints(fdp, pose);
  const int action = fdp.ConsumeIntegralInRange<int>(0, 4);
  if (action == 4) {
    for (const vpHomogeneousMatrix &cMo : pose.computePoseCandidates()) {
      if (!vspFuzz::isFiniteRigid(cMo)) {
        vspFuzz::fail("computePoseCandidates returned a non-finite or non-rigid pose");
      }
    }
    return;
  }
  const vpPoseGravity::vpPoseGravityMethod method =
      action == 0 ? vpPoseGravity::P3P : (action == 1 ? vpPoseGravity::LEAST_SQUARES : vpPoseGravity::RANSAC);
  vpHomogeneousMatrix cMo;
  const bool found = pose.computePose(method, cMo);
  if (found && !vspFuzz::isFiniteRigid(cMo)) {
    vspFuzz::fail("computePose returned true with a non-finite or non-rigid pose");
  }
  if (found && (action == 3 || fdp.ConsumeBool())) {
    if (pose.refinePose(cMo) && !vspFuzz::isFiniteRigid(cMo)) {
      vspFuzz::fail("refinePose returned true with a non-finite or non-rigid pose");
    }
    (void)pose.computeResidual(cMo);
  }
  if (found && pose.getStatus() == vpPoseGravity::STATUS_OK) {
    try {
      const vpMatrix C = pose.getCovarianceMatrix();
      for (unsigned int i = 0; i < C.size(); ++i)
        if (!std::isfinite(C.data[i]))
          vspFuzz::fail("getCovarianceMatrix returned a non-finite covariance");
    } catch (const vpPoseGravityException &) {
      // Not asked for, or not computable at that pose: a documented exception.
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) { return vspFuzz::runInput(data, size, run); }
