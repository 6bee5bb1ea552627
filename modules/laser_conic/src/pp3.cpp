/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// PP-3 minimal solver (Boutteau et al., JMIV 2018, Sec. 5.2): conics through three points tangent
// to the two epipolar lines that are tangent to the laser cone.
#include <visp3/laser_conic/vpLaserConicSolvers.h>
#include <visp3/robust/vpPolynomialRoots.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "laser_geometry.h"

namespace vpLaserSolvers
{
namespace
{
/*!
  Unit normal m of the two planes through the apex that are tangent to the cone
  x^2 + y^2 = tan^2(theta) z^2 (laser frame) and contain the point o: m . o = 0 and
  m^T diag(1, 1, -1/tan^2 theta) m = 0 (the dual cone). Real only when o is outside the cone.
*/
bool tangentPlaneNormals(const Eigen::Vector3d &o, double halfAngle, Eigen::Vector3d &m1, Eigen::Vector3d &m2)
{
  const double on = o.norm();
  if (!(on > 0.0))
    return false;
  const Eigen::Vector3d w = o / on;
  // Orthonormal basis (b1, b2) of the plane orthogonal to o.
  Eigen::Vector3d b1 = std::abs(w(0)) < 0.9 ? Eigen::Vector3d::UnitX().cross(w) : Eigen::Vector3d::UnitY().cross(w);
  b1.normalize();
  const Eigen::Vector3d b2 = w.cross(b1);
  const double t = std::tan(halfAngle);
  const Eigen::Vector3d dual(t * t, t * t, -1.0); // tan^2 theta * diag(1, 1, -1/tan^2 theta)
  // Quadratic form of m = cos(phi) b1 + sin(phi) b2.
  const double q11 = b1.dot(dual.cwiseProduct(b1)), q12 = b1.dot(dual.cwiseProduct(b2)),
               q22 = b2.dot(dual.cwiseProduct(b2));
  const double disc = q12 * q12 - q11 * q22;
  if (!(disc > 0.0))
    return false; // o inside the cone (or on it): no real tangent plane
  const double root = std::sqrt(disc);
  // Null directions (a, b) of q11 a^2 + 2 q12 a b + q22 b^2, picking the better-conditioned form.
  Eigen::Vector2d d1, d2;
  if (std::abs(q11) >= std::abs(q22)) {
    d1 << -q12 + root, q11;
    d2 << -q12 - root, q11;
  } else {
    d1 << q22, -q12 + root;
    d2 << q22, -q12 - root;
  }
  if (!(d1.norm() > 0.0) || !(d2.norm() > 0.0))
    return false;
  m1 = (d1(0) * b1 + d1(1) * b2).normalized();
  m2 = (d2(0) * b1 + d2(1) * b2).normalized();
  return true;
}

/*!
  Homography H with H x1 ~ (0,0,1), H x2 ~ (1,0,1), H x3 ~ (0,1,1), H e ~ (1,1,0) (eq. 36), in
  closed form: A diag(lambda) maps the standard projective basis onto (x1, x2, x3, e), and a fixed
  matrix N maps it onto the canonical points.
*/
bool canonicalHomography(const Eigen::Vector3d x[3], const Eigen::Vector3d &e, Eigen::Matrix3d &H)
{
  Eigen::Matrix3d A;
  A << x[0], x[1], x[2];
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
  if (!lu.isInvertible())
    return false;
  const Eigen::Vector3d lambda = lu.solve(e);
  const double scale = lambda.cwiseAbs().maxCoeff();
  if (!(lambda.cwiseAbs().minCoeff() > 1e-12 * scale))
    return false; // the epipole is aligned with two of the points
  Eigen::Matrix3d N;
  // Columns: -2 (0,0,1), (1,0,1), (0,1,1); their sum is (1,1,0).
  N << 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -2.0, 1.0, 1.0;
  H = N * lambda.cwiseInverse().asDiagonal() * lu.inverse();
  return H.allFinite();
}

//! Value and derivative of the polynomial k[0] + k[1] u + ... + k[degree] u^degree.
double polynomial(const double *k, int degree, double u, double &derivative)
{
  double p = 0.0;
  derivative = 0.0;
  for (int i = degree; i >= 0; --i) {
    derivative = derivative * u + p;
    p = p * u + k[i];
  }
  return p;
}

//! Largest imaginary part, relative to the modulus, of a quartic root taken as (nearly) real.
constexpr double kRelativeImaginary = 1e-3;

//! Real roots of a polynomial of degree <= 4 (coefficients k[0] + k[1] u + ...), Newton-polished.
int realQuarticRoots(const double k[5], double roots[4])
{
  std::complex<double> candidates[4];
  const int degree = vpPolynomialRoots(k, candidates); // as many roots as the degree found
  int count = 0;
  for (int i = 0; i < degree; ++i) {
    const std::complex<double> z = candidates[i];
    // Keep nearly real roots: a root that is real in exact arithmetic can come out complex, and a
    // double root splits into a complex pair whose imaginary part is of the order of the square root
    // of the rounding, sqrt(eps) |z|. A root whose imaginary part is small relative to its magnitude
    // is kept (its real part is polished below, the conic polished on the original constraints and
    // tested as an ellipse by the caller); a conjugate pair gives that real part once.
    if (std::abs(z.imag()) > kRelativeImaginary * std::max(std::abs(z), 1e-3))
      continue;
    if (z.imag() < 0.0 && std::abs(z.imag()) > 0.0) {
      bool conjugateKept = false;
      for (int j = 0; j < degree; ++j)
        conjugateKept = conjugateKept || (j != i && std::abs(candidates[j] - std::conj(z)) <= 1e-12 * std::abs(z));
      if (conjugateKept)
        continue;
    }
    // Newton polish, each step kept only if it lowers the residual (safe near double roots).
    double u = z.real(), d = 0.0;
    double residual = std::abs(polynomial(k, degree, u, d));
    for (int it = 0; it < 3 && residual > 0.0; ++it) {
      const double next = u - polynomial(k, degree, u, d) / d;
      double unused = 0.0;
      const double nextResidual = std::abs(polynomial(k, degree, next, unused));
      if (!(nextResidual < residual))
        break;
      u = next;
      residual = nextResidual;
    }
    if (std::isfinite(u))
      roots[count++] = u;
  }
  return count;
}
typedef Eigen::Matrix<double, 6, 1> Vector6d;
typedef Eigen::Matrix<double, 6, 6> Matrix6d;

/*!
  Samples with two points closer than this fraction of their spread are refused: the quartic's
  roots then merge and the conic is decided by rounding (stress-laser finds 0.5-1.5 rad errors on
  samples at 1e-5 relative spacing).
*/
constexpr double kMinimalSampleSpread = 1e-4;

//! Separation |r - s| / (1 + |r| + |s|) of the tangents in the canonical frame deemed well conditioned.
constexpr double kGoodTangentSeparation = 0.05;
//! Below this separation in every order the sample is refused (see pp3Conics()).
constexpr double kMinTangentSeparation = 1e-3;

//! Symmetric conic from its six distinct entries (c00, c01, c11, c02, c12, c22).
Eigen::Matrix3d conicOf(const Vector6d &k)
{
  Eigen::Matrix3d c;
  c << k(0), k(1), k(3), k(1), k(2), k(4), k(3), k(4), k(5);
  return c;
}

//! Line tangency l^T adj(c) l = 0, a quadratic form in the entries of c (adj: adjugate).
double tangency(const Vector6d &k, const Eigen::Vector3d &l)
{
  const Eigen::Matrix3d c = conicOf(k);
  Eigen::Matrix3d adj;
  adj(0, 0) = c(1, 1) * c(2, 2) - c(1, 2) * c(2, 1);
  adj(0, 1) = c(0, 2) * c(2, 1) - c(0, 1) * c(2, 2);
  adj(0, 2) = c(0, 1) * c(1, 2) - c(0, 2) * c(1, 1);
  adj(1, 1) = c(0, 0) * c(2, 2) - c(0, 2) * c(2, 0);
  adj(1, 2) = c(0, 2) * c(1, 0) - c(0, 0) * c(1, 2);
  adj(2, 2) = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  adj(1, 0) = adj(0, 1);
  adj(2, 0) = adj(0, 2);
  adj(2, 1) = adj(1, 2);
  return l.dot(adj * l);
}

/*!
  Newton polish of a PP-3 conic on the original constraints (3 incidences, 2 tangencies, unit scale
  along the initial conic). The canonical frame of eq. 36 degrades when the epipole nears the line
  through two of the points, and the quartic then has nearly double roots; the constraints
  themselves stay well conditioned, so a few Newton steps restore full precision. A step is kept only
  if it lowers the residual.
*/
void polishConic(const Eigen::Vector3d x[3], const Eigen::Vector3d &u, const Eigen::Vector3d &v, Eigen::Matrix3d &c)
{
  const Eigen::Vector3d lines[2] = {u.normalized(), v.normalized()};
  Vector6d k;
  k << c(0, 0), c(0, 1), c(1, 1), c(0, 2), c(1, 2), c(2, 2);
  k.normalize();
  const Vector6d k0 = k;
  auto residuals = [&](const Vector6d &q) {
    Vector6d r;
    for (int i = 0; i < 3; ++i)
      r(i) = x[i].dot(conicOf(q) * x[i]);
    r(3) = tangency(q, lines[0]);
    r(4) = tangency(q, lines[1]);
    r(5) = k0.dot(q) - 1.0;
    return r;
  };
  Vector6d r = residuals(k);
  for (int it = 0; it < 4 && r.norm() > 0.0; ++it) {
    Matrix6d J;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d &p = x[i];
      J.row(i) << p(0) * p(0), 2.0 * p(0) * p(1), p(1) * p(1), 2.0 * p(0) * p(2), 2.0 * p(1) * p(2), p(2) * p(2);
    }
    // The tangency is quadratic in k: central differences are exact up to rounding.
    const double h = 1e-4;
    for (int j = 0; j < 6; ++j) {
      Vector6d plus = k, minus = k;
      plus(j) += h;
      minus(j) -= h;
      for (int l = 0; l < 2; ++l)
        J(3 + l, j) = (tangency(plus, lines[l]) - tangency(minus, lines[l])) / (2.0 * h);
    }
    J.row(5) = k0.transpose();
    const Vector6d next = k - J.fullPivLu().solve(r);
    if (!next.allFinite())
      break;
    const Vector6d rn = residuals(next);
    if (!(rn.norm() < r.norm()))
      break;
    k = next;
    r = rn;
  }
  c = conicOf(k);
}
} // namespace

