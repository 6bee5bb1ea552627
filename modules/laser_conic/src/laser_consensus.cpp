/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The consensus sets of vpLaserConicPose's methods (laser_consensus.h).
#include "laser_consensus.h"

namespace vsp::laser_consensus
{
namespace
{
using vsp::laser_estimators::PointList;

/*!
  vpRansacLoop() followed by a final refit of the best model on all its inliers (refineFinal()). The
  loop only keeps a local refit when it scores better on the truncated Sampson cost, which a
  least-squares fit need not do even when it is closer to the truth under noise; the final refit is
  kept unless it loses more than a tenth of the inliers (a sign of a bad consensus). Skipped when
  \e finalRefit is false: the scale-adaptive final stage (laser_robust_fit.h) replaces it. A refit that
  gathers more inliers is refitted again on them (a few rounds): a consensus set found by a poor
  hypothesis misses points on one side of the trace, which biases a refit on that set alone.
*/
template <class Estimator>
bool ransacWithFinalRefit(const Estimator &estimator, const vpRansacOptions &options, bool finalRefit,
                          typename Estimator::Model &best, vpRansacReport &report)
{
  if (!vpRansacLoop(estimator, options, best, report))
    return false;
  if (!options.localOptimisation || !finalRefit)
    return true;
  const int kRounds = 3;
  std::vector<int> inliers;
  for (int round = 0; round < kRounds; ++round) {
    typename Estimator::Model refit = best;
    if (!estimator.refineFinal(report.inliers, refit))
      return true;
    vpRansacInliers(estimator, refit, options.threshold * options.threshold, inliers);
    const size_t before = report.inliers.size();
    if (10 * inliers.size() < 9 * before || static_cast<int>(inliers.size()) < Estimator::kSampleSize)
      return true;
    best = refit;
    report.inliers.swap(inliers);
    report.inlierCount = static_cast<int>(report.inliers.size());
    if (report.inliers.size() <= before)
      return true;
  }
  return true;
}
} // namespace

/*!
  The consensus set of \e method on the normalized points: every point for PLANE_PAIR, the RANSAC
  loop of the method's estimator otherwise (ransacWithFinalRefit(), the final refit when \e finalRefit).
*/
Consensus findConsensus(const PointList &normalized, vpLaserConicPose::vpLaserConicMethod method,
                        const vpLaserSolvers::LaserCone &cone, vpRansacOptions options, bool finalRefit)
{
  Consensus consensus;
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
  switch (method) {
  case vpLaserConicPose::PLANE_PAIR:
    for (int i = 0; i < static_cast<int>(normalized.size()); ++i)
      consensus.inliers.push_back(i);
    consensus.found = true;
    return consensus;
  case vpLaserConicPose::PP5:
    consensus.found = ransacWithFinalRefit(vsp::laser_estimators::Pp5Estimator(normalized), options, finalRefit, conic,
                                           consensus.report);
    break;
  case vpLaserConicPose::PP3: {
    vpLaserSolvers::EpipolarTangents tangents;
    if (!vpLaserSolvers::epipolarTangents(cone, tangents)) {
      consensus.cameraInsideCone = true;
      return consensus;
    }
    consensus.found = ransacWithFinalRefit(vsp::laser_estimators::Pp3Estimator(normalized, tangents), options,
                                           finalRefit, conic, consensus.report);
    break;
  }
  case vpLaserConicPose::GP3: {
    vsp::laser_estimators::PlaneModel model;
    vsp::laser_estimators::Gp3Estimator::tuneRansac(options);
    consensus.found = ransacWithFinalRefit(vsp::laser_estimators::Gp3Estimator(normalized, cone), options, finalRefit,
                                           model, consensus.report);
    consensus.startPlane = model.plane;
    break;
  }
  }
  consensus.inliers = consensus.report.inliers;
  return consensus;
}
} // namespace vsp::laser_consensus
