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
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <visp3/robust/vpRobustScale.h>

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
  Eigen::Vector3d t[2];  //!< the tangents: dc[k] = t[k] w^T + w t[k]^T for k < 2
  Eigen::Vector3d w;     //!< G^T M apex
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
  for (int k = 0; k < 2; ++k) {
    pc.dc[k] = tangents[k] * w.transpose() + w * tangents[k].transpose();
    pc.t[k] = tangents[k];
  }
  pc.w = w;
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
  Residuals and Jacobian rows of every point at one plane, kept so that a reweighting (IRLS) forms
  its normal equations without evaluating the conic again. NaN residual (zero Jacobian) where the
  conic has no gradient.
*/
struct PointTerms
{
  std::vector<double> r, j0, j1, j2;
  void resize(int n)
  {
    const size_t m = static_cast<size_t>(n);
    r.resize(m);
    j0.resize(m);
    j1.resize(m);
    j2.resize(m);
  }
};

//! Weighted sums of the normal equations (upper triangle of J^T J, J^T r, cost), one lane per point of a pair.
struct PairSums
{
  typedef Eigen::Array2d P;
  P h0 = P::Zero(), h1 = P::Zero(), h2 = P::Zero(), h3 = P::Zero(), h4 = P::Zero(), h5 = P::Zero();
  P g0 = P::Zero(), g1 = P::Zero(), g2 = P::Zero(), cost = P::Zero();
  void add(const P &w, const P &r, const P &J0, const P &J1, const P &J2)
  {
    const P wJ0 = w * J0, wJ1 = w * J1, wJ2 = w * J2;
    cost += w * r * r;
    h0 += wJ0 * J0;
    h1 += wJ0 * J1;
    h2 += wJ0 * J2;
    h3 += wJ1 * J1;
    h4 += wJ1 * J2;
    h5 += wJ2 * J2;
    g0 += wJ0 * r;
    g1 += wJ1 * r;
    g2 += wJ2 * r;
  }
  NormalEquations equations() const
  {
    NormalEquations ne;
    ne.JtJ << h0.sum(), h1.sum(), h2.sum(), h1.sum(), h3.sum(), h4.sum(), h2.sum(), h4.sum(), h5.sum();
    ne.Jtr << g0.sum(), g1.sum(), g2.sum();
    ne.cost = cost.sum();
    return ne;
  }
};

//! Weighted normal equations of stored terms (a reweighting: no evaluation of the conic), by pairs.
NormalEquations assemble(const PointTerms &t, const double *weights, int n)
{
  typedef Eigen::Array2d P;
  PairSums sums;
  for (int i = 0; i < n; i += 2) {
    const bool pair = i + 1 < n;
    const int i1 = pair ? i + 1 : i;
    const size_t k0 = static_cast<size_t>(i), k1 = static_cast<size_t>(i1);
    // Zero weight (NaN residual: no gradient, or the missing second point of an odd count): no contribution.
    const P w(weights[i], pair ? weights[i1] : 0.0);
    const P r((w(0) != 0.0) ? t.r[k0] : 0.0, (w(1) != 0.0) ? t.r[k1] : 0.0);
    const P J0(t.j0[k0], t.j0[k1]), J1(t.j1[k0], t.j1[k1]), J2(t.j2[k0], t.j2[k1]);
    sums.add(w, r, J0, J1, J2);
  }
  return sums.equations();
}

