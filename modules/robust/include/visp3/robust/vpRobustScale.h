/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpRobustScale.h
  \brief After a RANSAC search: the residual scale estimated from the data, the inliers re-collected
  at a threshold derived from it, and the weights of an iteratively reweighted least-squares refit.

  A fixed RANSAC threshold separates gross outliers; it is a poor inlier test for the final fit when
  the model cannot explain the data to that threshold (e.g. an imperfect calibration), since the
  consensus then keeps only the part of the data the model explains best. These helpers let a caller
  measure the actual residual scale of its consensus and refit at that scale.
*/
#ifndef VP_ROBUST_SCALE_H
#define VP_ROBUST_SCALE_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <visp3/core/vpConfig.h>

/*!
  \ingroup group_robust
  Robust standard deviation of zero-mean residuals: 1.4826 times the median of their absolute values
  (MAD about zero; 1.4826 makes it consistent for Gaussian residuals). Non-finite values are ignored;
  0 for an empty set. \e residuals is taken by value (partially sorted).
*/
inline double vpRobustMadScale(std::vector<double> residuals)
{
  // Absolute values of the finite residuals, compacted in place without a branch per value.
  size_t count = 0;
  for (double r : residuals) {
    residuals[count] = std::abs(r);
    count += std::isfinite(r) ? 1 : 0;
  }
  if (count == 0)
    return 0.0;
  residuals.resize(count);
  const size_t mid = count / 2;
  std::nth_element(residuals.begin(), residuals.begin() + static_cast<std::ptrdiff_t>(mid), residuals.end());
  double median = residuals[mid];
  if (count % 2 == 0) {
    const double below = *std::max_element(residuals.begin(), residuals.begin() + static_cast<std::ptrdiff_t>(mid));
    median = 0.5 * (median + below);
  }
  return 1.4826 * median;
}

/*!
  \ingroup group_robust
  Indices of the residuals whose absolute value is below \e threshold (NaN never is), written to \e inliers.
*/
inline void vpRobustCollect(const std::vector<double> &residuals, double threshold, std::vector<int> &inliers)
{
  // Without a branch per residual (inliers and outliers alternate at random near a trace): each
  // index is written at the end of the list, which advances only for an inlier.
  inliers.resize(residuals.size());
  size_t count = 0;
  for (size_t i = 0; i < residuals.size(); ++i) {
    inliers[count] = static_cast<int>(i);
    count += std::abs(residuals[i]) < threshold ? 1 : 0;
  }
  inliers.resize(count);
}

//! \ingroup group_robust Robust losses of vpRobustWeight().
enum class vpRobustLoss {
  HUBER, //!< quadratic up to k sigma, linear beyond (k = 1.345: 95 % efficiency under Gaussian noise)
  CAUCHY //!< log(1 + (r / (k sigma))^2) (k = 2.3849: 95 % efficiency), redescending-like, strong against outliers
};

/*!
  \ingroup group_robust
  IRLS weight w(r) = psi(r) / r of residual \e r for the loss at scale \e sigma (> 0): a weighted
  least-squares step with these weights is a Newton-like step on the robust cost. A zero or invalid
  scale gives unit weights.
*/
inline double vpRobustWeight(vpRobustLoss loss, double r, double sigma)
{
  if (!(sigma > 0.0) || !std::isfinite(r))
    return std::isfinite(r) ? 1.0 : 0.0;
  if (loss == vpRobustLoss::HUBER) {
    // min(1, k / |r|) is 1 exactly when |r| <= k (k / 0 = inf), and compiles without a branch.
    const double k = 1.345 * sigma, a = std::abs(r);
    return std::min(1.0, k / a);
  }
  const double u = r / (2.3849 * sigma);
  return 1.0 / (1.0 + u * u);
}

#endif
