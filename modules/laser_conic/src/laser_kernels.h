/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_kernels.h
  \brief Private per-point loops of the circular-laser estimators that dominate their run time,
  written on four-lane vectors. On x86-64 with GCC or Clang each one is compiled twice, for the
  baseline instruction set (SSE2: two registers per vector) and for AVX2 (one register), and the
  AVX2 version is chosen at load time when the processor has it; both run the same operations in
  the same order (no fused multiply-add), so their results are identical.
*/
#ifndef VP_LASER_KERNELS_H
#define VP_LASER_KERNELS_H

#include "laser_geometry.h"

/*!
  Marks a function to be compiled for the baseline instruction set and for AVX2, the loader choosing
  one (function multi-versioning) where the compiler and the platform support it; a single build
  elsewhere (Clang included: it rejects the four-lane vectors the AVX2 build would pass to the
  helpers it shares with the baseline one). The compiler vectorises the loops of each build for its
  own registers.
*/
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && !defined(__AVX2__)
#define VSP_LASER_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define VSP_LASER_KERNEL
#endif

/*!
  Marks a helper of the kernels: always inlined, so that each build of a kernel (see VSP_LASER_KERNEL)
  compiles it for its own instruction set. An out-of-line helper would be compiled once, for the
  baseline, and an AVX2 kernel passing or returning four-lane vectors would then call it with
  another calling convention (what -Wpsabi warns of): wrong values in any build that does not inline
  (debug builds, sanitizers).
*/
#if defined(__GNUC__)
#define VSP_LASER_INLINE inline __attribute__((always_inline))
#else
#define VSP_LASER_INLINE inline
#endif

namespace vpLaserSolvers
{
namespace detail
{
/*!
  RANSAC scoring of a conic on the points (x[j], y[j]), j < size (normalized coordinates, size <=
  64): the points whose squared Sampson distance is below \e thr2 are the inliers (NaN never is).
  Their indices first + j are written to \e inliers (room for \e size), the sum of the squared
  distances truncated at \e thr2 is added to \e cost. \return the number of inliers.
*/
int scoreConicChunk(const ConicCoefficients &c, const double *x, const double *y, int first, int size, double thr2,
                    double &cost, int *inliers);

/*!
  What planeTermsKernel() needs of a plane: its image conic \e c, the derivative \e dd of the conic
  along the altitude, and the vectors w and t_k of the rank-2 derivatives t_k w^T + w t_k^T along the
  two tangents of the normal (plane_refine.cpp).
*/
struct PlaneTermsCoefficients
{
  ConicCoefficients c, dd;
  double w[3], t0[3], t1[3];
};

/*!
  Weighted sums of the normal equations of the plane refinement: upper triangle of J^T W J (h[0..5]
  for (0,0), (0,1), (0,2), (1,1), (1,2), (2,2)), J^T W r (g[0..2]) and r^T W r (cost).
*/
struct PlaneTermsSums
{
  double h[6], g[3], cost;
};

/*!
  One pass of the plane refinement over the n points: per point the signed Sampson distance r of
  the point to the conic and its derivatives j0, j1, j2 along the three local coordinates of the
  plane, stored in the arrays (NaN residual and zero derivatives where the conic has no gradient),
  and their sums weighted by \e weights (unit weights when null; a point without gradient adds
  nothing).
*/
void planeTermsKernel(const PlaneTermsCoefficients &k, const Eigen::Vector2d *points, const double *weights, int n,
                      double *r, double *j0, double *j1, double *j2, PlaneTermsSums &sums);

//! The weighted sums of planeTermsKernel() from stored terms (zero weight or NaN residual: no contribution).
void planeTermsSums(const double *r, const double *j0, const double *j1, const double *j2, const double *weights, int n,
                    PlaneTermsSums &sums);
/*!
  IRLS weights of the Huber loss, w = min(1, k / |r|) (1 for r = 0), 0 for a non-finite residual:
  vpRobustWeight(vpRobustLoss::HUBER, r, k / 1.345) for k > 0, four residuals at a time.
*/
void huberWeights(const double *r, int n, double k, double *w);

/*!
  Centroid (cx, cy) of the points and their mean distance to it (the Hartley normalisation of the
  conic fit), with four partial sums per quantity.
*/
void centroidAndSpread(const Eigen::Vector2d *points, int n, double &cx, double &cy, double &meanDistance);

/*!
  Angular bins of the points points[indices[i]], i < n, around an ellipse: with u = U (p - centre)
  (U upper triangular, U^T U the quadratic part of the ellipse, so u lies on a circle), the bin is
  floor((atan2(u1, u0) + pi) bins / (2 pi)), from a polynomial atan2 (within 2e-8 rad: the polynomial
  of atan on [0, 1] of Abramowitz and Stegun, 4.4.49) unless the angle is within 1e-6 rad of a bin
  edge (then std::atan2, so that the bin is the one the exact angle gives); -1 for a point whose u has a NaN
  coordinate (a centre or a point that overflowed), which has no angle.
*/
void ellipseBins(const Eigen::Vector2d *points, const int *indices, int n, const Eigen::Vector2d &centre,
                 const Eigen::Matrix2d &U, int bins, int *out);
} // namespace detail
} // namespace vpLaserSolvers

#endif
