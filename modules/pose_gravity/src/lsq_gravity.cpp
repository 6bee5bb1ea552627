/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Closed-form least squares on n points with known vertical, and the translation of a pose of known
  rotation.

  With P_i = R X_i + t in the camera frame and (x_i, y_i) the normalized image point, the algebraic
  residuals x_i P_z - P_x and y_i P_z - P_y are u^T P_i for u = (-1, 0, x_i) and (0, -1, y_i) (sign
  irrelevant). Written in the upright frames, u^T P_i = v^T (Rz(alpha) Y_i + s) with v = wRc u,
  Y_i = wRo X_i and s = wRc t, which is linear in z = (cos alpha, sin alpha, 1, s):
      v^T Rz Y = cos (v_x Y_x + v_y Y_y) + sin (v_y Y_x - v_x Y_y) + v_z Y_z.
  The cost z^T M z is minimised over s in closed form (Schur complement), leaving a quadratic form
  q^T Q q in q = (cos, sin, 1) to be minimised on the unit circle. Its stationary points are the
  roots of a quartic in tan(phi / 2); the minima among them are polished by Newton steps and the
  lowest kept. Each point's equations carry a weight w_i: after a first solve with unit weights,
  w_i = mean depth / depth_i turns the algebraic residual z_i (x_i - P_x / P_z) into the
  reprojection error, so that a few passes approach the maximum-likelihood cost.
*/
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Dense>

#include <visp3/robust/vpPolynomialRoots.h>

#include "gravity_geometry.h"

