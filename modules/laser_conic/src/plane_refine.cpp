/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Geometric refinement of a ground plane on image points: Levenberg-Marquardt on the signed Sampson
// distances of the points to the image of the laser trace the plane predicts.
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace vpLaserSolvers
{
namespace
{
//! Signed first-order distance (the sign tells the side of the conic).
double signedSampson(const Eigen::Matrix3d &c, const Eigen::Vector2d &p)
{
  const Eigen::Vector3d x(p(0), p(1), 1.0);
  const Eigen::Vector3d cx = c * x;
  const double gradient = 2.0 * std::hypot(cx(0), cx(1));
  return gradient > 0.0 ? x.dot(cx) / gradient : 0.0;
}

//! Plane moved by (a, b) radians on the sphere of normals (tangent basis t1, t2) and by dd in d.
Eigen::Vector4d perturbed(const Eigen::Vector4d &plane, const Eigen::Vector3d &t1, const Eigen::Vector3d &t2,
                          const Eigen::Vector3d &delta)
{
  const Eigen::Vector3d rotation = delta(0) * t1 + delta(1) * t2;
  const double angle = rotation.norm();
  Eigen::Vector3d n = plane.head<3>();
  if (angle > 0.0)
    n = Eigen::AngleAxisd(angle, rotation / angle) * n;
  Eigen::Vector4d q;
  q << n.normalized(), plane(3) + delta(2);
  return q;
}

double cost(const Eigen::Vector2d *points, int n, const LaserCone &cone, const Eigen::Vector4d &plane)
{
  const Eigen::Matrix3d c = conicFromPlane(plane, cone);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = signedSampson(c, points[i]);
    sum += r * r;
  }
  return sum;
}
} // namespace

bool refinePlane(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int iterations)
{
  if (n < 3 || !plane.allFinite() || !(plane.head<3>().norm() > 0.0) || !(plane(3) > 0.0))
    return false;
  Eigen::Vector4d current = plane / plane.head<3>().norm();
  double currentCost = cost(points, n, cone, current);
  double damping = 1e-3;
  // Central-difference steps: radians for the normal, relative for the altitude.
  const double stepAngle = 1e-6;
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector3d normal = current.head<3>();
    Eigen::Vector3d t1 = normal.unitOrthogonal();
    const Eigen::Vector3d t2 = normal.cross(t1);
    const double steps[3] = {stepAngle, stepAngle, stepAngle * current(3)};
    Eigen::Matrix3d conicsPlus[3], conicsMinus[3];
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d delta = Eigen::Vector3d::Zero();
      delta(k) = steps[k];
      conicsPlus[k] = conicFromPlane(perturbed(current, t1, t2, delta), cone);
      conicsMinus[k] = conicFromPlane(perturbed(current, t1, t2, -delta), cone);
    }
    const Eigen::Matrix3d c = conicFromPlane(current, cone);
    // Normal equations J^T J and J^T r accumulated point by point (no n x 3 matrix).
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (int i = 0; i < n; ++i) {
      Eigen::Vector3d J;
      for (int k = 0; k < 3; ++k)
        J(k) = (signedSampson(conicsPlus[k], points[i]) - signedSampson(conicsMinus[k], points[i])) / (2.0 * steps[k]);
      const double r = signedSampson(c, points[i]);
      JtJ += J * J.transpose();
      Jtr += J * r;
    }
    bool improved = false;
    for (int attempt = 0; attempt < 8 && !improved; ++attempt) {
      Eigen::Matrix3d A = JtJ;
      A.diagonal() *= 1.0 + damping;
      const Eigen::Vector3d delta = -A.ldlt().solve(Jtr);
      if (!delta.allFinite())
        return false;
      const Eigen::Vector4d candidate = perturbed(current, t1, t2, delta);
      const double candidateCost = candidate(3) > 0.0 ? cost(points, n, cone, candidate) : HUGE_VAL;
      if (candidateCost < currentCost) {
        const double gain = (currentCost - candidateCost) / currentCost;
        current = candidate;
        currentCost = candidateCost;
        damping = std::max(1e-9, damping * 0.1);
        improved = true;
        if (gain < 1e-12) {
          plane = current;
          return true;
        }
      } else {
        damping *= 10.0;
      }
    }
    if (!improved)
      break; // converged: no step lowers the cost any more
  }
  plane = current;
  return true;
}
} // namespace vpLaserSolvers