/*!
  One pass over the points: their terms stored and the normal equations (unit weights when
  \e weights is null). The signed Sampson distance is r = A / (2 sqrt(B)) with A = x^T c x and
  B = |(c x)_{1,2}|^2, so dr = (dA - A dB / (2 B)) / (2 sqrt(B)) with dA = x^T dc x and
  dB = 2 (c x)_{1,2} . (dc x)_{1,2}. Points where the conic has no gradient are skipped.
  Two points at a time (Eigen::Array2d: one SIMD register), with the sums kept per lane.
*/
NormalEquations evaluateTerms(const Eigen::Vector2d *points, const double *weights, int n, const PlaneConics &pc,
                              PointTerms &t)
{
  typedef Eigen::Array2d P;
  // The normal moves along t: dc = t w^T + w t^T (rank 2), so with homogeneous x, x^T dc x = 2 (t.x)(w.x)
  // and (dc x)_{1,2} = t_{1,2} (w.x) + w_{1,2} (t.x): a few products per point instead of a conic each.
  const ConicCoefficients c(pc.c), dd(pc.dc[2]);
  const double w0 = pc.w(0), w1 = pc.w(1), w2 = pc.w(2);
  const double t00 = pc.t[0](0), t01 = pc.t[0](1), t02 = pc.t[0](2);
  const double t10 = pc.t[1](0), t11 = pc.t[1](1), t12 = pc.t[1](2);
  t.resize(n);
  PairSums sums;
  for (int i = 0; i < n; i += 2) {
    const bool pair = i + 1 < n; // the last point of an odd count goes alone (lane 1 weighted 0)
    const int i1 = pair ? i + 1 : i;
    const P x(points[i](0), points[i1](0)), y(points[i](1), points[i1](1));
    P w(weights ? weights[i] : 1.0, pair ? (weights ? weights[i1] : 1.0) : 0.0);
    const P v0 = c.a * x + c.b * y + c.d, v1 = c.b * x + c.e * y + c.f;
    const P A = x * v0 + y * v1 + (c.d * x + c.f * y + c.g);
    const P B = v0 * v0 + v1 * v1;
    const P invRoot = 0.5 / B.sqrt(), ratio = A / B;
    const P wx = w0 * x + w1 * y + w2, vw = v0 * w0 + v1 * w1;
    const P tx0 = t00 * x + t01 * y + t02, vt0 = v0 * t00 + v1 * t01;
    const P tx1 = t10 * x + t11 * y + t12, vt1 = v0 * t10 + v1 * t11;
    const P u0 = dd.a * x + dd.b * y + dd.d, u1 = dd.b * x + dd.e * y + dd.f;
    const P dA2 = x * u0 + y * u1 + (dd.d * x + dd.f * y + dd.g);
    P J0 = (2.0 * tx0 * wx - ratio * (vt0 * wx + vw * tx0)) * invRoot;
    P J1 = (2.0 * tx1 * wx - ratio * (vt1 * wx + vw * tx1)) * invRoot;
    P J2 = (dA2 - ratio * (v0 * u0 + v1 * u1)) * invRoot;
    P r = A * invRoot;
    if (pair) {
      P::Map(&t.r[static_cast<size_t>(i)]) = r;
      P::Map(&t.j0[static_cast<size_t>(i)]) = J0;
      P::Map(&t.j1[static_cast<size_t>(i)]) = J1;
      P::Map(&t.j2[static_cast<size_t>(i)]) = J2;
    } else {
      t.r[static_cast<size_t>(i)] = r(0);
      t.j0[static_cast<size_t>(i)] = J0(0);
      t.j1[static_cast<size_t>(i)] = J1(0);
      t.j2[static_cast<size_t>(i)] = J2(0);
    }
    if (!(B > 0.0).all()) { // no gradient: NaN residual, zero Jacobian, no contribution
      for (int l = 0; l < 2; ++l) {
        if (B(l) > 0.0)
          continue;
        if (l == 0 || pair) {
          const size_t k = static_cast<size_t>(i + l);
          t.r[k] = std::numeric_limits<double>::quiet_NaN();
          t.j0[k] = t.j1[k] = t.j2[k] = 0.0;
        }
        w(l) = r(l) = J0(l) = J1(l) = J2(l) = 0.0;
      }
    }
    sums.add(w, r, J0, J1, J2);
  }
  return sums.equations();
}

//! A plane, its terms and the normal equations evaluated there, in its own tangent basis.
struct Iterate
{
  Eigen::Vector4d plane;
  Eigen::Vector3d tangents[2];
  NormalEquations ne;
  PointTerms terms;
};

