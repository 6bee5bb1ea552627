/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_geometry.h
  \brief Private inline kernels of the laser_conic module shared by the solvers and the RANSAC
  estimators: the 3x3 form of the laser cone, the unnormalised image conic of the trace on a plane,
  the squared Sampson distance of a point to a conic stored as six coefficients and the signed one
  to a 3x3 conic.
*/
#ifndef VP_LASER_GEOMETRY_H
#define VP_LASER_GEOMETRY_H

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace vpLaserSolvers
{
namespace detail
{
/*!
  The ellipse C (its symmetric part, any scale) as centre + axes diag(a, b) (cos t, sin t): its centre, unit axes
  (columns) and semi-axes. False when C is no real ellipse.
*/
inline bool ellipseAxes(const Eigen::Matrix3d &C, Eigen::Vector2d &centre, Eigen::Matrix2d &axes, double &a, double &b)
{
  const Eigen::Matrix3d S = 0.5 * (C + C.transpose());
  const Eigen::Matrix2d A = S.topLeftCorner<2, 2>();
  if (!(std::fabs(A.determinant()) > 0.0))
    return false;
  centre = -A.inverse() * S.topRightCorner<2, 1>();
  const double level = -(centre.dot(S.topRightCorner<2, 1>()) + S(2, 2)); // (x - c)^T A (x - c) = level
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(A);
  const Eigen::Vector2d l = eig.eigenvalues() / level;
  if (!(l(0) > 0.0 && l(1) > 0.0) || !centre.allFinite())
    return false;
  axes = eig.eigenvectors();
  a = 1.0 / std::sqrt(l(0));
  b = 1.0 / std::sqrt(l(1));
  return std::isfinite(a) && std::isfinite(b);
}

//! Perimeter of an ellipse of semi-axes a and b (Ramanujan's second approximation).
inline double ellipsePerimeter(double a, double b)
{
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return M_PI * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

//! 3x3 form M of the laser cone: (X - apex)^T M (X - apex) = 0 in the camera frame (defined in cones.cpp).
Eigen::Matrix3d laserConeForm(const LaserCone &cone);

/*!
  Image conic of the trace of the cone (apex, form M) on a plane, not normalised. A ray r meets the
  plane at X = -d r / (n.r); up to that factor, X - apex = G r with G = d I + apex n^T, so the trace
  seen through r satisfies r^T G^T M G r = 0.
*/
inline Eigen::Matrix3d traceConic(const Eigen::Vector4d &plane, const Eigen::Vector3d &apex, const Eigen::Matrix3d &M)
{
  const Eigen::Matrix3d G = plane(3) * Eigen::Matrix3d::Identity() + apex * plane.head<3>().transpose();
  const Eigen::Matrix3d c = G.transpose() * M * G;
  return 0.5 * (c + c.transpose());
}

//! The six distinct coefficients of a symmetric conic, laid out for the per-point kernels below.
struct ConicCoefficients
{
  double a, b, d, e, f, g; //!< c = [a b d; b e f; d f g]

  //! Copies the upper triangle of a symmetric conic.
  explicit ConicCoefficients(const Eigen::Matrix3d &c)
    : a(c(0, 0)), b(c(0, 1)), d(c(0, 2)), e(c(1, 1)), f(c(1, 2)), g(c(2, 2))
  {
  }

  /*!
    c (x, y, 1): the first two entries are half the gradient of the conic at (x, y); the
    algebraic value x^T c x is returned.
  */
  double apply(double x, double y, double &v0, double &v1) const
  {
    v0 = a * x + b * y + d;
    v1 = b * x + e * y + f;
    return x * v0 + y * v1 + (d * x + f * y + g);
  }

  /*!
    Squared Sampson distance (x^T c x)^2 / |grad|^2 with |grad|^2 = 4 (v0^2 + v1^2): no square root.
    NaN or infinity when the gradient vanishes (never below a threshold).
  */
  double squaredSampson(double x, double y) const
  {
    double v0, v1;
    const double algebraic = apply(x, y, v0, v1);
    return (algebraic * algebraic) / (4.0 * (v0 * v0 + v1 * v1));
  }
};

//! Signed Sampson distance (x^T c x) / |grad| of \e p to the conic c (first order; the sign is the side of
//! the conic), NaN where the conic has no gradient.
inline double signedSampson(const Eigen::Matrix3d &c, const Eigen::Vector2d &p)
{
  const Eigen::Vector3d x(p(0), p(1), 1.0);
  const Eigen::Vector3d g = c * x;
  const double gn = g.head<2>().norm();
  return gn > 0.0 ? x.dot(g) / (2.0 * gn) : std::numeric_limits<double>::quiet_NaN();
}
//! Huber's tuning constant (vpRobustLoss::HUBER): quadratic up to this many noise scales, 95 % efficient.
constexpr double kHuberTuning = 1.345;

/*!
  Iteratively reweighted refinement of a plane (d > 0) on trace points: \e rounds rounds, each of
  Huber weights (vpRobustWeight(), k = kHuberTuning sigma) at the MAD scale sigma of the residuals of the
  current plane, then refinePlaneWeighted() with those weights (\e iterations iterations at most;
  the rounds before the last stop after their first accepted step).
  \e residuals receives the signed Sampson distances (normalized units) of the points to the final
  plane's conic, NaN where it has no gradient. The residuals of each plane are kept from the pass
  that evaluated it: no extra pass per round. \return false on invalid input or non-finite residuals.
*/
bool refinePlaneHuber(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane, int rounds,
                      int iterations, std::vector<double> &residuals);

/*!
  True when two of the \e n points of a minimal sample are closer than \e relative times the largest
  distance between two of them (or all coincide). Two nearly coincident points of a minimal sample
  leave the model determined by rounding only: the solvers refuse such samples rather than return
  an arbitrary model (RANSAC loses nothing, measured points of a trace are pixels apart).
*/
template <class Point> inline bool nearDuplicate(const Point *p, int n, double relative)
{
  double smallest = 0.0, largest = 0.0;
  bool first = true;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double d = (p[i] - p[j]).squaredNorm();
      smallest = first ? d : std::min(smallest, d);
      largest = std::max(largest, d);
      first = false;
    }
  return !(smallest > relative * relative * largest);
}
} // namespace detail
} // namespace vpLaserSolvers

#endif
