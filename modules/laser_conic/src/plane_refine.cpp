/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Geometric refinement of a ground plane on image points: Levenberg-Marquardt on the signed Sampson
// distances of the points to the image of the laser trace the plane predicts, with the Jacobian in
// closed form (one pass over the points per iteration, fixed-size 3x3 normal equations).
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "laser_geometry.h"

namespace vpLaserSolvers
{
namespace
{
using internal::ConicCoefficients;

/*!
  The image conic of a plane and its derivatives along the three local coordinates of the plane:
  rotations of the normal towards the tangent vectors t1, t2, and the altitude d.
*/
struct PlaneConics
{
  Eigen::Matrix3d c;     //!< conic of the plane (not normalised: the Sampson distance is scale-free)
  Eigen::Matrix3d dc[3]; //!< derivatives of c along t1, t2 and d
};

/*!
  With G = d I + apex n^T and c = G^T M G, a change dG gives dc = dG^T M G + G^T M dG:
  dG = I for the altitude, and dG = apex t^T when the normal moves along t, where
  dc = t w^T + w t^T with w = G^T M apex.
*/
PlaneConics planeConics(const Eigen::Vector4d &plane, const Eigen::Vector3d tangents[2], const Eigen::Vector3d &apex,
                        const Eigen::Matrix3d &M)
{
  const Eigen::Matrix3d G = plane(3) * Eigen::Matrix3d::Identity() + apex * plane.head<3>().transpose();
  const Eigen::Matrix3d MG = M * G;
  PlaneConics pc;
  pc.c = G.transpose() * MG;
  pc.c = 0.5 * (pc.c + pc.c.transpose());
  const Eigen::Vector3d w = MG.transpose() * apex;
  for (int k = 0; k < 2; ++k)
    pc.dc[k] = tangents[k] * w.transpose() + w * tangents[k].transpose();
  pc.dc[2] = MG + MG.transpose();
  return pc;
}

//! Sum of squared residuals with the normal equations J^T J, J^T r of the Gauss-Newton step.
struct NormalEquations
{
  Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero(); //!< J^T J
  Eigen::Vector3d Jtr = Eigen::Vector3d::Zero(); //!< J^T r
  double cost = 0.0;                             //!< sum of squared signed Sampson distances
};

/*!
  One pass over the points. The signed Sampson distance is r = A / (2 sqrt(B)) with A = x^T c x and
  B = |(c x)_{1,2}|^2, so dr = (dA - A dB / (2 B)) / (2 sqrt(B)) with dA = x^T dc x and
  dB = 2 (c x)_{1,2} . (dc x)_{1,2}. Points where the conic has no gradient are skipped.
*/
NormalEquations accumulate(const Eigen::Vector2d *points, const double *weights, int n, const PlaneConics &pc)
{
  const ConicCoefficients c(pc.c);
  const ConicCoefficients dc[3] = {ConicCoefficients(pc.dc[0]), ConicCoefficients(pc.dc[1]),
                                   ConicCoefficients(pc.dc[2])};
  double h[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; // upper triangle of J^T J, row-wise
  double g[3] = {0.0, 0.0, 0.0};
  double cost = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = points[i](0), y = points[i](1);
    double v0, v1;
    const double A = c.apply(x, y, v0, v1);
    const double B = v0 * v0 + v1 * v1;
    if (!(B > 0.0))
      continue;
    const double invRoot = 0.5 / std::sqrt(B), ratio = A / (2.0 * B);
    double J[3];
    for (int k = 0; k < 3; ++k) {
      double w0, w1;
      const double dA = dc[k].apply(x, y, w0, w1);
      J[k] = (dA - ratio * 2.0 * (v0 * w0 + v1 * w1)) * invRoot;
    }
    const double r = A * invRoot;
    if (weights) {
      // Weighted least squares: scale the residual and its gradient by the square root of the weight.
      const double sw = std::sqrt(weights[i]);
      for (int k = 0; k < 3; ++k)
        J[k] *= sw;
      const double rw = r * sw;
      cost += rw * rw;
      h[0] += J[0] * J[0];
      h[1] += J[0] * J[1];
      h[2] += J[0] * J[2];
      h[3] += J[1] * J[1];
      h[4] += J[1] * J[2];
      h[5] += J[2] * J[2];
      for (int k = 0; k < 3; ++k)
        g[k] += J[k] * rw;
      continue;
    }
    cost += r * r;
    h[0] += J[0] * J[0];
    h[1] += J[0] * J[1];
    h[2] += J[0] * J[2];
    h[3] += J[1] * J[1];
    h[4] += J[1] * J[2];
    h[5] += J[2] * J[2];
    for (int k = 0; k < 3; ++k)
      g[k] += J[k] * r;
  }
  NormalEquations ne;
  ne.JtJ << h[0], h[1], h[2], h[1], h[3], h[4], h[2], h[4], h[5];
  ne.Jtr << g[0], g[1], g[2];
  ne.cost = cost;
  return ne;
}

//! A plane and the normal equations evaluated there, in its own tangent basis.
struct Iterate
{
  Eigen::Vector4d plane;
  Eigen::Vector3d tangents[2];
  NormalEquations ne;
};

Iterate evaluate(const Eigen::Vector4d &plane, const Eigen::Vector2d *points, const double *weights, int n,
                 const Eigen::Vector3d &apex, const Eigen::Matrix3d &M)
{
  Iterate it;
  it.plane = plane;
  it.tangents[0] = plane.head<3>().unitOrthogonal();
  it.tangents[1] = plane.head<3>().cross(it.tangents[0]);
  it.ne = accumulate(points, weights, n, planeConics(plane, it.tangents, apex, M));
  return it;
}

//! Plane moved by delta: normal retracted onto the unit sphere, altitude shifted.
Eigen::Vector4d moved(const Iterate &it, const Eigen::Vector3d &delta)
{
  const Eigen::Vector3d n = it.plane.head<3>() + delta(0) * it.tangents[0] + delta(1) * it.tangents[1];
  Eigen::Vector4d q;
  q << n.normalized(), it.plane(3) + delta(2);
  return q;
}

//! True when a step is below rounding: radians for the normal, relative for the altitude.
bool negligible(const Eigen::Vector3d &delta, double altitude)
{
  return std::abs(delta(0)) < 1e-14 && std::abs(delta(1)) < 1e-14 && std::abs(delta(2)) < 1e-14 * altitude;
}
} // namespace

bool refinePlane(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int iterations)
{
  return refinePlaneWeighted(points, nullptr, n, cone, plane, iterations);
}

bool refinePlaneWeighted(const Eigen::Vector2d *points, const double *weights, int n, const LaserCone &cone,
                         Eigen::Vector4d &plane, int iterations)
{
  if (n < 3 || points == nullptr || !plane.allFinite() || !(plane.head<3>().norm() > 0.0) || !(plane(3) > 0.0))
    return false;
  const Eigen::Matrix3d M = internal::laserConeForm(cone);
  Iterate current = evaluate(plane / plane.head<3>().norm(), points, weights, n, cone.apex, M);
  if (!std::isfinite(current.ne.cost))
    return false;
  double damping = 1e-3;
  // Each iteration is one pass over the points: a rejected step reuses the normal equations of the
  // current plane with more damping, an accepted one brings those of the new plane. The loop ends
  // when the Gauss-Newton model promises (or the last step gave) a relative decrease of the cost
  // below kTolerance, far below the statistical uncertainty of the plane for any realistic noise.
  const double kTolerance = 1e-6;
  for (int it = 0; it < iterations && current.ne.cost > 0.0; ++it) {
    Eigen::Matrix3d A = current.ne.JtJ;
    A.diagonal() *= 1.0 + damping;
    const Eigen::Vector3d delta = -A.ldlt().solve(current.ne.Jtr);
    if (!delta.allFinite() || negligible(delta, current.plane(3)))
      break;
    // Decrease of the linearised cost |r + J delta|^2.
    const double predicted = -(2.0 * delta.dot(current.ne.Jtr) + delta.dot(current.ne.JtJ * delta));
    if (predicted < kTolerance * current.ne.cost)
      break;
    const Eigen::Vector4d candidate = moved(current, delta);
    if (!(candidate(3) > 0.0)) {
      damping *= 10.0;
      continue;
    }
    const Iterate next = evaluate(candidate, points, weights, n, cone.apex, M);
    if (next.ne.cost < current.ne.cost) {
      const double gain = (current.ne.cost - next.ne.cost) / current.ne.cost;
      current = next;
      damping = std::max(1e-9, 0.1 * damping);
      if (gain < kTolerance)
        break;
    } else {
      damping *= 10.0;
    }
  }
  plane = current.plane;
  return true;
}
} // namespace vpLaserSolvers
