/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_consensus.h
  \brief The robust stage of vpLaserConicPose::computePlane() (internal header): the consensus set of each
  method's minimal-sample RANSAC (Sec. 5 of the paper), before the final fit of laser_robust_fit.h.
*/
#ifndef VP_LASER_CONSENSUS_H
#define VP_LASER_CONSENSUS_H

#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSolvers.h>
#include <visp3/robust/vpRansac.h>

#include "laser_estimators.h"

namespace vsp::laser_consensus
{
//! What the robust stage of computePlane() found: the consensus set and, for GP-3, its plane.
struct Consensus
{
  bool found = false;
  bool cameraInsideCone = false; //!< PP3 only: no epipolar tangent, no sample was drawn
  std::vector<int> inliers;
  Eigen::Vector4d startPlane = Eigen::Vector4d::Zero();
  vpRansacReport report;
};

/*!
  The consensus set of \e method on the normalized points: every point for PLANE_PAIR, the RANSAC
  loop of the method's estimator otherwise (ransacWithFinalRefit(), the final refit when \e finalRefit).
*/
Consensus findConsensus(const vsp::laser_estimators::PointList &normalized, vpLaserConicPose::vpLaserConicMethod method,
                        const vpLaserSolvers::LaserCone &cone, vpRansacOptions options, bool finalRefit);
} // namespace vsp::laser_consensus

#endif
