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
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <visp3/robust/vpRobustScale.h>

#include "laser_geometry.h"
#include "laser_kernels.h"

namespace vpLaserSolvers
{
namespace
{
using detail::ConicCoefficients;

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
  conic has no gradient. One buffer of 4 n values (r, j0, j1, j2), allocated once per refinement
  and swapped between iterates.
*/
struct PointTerms
{
  std::unique_ptr<double[]> values;
  int size = 0, capacity = 0;
  void resize(int n)
  {
    if (n > capacity) {
      values.reset(new double[4 * static_cast<size_t>(n)]);
      capacity = n;
    }
    size = n;
  }
  double *r() const { return values.get(); }
  double *j0() const { return values.get() + capacity; }
  double *j1() const { return values.get() + 2 * static_cast<size_t>(capacity); }
  double *j2() const { return values.get() + 3 * static_cast<size_t>(capacity); }
};

NormalEquations equationsOf(const detail::PlaneTermsSums &s)
{
  NormalEquations ne;
  ne.JtJ << s.h[0], s.h[1], s.h[2], s.h[1], s.h[3], s.h[4], s.h[2], s.h[4], s.h[5];
  ne.Jtr << s.g[0], s.g[1], s.g[2];
  ne.cost = s.cost;
  return ne;
}

//! Weighted normal equations of stored terms (a reweighting: no evaluation of the conic).
NormalEquations assemble(const PointTerms &t, const double *weights, int n)
{
  detail::PlaneTermsSums sums;
  detail::planeTermsSums(t.r(), t.j0(), t.j1(), t.j2(), weights, n, sums);
  return equationsOf(sums);
}

/*!
  One pass over the points: their terms stored and the normal equations (unit weights when
  \e weights is null), by detail::planeTermsKernel(). Points where the conic has no gradient
  are skipped.
*/
NormalEquations evaluateTerms(const Eigen::Vector2d *points, const double *weights, int n, const PlaneConics &pc,
                              PointTerms &t)
{
  detail::PlaneTermsCoefficients k{ConicCoefficients(pc.c), ConicCoefficients(pc.dc[2]), {}, {}, {}};
  for (int i = 0; i < 3; ++i) {
    k.w[i] = pc.w(i);
    k.t0[i] = pc.t[0](i);
    k.t1[i] = pc.t[1](i);
  }
  t.resize(n);
  detail::PlaneTermsSums sums;
  detail::planeTermsKernel(k, points, weights, n, t.r(), t.j0(), t.j1(), t.j2(), sums);
  return equationsOf(sums);
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
  cost below kTolerance, far below the statistical uncertainty of the plane for any realistic noise,
  or, with \e firstStepOnly, after the first accepted step.
*/
void levenbergMarquardt(const Eigen::Vector2d *points, const double *weights, int n, const Eigen::Vector3d &apex,
                        const Eigen::Matrix3d &M, int iterations, Iterate &current, Iterate &next,
                        bool firstStepOnly = false)
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
      if (gain < kTolerance || firstStepOnly)
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

// Weights finite and >= 0 with at least 3 positive (the plane's degrees of freedom); nullptr: unit weights.
bool validWeights(const double *weights, int n)
{
  if (weights == nullptr)
    return true;
  int positive = 0;
  for (int i = 0; i < n; ++i) {
    if (!(weights[i] >= 0.0) || !std::isfinite(weights[i]))
      return false;
    positive += weights[i] > 0.0 ? 1 : 0;
  }
  return positive >= 3;
}
} // namespace

bool refinePlane(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int iterations)
{
  return refinePlaneWeighted(points, nullptr, n, cone, plane, iterations);
}

bool refinePlaneWeighted(const Eigen::Vector2d *points, const double *weights, int n, const LaserCone &cone,
                         Eigen::Vector4d &plane, int iterations)
{
  if (!validStart(points, n, plane) || !validWeights(weights, n))
    return false;
  const Eigen::Matrix3d M = detail::laserConeForm(cone);
  Iterate current, next;
  evaluate(plane / plane.head<3>().norm(), points, weights, n, cone.apex, M, current);
  if (!std::isfinite(current.ne.cost))
    return false;
  levenbergMarquardt(points, weights, n, cone.apex, M, iterations, current, next);
  plane = current.plane;
  return true;
}

namespace detail
{
bool refinePlaneHuber(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int rounds,
                      int iterations, std::vector<double> &residuals)
{
  if (!validStart(points, n, plane))
    return false;
  const Eigen::Matrix3d M = detail::laserConeForm(cone);
  Iterate current, next;
  evaluate(plane / plane.head<3>().norm(), points, nullptr, n, cone.apex, M, current);
  std::vector<double> w(static_cast<size_t>(n)), scratch;
  for (int round = 0; round < rounds; ++round) {
    // Weights at the scale of the residuals of the current plane (kept from its last evaluation).
    const double *r = current.terms.r();
    scratch.assign(r, r + n);
    const double sigma = vpRobustMadScale(std::move(scratch));
    // vpRobustWeight(vpRobustLoss::HUBER, r, sigma) for every residual (NaN, no gradient: zero weight).
    if (sigma > 0.0)
      detail::huberWeights(r, n, detail::kHuberTuning * sigma, w.data());
    else
      for (int i = 0; i < n; ++i)
        w[static_cast<size_t>(i)] = vpRobustWeight(vpRobustLoss::HUBER, r[i], sigma);
    current.ne = assemble(current.terms, w.data(), n);
    if (!std::isfinite(current.ne.cost))
      return false;
    // A round before the last only sets the residuals the next weights come from: converging it
    // exactly is wasted, the last round absorbs what is left of its step (a fraction of a standard
    // deviation of the plane) and runs to convergence.
    levenbergMarquardt(points, w.data(), n, cone.apex, M, iterations, current, next, round + 1 < rounds);
  }
  plane = current.plane;
  residuals.assign(current.terms.r(), current.terms.r() + n);
  return true;
}
} // namespace detail
} // namespace vpLaserSolvers
