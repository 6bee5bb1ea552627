/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Cone quadrics of the laser and of the camera (Boutteau et al., JMIV 2018, eq. 6-10).
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <cmath>

#include "laser_geometry.h"

namespace vpLaserSolvers
{
namespace detail
{
Eigen::Matrix3d laserConeForm(const LaserCone &cone)
{
  const double tan2 = std::tan(cone.halfAngle) * std::tan(cone.halfAngle);
  const Eigen::Vector3d d(1.0, 1.0, -tan2);
  // R_las = cRl^T, hence R_las^T d R_las = cRl d cRl^T.
  return cone.cRl * d.asDiagonal() * cone.cRl.transpose();
}
} // namespace detail

Eigen::Matrix4d laserConeQuadric(const LaserCone &cone)
{
  const Eigen::Matrix3d M = detail::laserConeForm(cone);
  const Eigen::Vector3d Mt = M * cone.apex;
  Eigen::Matrix4d D;
  D.topLeftCorner<3, 3>() = M;
  D.topRightCorner<3, 1>() = -Mt;
  D.bottomLeftCorner<1, 3>() = -Mt.transpose();
  D(3, 3) = cone.apex.dot(Mt);
  return D;
}

Eigen::Matrix4d cameraConeQuadric(const Eigen::Matrix3d &c)
{
  // P = [I | 0]: C = P^T c P.
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  C.topLeftCorner<3, 3>() = 0.5 * (c + c.transpose());
  return C;
}
} // namespace vpLaserSolvers
