/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  The two-point yaw problem of Sec. IV (D'Alfonso et al.), written for speed: it is the inner step
  of p2p(), p3p() and of every RANSAC trial (private to the module).

  Notations of p2p_gravity.cpp: F_i = wRc x_i (upright bearings, not normalised), Y_i = wRo X_i,
  d = Y_A - Y_B, n = F_A x F_B, and the yaw equation a cos + b sin + c = 0.

  Everything the poses need is linear in (cos, sin) of the yaw:
  - cRo v = wRc^T Rz(alpha) wRo v, so with (b1, b2, g) the rows of uprightRotation() and
    v_w = wRo v:  cRo v = (cos v_x - sin v_y) b1c + (sin v_x + cos v_y) b2c + v_z gc;
  - the depths solve lambda_A F_A - lambda_B F_B = Rz d in the least-squares sense; with unnormalised
    bearings the 2x2 normal equations give nn lambda_A = bb pA - ab pB, nn lambda_B = ab pA - aa pB
    (aa = |F_A|^2, bb = |F_B|^2, ab = F_A.F_B, nn = |n|^2) where p_i = F_i . Rz d is linear;
  - the translation t = (lambda_A x_A + lambda_B x_B - cRo (X_A + X_B)) / 2 and the image of a third
    point follow.
  So the coefficients of these linear forms are computed while the one square root of the yaw
  equation is pending, the roots give (cos, sin) without trigonometry, and each root costs a few
  multiply-adds; the full rotation is built only for the poses returned. Nothing allocates, the
  common case takes no data-dependent branch, and the rare cases (Lemma 1, double root,
  unobservable yaw) are out of line in p2p_gravity.cpp.
*/
#ifndef VP_GRAVITY_PAIR_SOLVER_H
#define VP_GRAVITY_PAIR_SOLVER_H

#include <cmath>

#include <Eigen/Core>

#include <visp3/pose_gravity/vpGravitySolvers.h>

namespace vpGravitySolvers
{
namespace detail
{
// Sine of the angle between the two rays below which the image points are taken as coincident
// (Lemma 1). Exactly aligned points projected in double precision differ by ~1e-16.
constexpr double kCoincidentRays = 1e-10;
// |a cos + b sin + c| can exceed sqrt(a^2 + b^2) by noise only. For unit n and d the excess is
// cos(theta_n + theta_d), about the angle by which the segment misses the plane of the rays;
// 1 px noise at f = 800 over a 30 px baseline tilts that plane by ~0.03 rad, so up to 0.05 rad the
// double root (the closest admissible angle) is returned, beyond it there is no solution.
constexpr double kMaxPlaneMismatch = 0.05;
// Below this (unit vectors) the pair does not constrain alpha: vertical segment, or both rays
// horizontal, or a vertical ray.
constexpr double kUnobservable = 1e-10;
// Returned by solvePairYaw() when both image points are on one ray (Lemma 1, see coincidentRays()).
constexpr int kCoincidentPair = -1;

//! Horizontal axes (b1, b2) of uprightRotation(g): its first two rows (see upright_frame.cpp).
inline void uprightAxes(const Eigen::Vector3d &g, Eigen::Vector3d &b1, Eigen::Vector3d &b2)
{
  // Branch on the sign of g_z so that the denominator sign + g_z never comes close to zero.
  const double sign = std::copysign(1.0, g.z());
  const double a = -1.0 / (sign + g.z());
  const double b = g.x() * g.y() * a;
  b1 = Eigen::Vector3d(1.0 + sign * g.x() * g.x() * a, sign * b, -sign * g.x());
  b2 = Eigen::Vector3d(b, sign + g.y() * g.y() * a, -g.y());
}

//! The two upright frames of a pair of gravity vectors, and the rotation as a function of the yaw.
struct vpYawFrame
{
  Eigen::Vector3d b1c, b2c, gc; //!< rows of wRc
  Eigen::Vector3d b1o, b2o, go; //!< rows of wRo

  //! Builds the frames of the unit gravity vectors \e gCam, \e gObj.
  vpYawFrame(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj) : gc(gCam), go(gObj)
  {
    uprightAxes(gCam, b1c, b2c);
    uprightAxes(gObj, b1o, b2o);
  }
  //! wRc x: a camera vector in the upright camera frame.
  Eigen::Vector3d upCamera(const Eigen::Vector3d &x) const
  {
    return Eigen::Vector3d(b1c.dot(x), b2c.dot(x), gc.dot(x));
  }
  //! wRo X: an object vector in the upright object frame.
  Eigen::Vector3d upObject(const Eigen::Vector3d &X) const
  {
    return Eigen::Vector3d(b1o.dot(X), b2o.dot(X), go.dot(X));
  }
  //! wRc^T w: an upright camera vector back in the camera frame.
  Eigen::Vector3d toCamera(double wx, double wy, double wz) const { return wx * b1c + wy * b2c + wz * gc; }
  //! cRo = wRc^T Rz wRo for the yaw of cosine \e c and sine \e s.
  Eigen::Matrix3d rotation(double c, double s) const
  {
    Eigen::Matrix3d R;
    rotation(c, s, R);
    return R;
  }
  //! The same, written into \e R.
  void rotation(double c, double s, Eigen::Matrix3d &R) const
  {
    // Rows of Rz wRo, then the sum of three outer products, column by column (storage order).
    const Eigen::Vector3d m1 = c * b1o - s * b2o, m2 = s * b1o + c * b2o;
    for (int k = 0; k < 3; ++k)
      R.col(k) = m1[k] * b1c + m2[k] * b2c + go[k] * gc;
  }
};

//! A linear form in (cos, sin) of the yaw: f = k[0] cos + k[1] sin + k[2].
struct vpYawLinear
{
  double k[3]; //!< coefficients of cos, sin and 1
  //! Value at (c, s).
  double operator()(double c, double s) const { return k[0] * c + k[1] * s + k[2]; }
};

//! The solved yaw equation of one pair and the linear forms its poses depend on.
struct vpPairYaw
{
  int roots;            //!< 1 (double root) or 2
  double cs[2][2];      //!< (cos, sin) of the roots, by increasing yaw (the double root twice)
  vpYawLinear qA;       //!< nn times the depth of A along x_A (positive in front of the camera)
  vpYawLinear qB;       //!< nn times the depth of B along x_B
  double h;             //!< 1 / (2 nn)
  double observability; //!< sqrt(a^2 + b^2) / (|n| |d|): how much the pair constrains the yaw (0: not at all, 1: best)

  //! Translation cto of the root (c, s), given \e RS = cRo (X_A + X_B).
  Eigen::Vector3d translation(double c, double s, const Eigen::Vector3d &xA, const Eigen::Vector3d &xB,
                              const Eigen::Vector3d &RS) const
  {
    return (h * qA(c, s)) * xA + (h * qB(c, s)) * xB - 0.5 * RS;
  }
};

/*!
  Yaw roots when the common case (two distinct roots, observable yaw) does not hold: the double root
  within the noise margin, an unobservable yaw or no solution. \e a, \e b, \e c are the coefficients
  of a cos + b sin + c = 0 and \e scale2 the squared norm of n times that of d (their unit-vector
  scale). Writes the (cos, sin) of the root into \e cs[0] and returns 1, or returns 0 with \e p2pCase set.
*/
int degenerateYaw(double a, double b, double c, double scale2, double cs[2][2], P2PCase &p2pCase);

/*!
  Lemma 1 (both image points on one ray): writes the pose of the UniqueRotation case and returns 1,
  or returns 0; \e p2pCase receives the case.
*/
int coincidentRays(const vpYawFrame &frame, const Eigen::Vector3d &xA, const Eigen::Vector3d &xB,
                   const Eigen::Vector3d &XA, const Eigen::Vector3d &XB, Pose &pose, P2PCase &p2pCase);

//! True when the yaw of (c1, s1) is below the yaw of (c2, s2), yaws taken in (-pi, pi].
inline bool yawLess(double c1, double s1, double c2, double s2)
{
  // Upper half (0, pi] against lower half (-pi, 0]; inside one half the sign of sin(alpha2 - alpha1).
  const bool upper1 = s1 > 0.0 || (s1 == 0.0 && c1 < 0.0);
  const bool upper2 = s2 > 0.0 || (s2 == 0.0 && c2 < 0.0);
  return (upper1 != upper2) ? upper2 : (c1 * s2 - s1 * c2 > 0.0);
}

/*!
  Solves the yaw equation of the pair A, B given in the upright frames (\e FA, \e FB = wRc x, \e YA,
  \e YB = wRo X; finite data, bearings of positive depth, checked by the callers).
  \return the number of roots written into \e yaw (1 or 2, \e p2pCase left to the caller), 0 with
  \e p2pCase set when the pair has no usable root, or kCoincidentPair when both image points are on
  one ray (see coincidentRays()).
*/
inline int solvePairYaw(const Eigen::Vector3d &FA, const Eigen::Vector3d &FB, const Eigen::Vector3d &YA,
                        const Eigen::Vector3d &YB, vpPairYaw &yaw, P2PCase &p2pCase)
{
  const Eigen::Vector3d d = YA - YB;
  const double nx = FA.y() * FB.z() - FA.z() * FB.y();
  const double ny = FA.z() * FB.x() - FA.x() * FB.z();
  const double nz = FA.x() * FB.y() - FA.y() * FB.x();
  const double dd = d.squaredNorm(), nn = nx * nx + ny * ny + nz * nz;
  const double aa = FA.squaredNorm(), bb = FB.squaredNorm(), ab = FA.dot(FB);
  if (!(dd > 0.0)) {
    p2pCase = P2PCase::NoSolution; // identical object points
    return 0;
  }
  if (nn < kCoincidentRays * kCoincidentRays * aa * bb)
    return kCoincidentPair;

  // n . Rz(alpha) d = a cos + b sin + c (see p2p_gravity.cpp).
  const double a = nx * d.x() + ny * d.y(), b = ny * d.x() - nx * d.y(), c = nz * d.z();
  const double M2 = a * a + b * b;
  const double disc = M2 - c * c;
  int roots = 2;
  if (disc > 0.0 && M2 >= kUnobservable * kUnobservable * nn * dd) {
    // With (a, b) = M (cos phi, sin phi) the roots are phi -/+ delta, cos delta = -c / M,
    // sin delta = sqrt(disc) / M: the angle sum formulas give (cos, sin) without trigonometry.
    const double r = std::sqrt(disc), inv = 1.0 / M2;
    const double c0 = (b * r - a * c) * inv, s0 = -(b * c + a * r) * inv;
    const double c1 = -(a * c + b * r) * inv, s1 = (a * r - b * c) * inv;
    const bool swap = yawLess(c1, s1, c0, s0);
    yaw.cs[0][0] = swap ? c1 : c0;
    yaw.cs[0][1] = swap ? s1 : s0;
    yaw.cs[1][0] = swap ? c0 : c1;
    yaw.cs[1][1] = swap ? s0 : s1;
  } else {
    roots = degenerateYaw(a, b, c, nn * dd, yaw.cs, p2pCase);
    if (roots == 0)
      return 0;
    yaw.cs[1][0] = yaw.cs[0][0];
    yaw.cs[1][1] = yaw.cs[0][1];
  }
  yaw.roots = roots;
  yaw.observability = std::sqrt(M2 / (nn * dd));

  // p_i = F_i . Rz d, then the depth numerators of the normal equations (determinant -nn).
  const double pA[3] = {FA.x() * d.x() + FA.y() * d.y(), FA.y() * d.x() - FA.x() * d.y(), FA.z() * d.z()};
  const double pB[3] = {FB.x() * d.x() + FB.y() * d.y(), FB.y() * d.x() - FB.x() * d.y(), FB.z() * d.z()};
  for (int k = 0; k < 3; ++k) {
    yaw.qA.k[k] = bb * pA[k] - ab * pB[k];
    yaw.qB.k[k] = ab * pA[k] - aa * pB[k];
  }
  yaw.h = 0.5 / nn;
  return roots;
}

/*!
  P2P poses of the pair A, B (finite data, bearings of positive depth, checked by the callers): the
  contract of vpGravitySolvers::p2p() for \e poses (room for two) and \e p2pCase.
*/
inline int solvePairPoses(const vpYawFrame &frame, const Eigen::Vector3d &xA, const Eigen::Vector3d &xB,
                          const Eigen::Vector3d &XA, const Eigen::Vector3d &XB, Pose *poses, P2PCase &p2pCase)
{
  vpPairYaw yaw;
  const int roots =
      solvePairYaw(frame.upCamera(xA), frame.upCamera(xB), frame.upObject(XA), frame.upObject(XB), yaw, p2pCase);
  if (roots == kCoincidentPair)
    return coincidentRays(frame, xA, xB, XA, XB, poses[0], p2pCase);
  const Eigen::Vector3d S = XA + XB;
  int count = 0;
  for (int k = 0; k < roots; ++k) {
    // Every root is written; one that puts a point behind the camera (cheirality) does not advance
    // the count, so that the next root takes its slot.
    const double c = yaw.cs[k][0], s = yaw.cs[k][1];
    Pose &pose = poses[count];
    frame.rotation(c, s, pose.R);
    pose.t = yaw.translation(c, s, xA, xB, pose.R * S);
    count += static_cast<int>(yaw.qA(c, s) > 0.0) & static_cast<int>(yaw.qB(c, s) > 0.0); // no branch
  }
  if (roots > 0)
    p2pCase = (count > 0) ? P2PCase::TwoSolutions : P2PCase::NoSolution;
  return count;
}

//! True when all \e count vectors of \e v are finite.
inline bool allFinite(const Eigen::Vector3d *v, int count)
{
  // x - x is 0 for a finite x and NaN otherwise; one comparison for the whole sum.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i)
    sum += v[i] - v[i];
  return sum.sum() == 0.0;
}
} // namespace detail
} // namespace vpGravitySolvers

#endif