bool epipolarTangents(const LaserCone &cone, EpipolarTangents &tangents)
{
  // The camera centre in the laser frame.
  const Eigen::Vector3d o = -cone.cRl.transpose() * cone.apex;
  Eigen::Vector3d m1, m2;
  if (!tangentPlaneNormals(o, cone.halfAngle, m1, m2))
    return false;
  // Each tangent plane contains the apex and the camera centre: in the camera frame it is
  // (N, 0) with N = cRl m, and with P = [I | 0] its image is the line N.
  tangents.epipole = cone.apex;
  tangents.u = cone.cRl * m1;
  tangents.v = cone.cRl * m2;
  return true;
}

int pp3Conics(const Eigen::Vector2d points[3], const EpipolarTangents &tangents, Eigen::Matrix3d conics[4])
{
  if (detail::nearDuplicate(points, 3, kMinimalSampleSpread))
    return 0;
  const Eigen::Vector3d x[3] = {Eigen::Vector3d(points[0](0), points[0](1), 1.0),
                                Eigen::Vector3d(points[1](0), points[1](1), 1.0),
                                Eigen::Vector3d(points[2](0), points[2](1), 1.0)};
  // The canonical frame of eq. 36 depends on which point goes to (0,0,1), (1,0,1), (0,1,1). When
  // the two tangents map to nearly the same line (r ~ s), the quartic's leading coefficient (r-s)^2
  // vanishes and its roots merge: the solutions are then lost to rounding. The three cyclic orders
  // give the same conics in exact arithmetic; the one with the best-separated tangents is used.
  Eigen::Matrix3d H;
  double r = 0.0, s = 0.0, separation = -1.0;
  for (int shift = 0; shift < 3 && separation < kGoodTangentSeparation; ++shift) {
    const Eigen::Vector3d ordered[3] = {x[shift], x[(shift + 1) % 3], x[(shift + 2) % 3]};
    Eigen::Matrix3d Hs;
    if (!canonicalHomography(ordered, tangents.epipole, Hs))
      continue;
    // Lines map with H^-T (eq. 38-39); both contain (1,1,0), so they read (1, -1, r) and (1, -1, s).
    const Eigen::Matrix3d Hinv = Hs.inverse();
    const Eigen::Vector3d up = Hinv.transpose() * tangents.u, vp = Hinv.transpose() * tangents.v;
    if (!(std::abs(up(0)) > 1e-12 * up.norm()) || !(std::abs(vp(0)) > 1e-12 * vp.norm()))
      continue;
    const double rs = up(2) / up(0), ss = vp(2) / vp(0);
    const double sep = std::abs(rs - ss) / (1.0 + std::abs(rs) + std::abs(ss));
    if (sep > separation) {
      separation = sep;
      H = Hs;
      r = rs;
      s = ss;
    }
  }
  // Even the best order separates the tangents poorly when two points are nearly aligned with the
  // epipole (their epipolar lines merge, and with them the reference lines of the pencil at e): the
  // quartic then loses the true solution to rounding (stress-laser finds 2 rad errors at 1e-5).
  // The parametrisation is degenerate there; the sample is refused.
  if (!(separation > kMinTangentSeparation))
    return 0;
  // Quartic in u (eq. 53), lowest degree first.
  const double k[5] = {16.0 * (r + s) * (r + s), -32.0 * (r + s) * (r * s + 1.0),
                       8.0 * (r * r + 4.0 * r * s + s * s + 2.0), 8.0 * (r + s) * (r * s - 1.0), (r - s) * (r - s)};
  double roots[4];
  const int nroots = realQuarticRoots(k, roots);
  int count = 0;
  for (int i = 0; i < nroots; ++i) {
    const double u = roots[i];
    // t from eq. 52.
    const double denominator = 2.0 * u * (s - r) + 4.0 * (r * r - s * s);
    if (!(std::abs(denominator) > 1e-14 * (1.0 + std::abs(u)) * (std::abs(r) + std::abs(s))))
      continue;
    const double t = (2.0 * u * (s - r) + u * u * (r * r - s * s)) / denominator;
    Eigen::Matrix3d cc;
    cc << 2.0, u, -1.0, u, 2.0 * t, -t, -1.0, -t, 0.0; // eq. 43
    Eigen::Matrix3d c = H.transpose() * cc * H;        // eq. 54
    polishConic(x, tangents.u, tangents.v, c);
    const double norm = c.norm();
    if (!(norm > 0.0) || !std::isfinite(norm))
      continue;
    c /= norm;
    if (isEllipse(c))
      conics[count++] = c;
  }
  return count;
}
} // namespace vpLaserSolvers
