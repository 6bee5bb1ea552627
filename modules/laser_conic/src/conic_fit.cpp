/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Conic fitting by DLT (Boutteau et al., JMIV 2018, eq. 29-31) on Hartley-normalised points.
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <algorithm>
#include <cmath>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "laser_geometry.h"
#include "laser_kernels.h"

namespace vpLaserSolvers
{
namespace
{
typedef Eigen::Matrix<double, 6, 1> Vector6d;
typedef Eigen::Matrix<double, 6, 6> Matrix6d;

//! Similarity T moving the centroid to the origin and the mean distance to sqrt(2).
bool hartleyNormalisation(const Eigen::Vector2d *points, int n, Eigen::Matrix3d &T)
{
  double cx = 0.0, cy = 0.0, meanDistance = 0.0;
  detail::centroidAndSpread(points, n, cx, cy, meanDistance);
  const Eigen::Vector2d centroid(cx, cy);
  if (!(meanDistance > 0.0) || !std::isfinite(meanDistance))
    return false;
  const double s = std::sqrt(2.0) / meanDistance;
  T << s, 0.0, -s * centroid(0), 0.0, s, -s * centroid(1), 0.0, 0.0, 1.0;
  return true;
}

//! Row of the DLT system (eq. 31) for a normalised point.
Vector6d conicRow(const Eigen::Matrix3d &T, const Eigen::Vector2d &p)
{
  const double x = T(0, 0) * p(0) + T(0, 2), y = T(1, 1) * p(1) + T(1, 2);
  Vector6d row;
  row << x * x, x * y, y * y, x, y, 1.0;
  return row;
}

//! Dot product of two arrays with four partial sums (the additions do not wait for one another).
inline double dot(const double *a, const double *b, int m)
{
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int i = 0;
  for (; i + 3 < m; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < m; ++i)
    s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

/*!
  Upper-triangular factor R (6x6) of a QR of the DLT system of n points, by blocks of kBlockRows
  rows: the R of the rows seen so far is updated with the next block by six Householder reflections,
  each zeroing one column of the block under the diagonal of R. Since R is already triangular, a
  reflection touches one row of R and the block only (R^T R = A^T A is preserved), and the block is
  kept column by column on the stack so that the updates are contiguous loops (built for SSE2 and
  AVX2, see laser_kernels.h).
*/
VSP_LASER_KERNEL Matrix6d triangularFactor(const Eigen::Matrix3d &T, const Eigen::Vector2d *points, int n)
{
  constexpr int kBlockRows = 64;
  double R[6][6] = {};     // R[k][j], upper triangle
  double X[6][kBlockRows]; // the block, column j = X[j]
  for (int start = 0; start < n; start += kBlockRows) {
    const int m = std::min(kBlockRows, n - start);
    for (int i = 0; i < m; ++i) {
      const Vector6d row = conicRow(T, points[start + i]);
      for (int j = 0; j < 6; ++j)
        X[j][i] = row(j);
    }
    for (int k = 0; k < 6; ++k) {
      double *x = X[k];
      const double norm2 = dot(x, x, m);
      if (norm2 == 0.0)
        continue; // the block is already zero in that column
      const double alpha = R[k][k];
      const double beta = -std::copysign(std::sqrt(alpha * alpha + norm2), alpha);
      // Reflector (1 at row k of R, v in the block) with H = I - tau [1; v] [1; v]^T.
      const double scale = 1.0 / (alpha - beta), tau = (beta - alpha) / beta;
      for (int i = 0; i < m; ++i)
        x[i] *= scale;
      R[k][k] = beta;
      for (int j = k + 1; j < 6; ++j) {
        double *xj = X[j];
        const double f = tau * (R[k][j] + dot(x, xj, m));
        R[k][j] -= f;
        for (int i = 0; i < m; ++i)
          xj[i] -= f * x[i];
      }
    }
  }
  Matrix6d out = Matrix6d::Zero();
  for (int k = 0; k < 6; ++k)
    for (int j = k; j < 6; ++j)
      out(k, j) = R[k][j];
  return out;
}

/*!
  Null vector of the 6x6 triangular factor R (or padded minimal system): smallest right singular
  vector. Fails when the null space has dimension > 1 (e.g. collinear points).
*/
bool smallestSingularVector(const Matrix6d &R, Vector6d &coefficients)
{
  Eigen::JacobiSVD<Matrix6d> svd(R, Eigen::ComputeFullV);
  const Vector6d &sv = svd.singularValues();
  if (!(sv(0) > 0.0) || !(sv(4) > 1e-12 * sv(0)))
    return false;
  coefficients = svd.matrixV().col(5);
  return true;
}
/*!
  Null vector of a minimal system (5 rows of A, padded with a zero row in R): the last column of the Q of a
  column-pivoted QR of A^T, orthogonal to its five rows; a ninth of the time of the singular value
  decomposition, which RANSAC pays per sample. Fails when the rows are dependent (e.g. four collinear points).
*/
bool minimalNullVector(const Matrix6d &R, Vector6d &coefficients)
{
  const Eigen::Matrix<double, 6, 5> At = R.topRows<5>().transpose();
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 6, 5> > qr(At);
  const double largest = std::abs(qr.matrixR()(0, 0)), smallest = std::abs(qr.matrixR()(4, 4));
  if (!(largest > 0.0) || !(smallest > 1e-12 * largest))
    return false;
  const Matrix6d Q = qr.householderQ();
  coefficients = Q.col(5);
  return true;
}
} // namespace

bool fitConic(const Eigen::Vector2d *points, int n, Eigen::Matrix3d &c)
{
  if (n < 5 || points == nullptr)
    return false;
  // A minimal sample with two nearly coincident points determines its conic by rounding only.
  if (n == 5 && detail::nearDuplicate(points, 5, 1e-6))
    return false;
  Eigen::Matrix3d T;
  if (!hartleyNormalisation(points, n, T))
    return false;

  Matrix6d R = Matrix6d::Zero();
  if (n <= 6) {
    // Minimal (and one-over) case: the system itself, padded with zero rows, on the stack.
    for (int i = 0; i < n; ++i)
      R.row(i) = conicRow(T, points[i]).transpose();
  } else {
    // Least squares: the triangular factor of a QR has the same right singular vectors as A and
    // avoids squaring the condition number as A^T A would.
    R = triangularFactor(T, points, n);
  }
  Vector6d k;
  if (!(n == 5 ? minimalNullVector(R, k) : smallestSingularVector(R, k)))
    return false;

  Eigen::Matrix3d cn;
  cn << k(0), 0.5 * k(1), 0.5 * k(3), 0.5 * k(1), k(2), 0.5 * k(4), 0.5 * k(3), 0.5 * k(4), k(5);
  c = T.transpose() * cn * T;
  const double norm = c.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    return false;
  c /= norm;
  return true;
}
} // namespace vpLaserSolvers