void evaluate(const Eigen::Vector4d &plane, const Eigen::Vector2d *points, const double *weights, int n,
              const Eigen::Vector3d &apex, const Eigen::Matrix3d &M, Iterate &it)
{
  it.plane = plane;
  it.tangents[0] = plane.head<3>().unitOrthogonal();
  it.tangents[1] = plane.head<3>().cross(it.tangents[0]);
  it.ne = evaluateTerms(points, weights, n, planeConics(plane, it.tangents, apex, M), it.terms);
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

/*!
  Levenberg-Marquardt iterations from \e current (evaluated with the same weights). Each iteration is
  one pass over the points: a rejected step reuses the normal equations of the current plane with
  more damping, an accepted one brings those of the new plane (\e next is the scratch iterate). The
  loop ends when the Gauss-Newton model promises (or the last step gave) a relative decrease of the
  cost below kTolerance, far below the statistical uncertainty of the plane for any realistic noise.
*/
void levenbergMarquardt(const Eigen::Vector2d *points, const double *weights, int n, const Eigen::Vector3d &apex,
                        const Eigen::Matrix3d &M, int iterations, Iterate &current, Iterate &next)
{
  double damping = 1e-3;
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
    evaluate(candidate, points, weights, n, apex, M, next);
    if (next.ne.cost < current.ne.cost) {
      const double gain = (current.ne.cost - next.ne.cost) / current.ne.cost;
      std::swap(current, next);
      damping = std::max(1e-9, 0.1 * damping);
      if (gain < kTolerance)
        break;
    } else {
      damping *= 10.0;
    }
  }
}

bool validStart(const Eigen::Vector2d *points, int n, const Eigen::Vector4d &plane)
{
  return n >= 3 && points != nullptr && plane.allFinite() && plane.head<3>().norm() > 0.0 && plane(3) > 0.0;
}
} // namespace

bool refinePlane(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int iterations)
{
  return refinePlaneWeighted(points, nullptr, n, cone, plane, iterations);
}

bool refinePlaneWeighted(const Eigen::Vector2d *points, const double *weights, int n, const LaserCone &cone,
                         Eigen::Vector4d &plane, int iterations)
{
  if (!validStart(points, n, plane))
    return false;
  const Eigen::Matrix3d M = internal::laserConeForm(cone);
  Iterate current, next;
  evaluate(plane / plane.head<3>().norm(), points, weights, n, cone.apex, M, current);
  if (!std::isfinite(current.ne.cost))
    return false;
  levenbergMarquardt(points, weights, n, cone.apex, M, iterations, current, next);
  plane = current.plane;
  return true;
}

namespace internal
{
bool refinePlaneHuber(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int rounds,
                      int iterations, std::vector<double> &residuals)
{
  if (!validStart(points, n, plane))
    return false;
  const Eigen::Matrix3d M = internal::laserConeForm(cone);
  Iterate current, next;
  evaluate(plane / plane.head<3>().norm(), points, nullptr, n, cone.apex, M, current);
  std::vector<double> w(static_cast<size_t>(n));
  for (int round = 0; round < rounds; ++round) {
    // Weights at the scale of the residuals of the current plane (kept from its last evaluation).
    const double sigma = vpRobustMadScale(current.terms.r);
    for (int i = 0; i < n; ++i) // NaN residuals (no gradient) get a zero weight
      w[static_cast<size_t>(i)] = vpRobustWeight(vpRobustLoss::HUBER, current.terms.r[static_cast<size_t>(i)], sigma);
    current.ne = assemble(current.terms, w.data(), n);
    if (!std::isfinite(current.ne.cost))
      return false;
    levenbergMarquardt(points, w.data(), n, cone.apex, M, iterations, current, next);
  }
  plane = current.plane;
  residuals = current.terms.r;
  return true;
}
} // namespace internal
} // namespace vpLaserSolvers
