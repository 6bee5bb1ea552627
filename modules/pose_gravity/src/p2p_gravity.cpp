/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section IV of D'Alfonso et al. (P2P with known vertical) and its Lemma 1, in a formulation
  without the paper's singular frames.

  In the upright frames (see gravityGeometry.h) the projection of the two points reads
      Rz(alpha) Y_i + s = lambda_i f_i,   i = A, B,
  with f_i = wRc x_i the bearings, Y_i = wRo X_i the object points and s = wRc t. Subtracting the
  two equations removes s:  Rz(alpha) d = lambda_A f_A - lambda_B f_B,  d = Y_A - Y_B.
  So Rz(alpha) d lies in the plane of the two rays, of normal n = f_A x f_B:
      n . Rz(alpha) d = a cos(alpha) + b sin(alpha) + c = 0,
      a = n_x d_x + n_y d_y,  b = n_y d_x - n_x d_y,  c = n_z d_z,
  the paper's eq. 12 with no division by any gravity component. The depths then follow by linear
  least squares and s from either point.
*/
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "gravityGeometry.h"

namespace vpGravitySolvers
{
namespace
{
// Sine of the angle between the two rays below which the image points are taken as coincident
// (Lemma 1). Exactly aligned points projected in double precision differ by ~1e-16.
const double kCoincidentRays = 1e-10;
// |a cos + b sin + c| can exceed sqrt(a^2 + b^2) by noise only. For unit n and d the excess is
// cos(theta_n + theta_d), about the angle by which the segment misses the plane of the rays;
// 1 px noise at f = 800 over a 30 px baseline tilts that plane by ~0.03 rad, so up to 0.05 rad the
// double root (the closest admissible angle) is returned, beyond it there is no solution.
const double kMaxPlaneMismatch = 0.05;
// Below this (unit vectors) the pair does not constrain alpha: vertical segment, or both rays
// horizontal, or a vertical ray.
const double kUnobservable = 1e-10;

// Writes the pose for a given yaw when the two rays are distinct; false if a depth is not positive.
bool poseFromYaw(double alpha, const Eigen::Matrix3d &wRc, const Eigen::Matrix3d &wRo, const Eigen::Vector3d &fA,
                 const Eigen::Vector3d &fB, const Eigen::Vector3d &YA, const Eigen::Vector3d &YB, Pose &pose)
{
  const double c = std::cos(alpha), s = std::sin(alpha);
  const Eigen::Matrix3d Rz = detail::rotationZ(c, s);
  const Eigen::Vector3d D = Rz * (YA - YB);
  // Least squares on lambda_A f_A - lambda_B f_B = D (unit bearings, 2x2 normal equations).
  const double k = fA.dot(fB);
  const double det = 1.0 - k * k;
  const double pA = fA.dot(D), pB = fB.dot(D);
  const double lambdaA = (pA - k * pB) / det;
  const double lambdaB = (k * pA - pB) / det;
  if (!(lambdaA > 0.0) || !(lambdaB > 0.0))
    return false; // cheirality: one point would be behind the camera
  const Eigen::Vector3d sUp = 0.5 * ((lambdaA * fA - Rz * YA) + (lambdaB * fB - Rz * YB));
  pose.R = wRc.transpose() * Rz * wRo;
  pose.t = wRc.transpose() * sUp;
  return true;
}

// Lemma 1, both image points on one ray f (unit, upright frame).
int coincidentRays(const Eigen::Matrix3d &wRc, const Eigen::Matrix3d &wRo, const Eigen::Vector3d &xA,
                   const Eigen::Vector3d &XA, const Eigen::Vector3d &f, const Eigen::Vector3d &d,
                   std::array<Pose, 2> &poses, P2PCase &p2pCase)
{
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
  const double alpha = detail::wrapAngle(std::atan2(sigma * f.y(), sigma * f.x()) - std::atan2(d.y(), d.x()));
  Pose &pose = poses[0];
  pose.R = detail::composeRotation(wRc, alpha, wRo);
  // Depths along the camera ray u = x_A / z_A differ by mu / |u|; the nearer point gets depth 1.
  const Eigen::Vector3d u = xA / xA.z();
  const double depthGap = sigma * dn / u.norm(); // depth_A - depth_B
  const double depthA = (depthGap < 0.0) ? 1.0 : 1.0 + depthGap;
  pose.t = depthA * u - pose.R * XA;
  p2pCase = P2PCase::UniqueRotation;
  return 1;
}
} // namespace

int p2p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[2],
        const Eigen::Vector3d X[2], std::array<Pose, 2> &poses, P2PCase *p2pCase)
{
  P2PCase localCase = P2PCase::NoSolution;
  P2PCase &result = p2pCase ? *p2pCase : localCase;
  result = P2PCase::NoSolution;
  if (!detail::allFinite(gCam) || !detail::allFinite(gObj) || !detail::allFinite(x[0]) || !detail::allFinite(x[1]) ||
      !detail::allFinite(X[0]) || !detail::allFinite(X[1]) || !(x[0].z() > 0.0) || !(x[1].z() > 0.0))
    return 0;

  const Eigen::Matrix3d wRc = uprightRotation(gCam);
  const Eigen::Matrix3d wRo = uprightRotation(gObj);
  const Eigen::Vector3d fA = (wRc * x[0]).normalized();
  const Eigen::Vector3d fB = (wRc * x[1]).normalized();
  const Eigen::Vector3d YA = wRo * X[0], YB = wRo * X[1];
  const Eigen::Vector3d d = YA - YB;
  const double dn = d.norm();
  if (!(dn > 0.0))
    return 0; // identical object points

  Eigen::Vector3d n = fA.cross(fB);
  const double nn = n.norm();
  if (nn < kCoincidentRays)
    return coincidentRays(wRc, wRo, x[0], X[0], (fA + fB).normalized(), d, poses, result);

  n /= nn;
  const Eigen::Vector3d u = d / dn;
  const double a = n.x() * u.x() + n.y() * u.y();
  const double b = n.y() * u.x() - n.x() * u.y();
  const double c = n.z() * u.z();
  const double M = std::hypot(a, b);
  if (M < kUnobservable) {
    // Vertical segment, or both rays horizontal: every yaw satisfies the equation if c ~ 0 too.
    result = (std::abs(c) <= kMaxPlaneMismatch) ? P2PCase::Undetermined : P2PCase::NoSolution;
    return 0;
  }
  if (std::abs(c) - M > kMaxPlaneMismatch)
    return 0;

  // a cos(alpha) + b sin(alpha) = M cos(alpha - phi) = -c.
  const double phi = std::atan2(b, a);
  double alphas[2];
  int roots = 0;
  if (std::abs(c) >= M) {
    alphas[roots++] = phi + (c > 0.0 ? 3.14159265358979323846 : 0.0); // double root (clamped)
  } else {
    // atan2 of (sin, cos) of the half-opening keeps full accuracy near the double root.
    const double delta = std::atan2(std::sqrt((M - c) * (M + c)), -c);
    alphas[roots++] = phi - delta;
    alphas[roots++] = phi + delta;
  }
  for (int k = 0; k < roots; ++k)
    alphas[k] = detail::wrapAngle(alphas[k]);
  if (roots == 2 && alphas[1] < alphas[0])
    std::swap(alphas[0], alphas[1]);

  int count = 0;
  for (int k = 0; k < roots; ++k)
    if (poseFromYaw(alphas[k], wRc, wRo, fA, fB, YA, YB, poses[count]))
      ++count;
  result = (count > 0) ? P2PCase::TwoSolutions : P2PCase::NoSolution;
  return count;
}
} // namespace vpGravitySolvers
