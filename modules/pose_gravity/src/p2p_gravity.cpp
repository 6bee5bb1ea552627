/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section IV of D'Alfonso et al. (P2P with known vertical) and its Lemma 1, in a formulation
  without the paper's singular frames.

  In the upright frames (see gravity_geometry.h) the projection of the two points reads
      Rz(alpha) Y_i + s = lambda_i f_i,   i = A, B,
  with f_i = wRc x_i the bearings, Y_i = wRo X_i the object points and s = wRc t. Subtracting the
  two equations removes s:  Rz(alpha) d = lambda_A f_A - lambda_B f_B,  d = Y_A - Y_B.
  So Rz(alpha) d lies in the plane of the two rays, of normal n = f_A x f_B:
      n . Rz(alpha) d = a cos(alpha) + b sin(alpha) + c = 0,
      a = n_x d_x + n_y d_y,  b = n_y d_x - n_x d_y,  c = n_z d_z,
  the paper's eq. 12 with no division by any gravity component. The depths then follow by linear
  least squares and s from either point.

  The common case is inline in gravity_pair_solver.h; this file holds the public entry point and the
  rare cases of the yaw equation.
*/
#include <cmath>

#include "gravity_geometry.h"
#include "gravity_pair_solver.h"

namespace vpGravitySolvers
{
namespace detail
{
int degenerateYaw(double a, double b, double c, double scale2, double cs[2][2], P2PCase &p2pCase)
{
  const double scale = std::sqrt(scale2); // |n| |d|: the coefficients of unit vectors are a / scale, ...
  const double M = std::hypot(a, b);
  if (M < kUnobservable * scale) {
    // Vertical segment, or both rays horizontal: every yaw satisfies the equation if c ~ 0 too.
    p2pCase = (std::abs(c) <= kMaxPlaneMismatch * scale) ? P2PCase::Undetermined : P2PCase::NoSolution;
    return 0;
  }
  if (std::abs(c) - M > kMaxPlaneMismatch * scale) {
    p2pCase = P2PCase::NoSolution;
    return 0;
  }
  // a cos(alpha) + b sin(alpha) = M cos(alpha - phi) = -c with |c| >= M up to rounding: the double
  // root alpha = phi, or phi + pi when c > 0 (the closest admissible angle).
  const double sign = (c > 0.0) ? -1.0 : 1.0;
  cs[0][0] = sign * a / M;
  cs[0][1] = sign * b / M;
  return 1;
}

int coincidentRays(const vpYawFrame &frame, const Eigen::Vector3d &xA, const Eigen::Vector3d &xB,
                   const Eigen::Vector3d &XA, const Eigen::Vector3d &XB, Pose &pose, P2PCase &p2pCase)
{
  // The common ray f and the segment d in the upright frames.
  const Eigen::Vector3d f = frame.upCamera((xA.normalized() + xB.normalized()).normalized());
  const Eigen::Vector3d d = frame.upObject(XA - XB);
  const double dn = d.norm();
  const double fh = std::hypot(f.x(), f.y());
  const double dh = std::hypot(d.x(), d.y()) / dn;
  if (fh < kUnobservable) {
    // Vertical ray: the data only repeat the IMUs. Consistent only if the segment is vertical too.
    p2pCase = (dh < kMaxPlaneMismatch) ? P2PCase::Undetermined : P2PCase::NoSolution;
    return 0;
  }
  // Rz(alpha) d = mu f with |mu| = |d|: the segment must have the elevation of the ray, up to sign.
  const double dz = d.z() / dn;
  if (std::abs(std::abs(dz) - std::abs(f.z())) > kMaxPlaneMismatch || dh < kUnobservable) {
    p2pCase = P2PCase::NoSolution;
    return 0;
  }
  // The sign of mu = lambda_A - lambda_B follows from the vertical components when they are
  // measurable; for a horizontal ray it is not observable and point A is taken as the nearer one
  // (the one that is visible when both lie on the same ray).
  const double sigma = (std::abs(dz * f.z()) > 1e-12) ? std::copysign(1.0, dz * f.z()) : -1.0;
  const double alpha = std::atan2(sigma * f.y(), sigma * f.x()) - std::atan2(d.y(), d.x());
  pose.R = frame.rotation(std::cos(alpha), std::sin(alpha));
  // Depths along the camera ray u = x_A / z_A differ by mu / |u|; the nearer point gets depth 1.
  const Eigen::Vector3d u = xA / xA.z();
  const double depthGap = sigma * dn / u.norm(); // depth_A - depth_B
  const double depthA = (depthGap < 0.0) ? 1.0 : 1.0 + depthGap;
  pose.t = depthA * u - pose.R * XA;
  p2pCase = P2PCase::UniqueRotation;
  return 1;
}
} // namespace detail

int p2p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[2],
        const Eigen::Vector3d X[2], std::array<Pose, 2> &poses, P2PCase *p2pCase)
{
  P2PCase localCase = P2PCase::NoSolution;
  P2PCase &result = p2pCase ? *p2pCase : localCase;
  result = P2PCase::NoSolution;
  if (!detail::unitGravities(gCam, gObj) || !detail::allFinite(x, 2) || !detail::allFinite(X, 2) || !(x[0].z() > 0.0) ||
      !(x[1].z() > 0.0))
    return 0;

  return detail::solvePairPoses(detail::vpYawFrame(gCam, gObj), x[0], x[1], X[0], X[1], poses.data(), result);
}
} // namespace vpGravitySolvers