namespace vpGravitySolvers
{
namespace
{
// Indices of (cos, sin, 1) and of s in z = (cos, sin, s_x, s_y, s_z, 1).
const int kQ[3] = {0, 1, 5};
const int kS[3] = {2, 3, 4};

// Adds the two algebraic equations of one point to the normal matrix M (upper triangle is enough
// but the full matrix is cheap at this size).
void accumulatePoint(const Eigen::Matrix3d &wRc, const Eigen::Vector3d &x, const Eigen::Vector3d &Y, double w,
                     Eigen::Matrix<double, 6, 6> &M)
{
  const double xn = x.x() / x.z(), yn = x.y() / x.z();
  const Eigen::Vector3d v1 = w * (wRc * Eigen::Vector3d(1.0, 0.0, -xn));
  const Eigen::Vector3d v2 = w * (wRc * Eigen::Vector3d(0.0, 1.0, -yn));
  for (const Eigen::Vector3d *v : {&v1, &v2}) {
    Eigen::Matrix<double, 6, 1> row;
    row << v->x() * Y.x() + v->y() * Y.y(), v->y() * Y.x() - v->x() * Y.y(), v->x(), v->y(), v->z(), v->z() * Y.z();
    M.noalias() += row * row.transpose();
  }
}

// Cost q^T Q q at angle phi.
double circleCost(const Eigen::Matrix3d &Q, double phi)
{
  const Eigen::Vector3d q(std::cos(phi), std::sin(phi), 1.0);
  return q.dot(Q * q);
}

// First and second derivatives of q^T Q q at angle phi (Q symmetric).
void circleDerivatives(const Eigen::Matrix3d &Q, double phi, double &d1, double &d2)
{
  const double c = std::cos(phi), s = std::sin(phi);
  const double c2 = c * c - s * s, s2 = 2.0 * c * s;
  const double dQ = Q(0, 0) - Q(1, 1);
  d1 = -dQ * s2 + 2.0 * Q(0, 1) * c2 - 2.0 * Q(0, 2) * s + 2.0 * Q(1, 2) * c;
  d2 = -2.0 * dQ * c2 - 4.0 * Q(0, 1) * s2 - 2.0 * Q(0, 2) * c - 2.0 * Q(1, 2) * s;
}

// Real parts of the roots of the polynomial sum_k coeffs[k] t^k (see vpPolynomialRoots()). Complex roots
// are returned too (their real part): the caller only evaluates the cost there, which cannot hide the true
// minimiser. Returns the number written.
int polynomialRootsRealPart(const double coeffs[5], double roots[4])
{
  std::complex<double> complexRoots[4];
  const int count = vpPolynomialRoots(coeffs, complexRoots);
  for (int k = 0; k < count; ++k)
    roots[k] = complexRoots[k].real();
  return count;
}

// Everything needed to score a candidate yaw: the reduced cost and the points in front of the camera.
struct Problem
{
  const Eigen::Matrix3d &wRc, &wRo;
  const Eigen::Vector3d *x, *X;
  int n;
  Eigen::Vector3d centroid; // object points are centred on it (better conditioning, same yaw)
  Eigen::Matrix3d MssInv, Mqs;
};

// Translation (upright camera frame) minimising the algebraic cost for a given yaw.
Eigen::Vector3d translationForYaw(const Problem &p, double alpha)
{
  const Eigen::Vector3d q(std::cos(alpha), std::sin(alpha), 1.0);
  return -p.MssInv * p.Mqs.transpose() * q;
}

// Sum of squared reprojection errors of the pose of a yaw and its best translation (infinite when
// a point is behind the camera).
double reprojectionCostForYaw(const Problem &p, double alpha)
{
  const Eigen::Matrix3d Rz = detail::rotationZ(std::cos(alpha), std::sin(alpha));
  const Eigen::Vector3d s = translationForYaw(p, alpha);
  double cost = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const Eigen::Vector3d P = p.wRc.transpose() * (Rz * (p.wRo * (p.X[i] - p.centroid)) + s);
    if (!(P.z() > 0.0))
      return std::numeric_limits<double>::infinity();
    const double ex = P.x() / P.z() - p.x[i].x() / p.x[i].z(), ey = P.y() / P.z() - p.x[i].y() / p.x[i].z();
    cost += ex * ex + ey * ey;
  }
  return cost;
}

// Yaw of the best minimum of q^T Q q on the unit circle, q = (cos, sin, 1): among its minima, the
// one whose pose reprojects the points best.
double minimiseOnCircle(const Eigen::Matrix3d &Qin, const Problem &problem)
{
  // Reference angle: the unconstrained minimiser over (c, s). For exact data it is the solution,
  // so after rotating by it the sought root of the half-angle quartic is near 0, far from the
  // point at infinity (phi = pi) where tan(phi / 2) loses accuracy.
  double theta0 = 0.0;
  const Eigen::Matrix2d H = Qin.topLeftCorner<2, 2>();
  const double detH = H.determinant();
  if (std::abs(detH) > 1e-12 * H.squaredNorm()) {
    const Eigen::Vector2d cs = -H.inverse() * Qin.topRightCorner<2, 1>();
    theta0 = std::atan2(cs.y(), cs.x());
  }
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T.topLeftCorner<2, 2>() << std::cos(theta0), -std::sin(theta0), std::sin(theta0), std::cos(theta0);
  const Eigen::Matrix3d Q = T.transpose() * Qin * T;

  // d cost / d phi = 0  <=>  (Q00 - Q11) c s + Q01 (s^2 - c^2) + Q02 s - Q12 c = 0, with
  // c = (1 - t^2) / (1 + t^2), s = 2 t / (1 + t^2), multiplied by (1 + t^2)^2.
  const double dQ = Q(0, 0) - Q(1, 1);
  const double coeffs[5] = {-Q(0, 1) - Q(1, 2), 2.0 * dQ + 2.0 * Q(0, 2), 6.0 * Q(0, 1), -2.0 * dQ + 2.0 * Q(0, 2),
                            Q(1, 2) - Q(0, 1)};
  double phis[5];
  int count = polynomialRootsRealPart(coeffs, phis);
  for (int k = 0; k < count; ++k)
    phis[k] = 2.0 * std::atan(phis[k]);
  phis[count++] = 3.14159265358979323846; // the stationary point lost by the half-angle substitution, if it is one

  // Scale of the cost's curvature: second derivatives below it (relative) are taken as flat.
  const double curvatureScale = Q.norm();
  double phiMin[5], costMin[5];
  int minima = 0;
  for (int k = 0; k < count; ++k) {
    // Newton polishing: the roots of vpPolynomialRoots() (or the real part of a nearly real pair) are
    // close to the stationary point; a few steps make it exact. Maxima and inflections are skipped.
    double phi = phis[k], d1 = 0.0, d2 = 0.0;
    for (int it = 0; it < 20; ++it) {
      circleDerivatives(Q, phi, d1, d2);
      if (!(d2 > 1e-12 * curvatureScale))
        break;
      const double delta = d1 / d2;
      phi -= delta;
      if (std::abs(delta) < 1e-14) // quadratic convergence: usually 1 to 3 steps
        break;
    }
    circleDerivatives(Q, phi, d1, d2);
    if (!(d2 > 1e-12 * curvatureScale))
      continue;
    phiMin[minima] = phi;
    costMin[minima++] = circleCost(Q, phi);
  }
  if (minima == 0)
    return theta0; // a constant cost (unobservable yaw) is rejected by the caller before
  // The minima are ranked by the cost that matters, the sum of squared reprojection errors
  // (infinite with a point behind the camera): the algebraic cost weighs each point by its squared
  // depth, so that with an outlier its lowest minimum can be a pose squeezed towards the camera or
  // behind it. Without any minimum in front, the lowest algebraic cost.
  int best = static_cast<int>(std::min_element(costMin, costMin + minima) - costMin);
  double bestCost = std::numeric_limits<double>::infinity();
  for (int k = 0; k < minima; ++k) {
    const double cost = reprojectionCostForYaw(problem, detail::wrapAngle(theta0 + phiMin[k]));
    if (cost < bestCost) {
      bestCost = cost;
      best = k;
    }
  }
  return detail::wrapAngle(theta0 + phiMin[best]);
}
} // namespace

