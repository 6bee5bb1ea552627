/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Per-point loops on four-lane vectors (see laser_kernels.h).
#include "laser_kernels.h"

#include <cstring>

// Two builds of each kernel (baseline and AVX2, chosen once by the loader) where the compiler and
// the platform support function multi-versioning; a single baseline build elsewhere.
#if defined(__GNUC__) && defined(__x86_64__) && defined(__linux__) && !defined(__AVX2__)
#define VSP_LASER_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define VSP_LASER_KERNEL
#endif

namespace vpLaserSolvers
{
namespace internal
{
namespace
{
#if defined(__GNUC__)
typedef double Lanes __attribute__((vector_size(4 * sizeof(double))));
typedef long long LaneMask __attribute__((vector_size(4 * sizeof(double))));
#endif

constexpr int kLanes = 4;
} // namespace

VSP_LASER_KERNEL int scoreConicChunk(const ConicCoefficients &c, const double *x, const double *y, int first,
                                      int size, double thr2, double &cost, int *inliers)
{
  const double thr2Times4 = 4.0 * thr2;
  int count = 0;
  double sum = 0.0;
  int j = 0;
#if defined(__GNUC__)
  // A point is an inlier when (x^T c x)^2 < thr2 |grad|^2 (no division; NaN compares false); its
  // truncated cost is the squared distance then, thr2 otherwise. The index of every point is written
  // at the end of the list, which only advances for an inlier: no branch per point.
  Lanes acc = {0.0, 0.0, 0.0, 0.0};
  const Lanes t4 = {thr2Times4, thr2Times4, thr2Times4, thr2Times4}, t = {thr2, thr2, thr2, thr2};
  for (; j + kLanes <= size; j += kLanes) {
    Lanes X, Y;
    std::memcpy(&X, x + j, sizeof X);
    std::memcpy(&Y, y + j, sizeof Y);
    const Lanes v0 = c.a * X + c.b * Y + c.d, v1 = c.b * X + c.e * Y + c.f;
    const Lanes algebraic = X * v0 + Y * v1 + (c.d * X + c.f * Y + c.g);
    const Lanes a2 = algebraic * algebraic, g2 = v0 * v0 + v1 * v1;
    const LaneMask in = a2 < t4 * g2;
    const Lanes d2 = a2 / (4.0 * g2);
    acc += in ? d2 : t;
    for (int l = 0; l < kLanes; ++l) {
      inliers[count] = first + j + l;
      count -= static_cast<int>(in[l]); // -1 for an inlier
    }
  }
  sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
#endif
  for (; j < size; ++j) {
    double v0, v1;
    const double algebraic = c.apply(x[j], y[j], v0, v1);
    const double a2 = algebraic * algebraic, g2 = v0 * v0 + v1 * v1;
    const bool in = a2 < thr2Times4 * g2;
    sum += in ? a2 / (4.0 * g2) : thr2;
    inliers[count] = first + j;
    count += in ? 1 : 0;
  }
  cost += sum;
  return count;
}
} // namespace internal
} // namespace vpLaserSolvers
