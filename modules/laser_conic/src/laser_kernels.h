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

namespace vpLaserSolvers
{
namespace internal
{
/*!
  RANSAC scoring of a conic on the points (x[j], y[j]), j < size (normalized coordinates, size <=
  64): the points whose squared Sampson distance is below \e thr2 are the inliers (NaN never is).
  Their indices first + j are written to \e inliers (room for \e size), the sum of the squared
  distances truncated at \e thr2 is added to \e cost. \return the number of inliers.
*/
int scoreConicChunk(const ConicCoefficients &c, const double *x, const double *y, int first, int size, double thr2,
                    double &cost, int *inliers);
} // namespace internal
} // namespace vpLaserSolvers

#endif