namespace
{
// Sum of squared reprojection errors in normalized coordinates (infinite with a point behind the camera).
double reprojectionCost(const Pose &pose, const Eigen::Vector3d *x, const Eigen::Vector3d *X, int n)
{
  double cost = 0.0;
  for (int i = 0; i < n; ++i)
    cost += detail::reprojectionError2(pose, x[i], X[i]);
  return cost;
}

// One weighted solve: the global minimum of the weighted algebraic cost (see minimiseOnCircle()).
// Unit weights without a previous estimate; otherwise w_i = meanDepth / depth_i of *previous (all
// depths positive, checked by the caller): the weights are recomputed here so that nothing allocates.
bool solveWeighted(const Eigen::Matrix3d &wRc, const Eigen::Matrix3d &wRo, const Eigen::Vector3d *x,
                   const Eigen::Vector3d *X, int n, const Eigen::Vector3d &centroid, const Pose *previous,
                   double meanDepth, Pose &pose)
{
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < n; ++i) {
    const double w = previous ? meanDepth / (previous->R.row(2).dot(X[i]) + previous->t.z()) : 1.0;
    accumulatePoint(wRc, x[i], wRo * (X[i] - centroid), w, M);
  }

  Eigen::Matrix3d Mqq, Mqs, Mss;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      Mqq(r, c) = M(kQ[r], kQ[c]);
      Mqs(r, c) = M(kQ[r], kS[c]);
      Mss(r, c) = M(kS[r], kS[c]);
    }
  // Mss = sum v v^T spans the planes orthogonal to the rays: invertible iff two rays differ.
  Eigen::Matrix3d MssInv;
  bool invertible = false;
  const double traceScale = Mss.trace() / 3.0;
  Mss.computeInverseWithCheck(MssInv, invertible, 1e-14 * traceScale * traceScale * traceScale);
  if (!invertible || !(traceScale > 0.0))
    return false;
  const Eigen::Matrix3d Q = Mqq - Mqs * MssInv * Mqs.transpose();

  // The yaw is observable only if the reduced cost depends on (cos, sin): it does not when all the
  // points lie on one vertical line (the data then only repeat the IMUs). Exact data give a
  // dependence at rounding level there, any observable geometry a dependence of order trace(Mqq).
  const double yawDependence = Q.topLeftCorner<2, 2>().norm() + Q.topRightCorner<2, 1>().norm();
  if (!(yawDependence > 1e-10 * Mqq.trace()))
    return false;

  const Problem problem{wRc, wRo, x, X, n, centroid, MssInv, Mqs};
  const double alpha = minimiseOnCircle(0.5 * (Q + Q.transpose()), problem);
  const Eigen::Vector3d sUp = translationForYaw(problem, alpha);
  pose.R = detail::composeRotation(wRc, alpha, wRo);
  pose.t = wRc.transpose() * sUp - pose.R * centroid;
  return pose.R.allFinite() && pose.t.allFinite();
}
} // namespace

