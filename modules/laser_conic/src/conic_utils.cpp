/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Small conic helpers: image of the laser trace, point-to-conic distance, ellipse test, attitude.
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "laser_geometry.h"

namespace vpLaserSolvers
{
Eigen::Matrix3d conicFromPlane(const Eigen::Vector4d &plane, const LaserCone &cone)
{
  const Eigen::Matrix3d c = detail::traceConic(plane, cone.apex, detail::laserConeForm(cone));
  const double norm = c.norm();
  return norm > 0.0 ? Eigen::Matrix3d(c / norm) : c;
}

double sampsonDistance(const Eigen::Matrix3d &c, const Eigen::Vector2d &p)
{
  const Eigen::Vector3d x(p(0), p(1), 1.0);
  const Eigen::Vector3d cx = c * x;
  const double algebraic = x.dot(cx);
  // Gradient of x^T c x with respect to the two inhomogeneous coordinates. std::hypot, which guards against
  // overflow and underflow (and was a few percent of a tracked frame), only for sums of squares out of the
  // normal range (conics scaled near the largest or smallest doubles).
  const double squared = cx(0) * cx(0) + cx(1) * cx(1);
  const bool normal = squared >= std::numeric_limits<double>::min() && squared <= std::numeric_limits<double>::max();
  const double gradient = 2.0 * (normal ? std::sqrt(squared) : std::hypot(cx(0), cx(1)));
  if (!(gradient > 0.0))
    return algebraic == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return std::abs(algebraic) / gradient;
}

bool isEllipse(const Eigen::Matrix3d &c)
{
  const Eigen::Matrix3d sym = 0.5 * (c + c.transpose());
  // The threshold is relative to the quadratic part, not to the largest coefficient: the constant term of a
  // conic in pixel coordinates grows as the square of its centre's distance to the origin (10^6 times the
  // quadratic terms at the centre of a 1600x1200 image), and a ring there is still an ellipse.
  const double scale = sym.topLeftCorner<2, 2>().cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale) || !sym.allFinite())
    return false;
  const Eigen::Matrix3d s = sym / scale;
  const double det2 = s(0, 0) * s(1, 1) - s(0, 1) * s(1, 0);
  // Definite 2x2 block: bounded conic; real and non-degenerate when det(c) has the sign opposite to c11.
  return det2 > 1e-12 && s(0, 0) * s.determinant() < 0.0;
}

void altitudeRollPitch(const Eigen::Vector4d &plane, double &altitude, double &roll, double &pitch)
{
  // Orient the normal towards the camera (d > 0) whatever the sign the caller used.
  const Eigen::Vector4d p = plane(3) < 0.0 ? Eigen::Vector4d(-plane) : plane;
  const double norm = p.head<3>().norm();
  const Eigen::Vector3d g = -p.head<3>() / norm; // downward unit normal, camera frame
  altitude = p(3) / norm;
  roll = std::atan2(-g(1), g(2));
  pitch = std::asin(std::max(-1.0, std::min(1.0, g(0))));
}
} // namespace vpLaserSolvers

namespace vpLaserSolvers
{
Eigen::Vector4d planeFromAltitudeRollPitch(double altitude, double roll, double pitch)
{
  // g = R_x(roll) R_y(pitch) e_z = (sin p, -sin r cos p, cos r cos p).
  const Eigen::Vector3d g(std::sin(pitch), -std::sin(roll) * std::cos(pitch), std::cos(roll) * std::cos(pitch));
  Eigen::Vector4d plane;
  plane << -g, altitude;
  return plane;
}
} // namespace vpLaserSolvers
