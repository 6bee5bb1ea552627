/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// GP-3 minimal solver (Boutteau et al., JMIV 2018, Sec. 5.3): ground planes through three
// ray/laser-cone intersections.
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <cmath>

#include <Eigen/Geometry>

#include "laser_geometry.h"

namespace vpLaserSolvers
{
namespace
{
/*!
  Points where the ray lambda (x, y, 1), lambda > 0, meets the forward nappe of the laser cone
  (eq. 57: lambda^2 c2 - 2 lambda c1 + c0 = 0). \return how many (0 to 2).
*/
int rayConeIntersections(const Eigen::Vector2d &p, const LaserCone &cone, const Eigen::Matrix3d &M,
                         Eigen::Vector3d out[2])
{
  const Eigen::Vector3d ray(p(0), p(1), 1.0);
  const Eigen::Vector3d Mr = M * ray;
  const double c2 = ray.dot(Mr), c1 = cone.apex.dot(Mr), c0 = cone.apex.dot(M * cone.apex);
  double lambdas[2];
  int nl = 0;
  if (c2 == 0.0) {
    // The ray is parallel to a generator: one finite root.
    if (c1 != 0.0)
      lambdas[nl++] = c0 / (2.0 * c1);
  } else {
    const double delta = c1 * c1 - c0 * c2;
    if (delta < 0.0)
      return 0;
    // Cancellation-free pair of roots: q = c1 + sign(c1) sqrt(delta), lambda = q / c2 and c0 / q.
    const double q = c1 + std::copysign(std::sqrt(delta), c1);
    lambdas[nl++] = q / c2;
    if (q != 0.0)
      lambdas[nl++] = c0 / q;
  }
  const Eigen::Vector3d axis = cone.cRl.col(2);
  int count = 0;
  for (int i = 0; i < nl; ++i) {
    if (!(lambdas[i] > 0.0) || !std::isfinite(lambdas[i]))
      continue;
    const Eigen::Vector3d X = lambdas[i] * ray;
    if ((X - cone.apex).dot(axis) > 0.0) // forward nappe only: the laser does not shine backwards
      out[count++] = X;
  }
  return count;
}
} // namespace

int gp3Planes(const Eigen::Vector2d points[3], const LaserCone &cone, Eigen::Vector4d planes[8])
{
  // Two nearly coincident rays leave the plane turning about the line through them, fixed by rounding.
  if (detail::nearDuplicate(points, 3, 1e-6))
    return 0;
  const Eigen::Matrix3d M = laserConeQuadric(cone).topLeftCorner<3, 3>();
  Eigen::Vector3d X[3][2];
  int nx[3];
  for (int i = 0; i < 3; ++i) {
    nx[i] = rayConeIntersections(points[i], cone, M, X[i]);
    if (nx[i] == 0)
      return 0;
  }
  int count = 0;
  for (int a = 0; a < nx[0]; ++a)
    for (int b = 0; b < nx[1]; ++b)
      for (int c = 0; c < nx[2]; ++c) {
        const Eigen::Vector3d &P0 = X[0][a], &P1 = X[1][b], &P2 = X[2][c];
        Eigen::Vector3d n = (P1 - P0).cross(P2 - P0);
        const double area = n.norm();
        const double size = (P1 - P0).norm() * (P2 - P0).norm();
        if (!(area > 1e-12 * size))
          continue; // collinear triplet
        n /= area;
        double d = -n.dot(P0);
        if (d < 0.0) {
          n = -n;
          d = -d;
        }
        // Both optical centres on the same side (camera side: d > 0), not on the plane.
        const double scale = 1e-12 * (P0.norm() + cone.apex.norm());
        if (!(d > scale) || !(n.dot(cone.apex) + d > scale))
          continue;
        planes[count++] << n, d;
      }
  return count;
}
} // namespace vpLaserSolvers