bool leastSquares(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                  const Eigen::Vector3d *X, int n, Pose &pose, int reweightingPasses)
{
  if (n < 2 || !detail::unitGravities(gCam, gObj))
    return false;
  const Eigen::Matrix3d wRc = uprightRotation(gCam);
  const Eigen::Matrix3d wRo = uprightRotation(gObj);
  // Centring the object points only shifts t (by R * centroid) but keeps the normal matrix free of
  // a large common offset, which would otherwise swamp the yaw-dependent terms.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    if (!(x[i].z() > 0.0) || !detail::allFinite(x[i]) || !detail::allFinite(X[i]))
      return false;
    centroid += X[i];
  }
  centroid /= n;
  Pose current;
  if (!solveWeighted(wRc, wRo, x, X, n, centroid, nullptr, 1.0, current))
    return false;
  for (int pass = 0; pass < reweightingPasses; ++pass) {
    // Inverse depths of the current estimate, relative to their mean (a scale-free weighting).
    double mean = 0.0;
    bool inFront = true;
    for (int i = 0; i < n; ++i) {
      const double depth = current.R.row(2).dot(X[i]) + current.t.z();
      inFront = inFront && (depth > 0.0);
      mean += depth / n;
    }
    // A pass is kept only if it lowers the sum of squared reprojection errors (the cost it
    // approaches): with an outlier, inverse-depth weights can otherwise run away.
    // A pass that gains less than 0.1 % leaves nothing for the next one.
    Pose next;
    if (!inFront || !solveWeighted(wRc, wRo, x, X, n, centroid, &current, mean, next))
      break;
    const double before = reprojectionCost(current, x, X, n), after = reprojectionCost(next, x, X, n);
    if (!(after <= before))
      break;
    current = next;
    if (!(after < (1.0 - 1e-3) * before))
      break;
  }
  pose = current;
  return true;
}

bool translationFromRotation(const Eigen::Matrix3d &R, const Eigen::Vector3d *x, const Eigen::Vector3d *X, int n,
                             Eigen::Vector3d &t)
{
  // Point-to-ray least squares: sum_i || (I - f_i f_i^T)(R X_i + t) ||^2 with unit bearings f_i,
  // i.e. the component of each transformed point orthogonal to its ray (the paper's eq. 14 uses
  // one of these equations per point; all of them are used here).
  if (n < 2)
    return false;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d f = x[i].normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - f * f.transpose();
    A += P;
    b -= P * (R * X[i]);
  }
  Eigen::Matrix3d Ainv;
  bool invertible = false;
  const double traceScale = A.trace() / 3.0;
  A.computeInverseWithCheck(Ainv, invertible, 1e-14 * traceScale * traceScale * traceScale);
  if (!invertible || !b.allFinite())
    return false;
  t = Ainv * b;
  return true;
}
} // namespace vpGravitySolvers
