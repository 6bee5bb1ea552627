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
#include <cstdint>
#include <cstring>
#include <vector>

#include <visp3/core/vpConfig.h>

namespace vsp::detail
{
//! \e x when \e keep, +0 otherwise, by a bit mask: compilers turn a select of doubles into a branch.
inline double zeroUnless(bool keep, double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits &= ~static_cast<std::uint64_t>(0) * static_cast<std::uint64_t>(keep);
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

/*!
  The k-th and (k-1)-th smallest of v[0, n) (finite, non-negative; 1 <= k < n), v reordered. Exact,
  like std::nth_element, whose partitioning mispredicts a branch for about every other value of
  random data: a histogram of the values over their range (bin = floor((v - lo) scale), monotone in
  v, so every value of a lower bin is below every value of a higher one) locates the bin of the k-th
  value in one branch-free pass; its values are moved to the front and the search goes on among them.
  A few levels leave a handful of values for std::nth_element.
*/
inline void selectPair(double *v, size_t n, size_t k, double &kth, double &previous)
{
  constexpr int kBins = 256;
  constexpr size_t kSmall = 32;
  // Largest value of the bins left below the current range; used only when the k-th value ends first
  // in its range, which some value below then precedes (values >= 0, so 0 stands for none).
  double below = 0.0;
  for (int level = 0; level < 4 && n > kSmall; ++level) {
    double lo = v[0], hi = v[0];
    for (size_t i = 1; i < n; ++i) {
      lo = std::min(lo, v[i]);
      hi = std::max(hi, v[i]);
    }
    const double scale = kBins / (hi - lo);
    if (!(hi > lo) || !std::isfinite(scale))
      break; // all equal, or a range too narrow for bins
    unsigned int counts[kBins] = {};
    for (size_t i = 0; i < n; ++i)
      ++counts[std::min(kBins - 1, static_cast<int>((v[i] - lo) * scale))];
    int bin = 0;
    size_t before = 0;
    while (before + counts[bin] <= k)
      before += counts[bin++];
    // The values of that bin to the front (branch-free), the largest value below it kept.
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {
      const double x = v[i];
      const int b = std::min(kBins - 1, static_cast<int>((x - lo) * scale));
      below = std::max(below, zeroUnless(b < bin, x));
      v[m] = x;
      m += b == bin ? 1 : 0;
    }
    n = m;
    k -= before;
  }
  std::nth_element(v, v + static_cast<std::ptrdiff_t>(k), v + static_cast<std::ptrdiff_t>(n));
  kth = v[k];
  previous = k > 0 ? *std::max_element(v, v + static_cast<std::ptrdiff_t>(k)) : below;
}
} // namespace vsp::detail

/*!
  \ingroup group_robust
  Robust standard deviation of zero-mean residuals: 1.4826 times the median of their absolute values
  (MAD about zero; 1.4826 makes it consistent for Gaussian residuals). Non-finite values are ignored;
  0 for an empty set. \e residuals is taken by value (reordered).
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
  if (count == 1)
    return 1.4826 * residuals[0];
  const size_t mid = count / 2;
  double median = 0.0, below = 0.0;
  vsp::detail::selectPair(residuals.data(), count, mid, median, below);
  if (count % 2 == 0)
    median = 0.5 * (median + below);
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

/*!
  \ingroup group_robust
  The robust losses of the project, one vocabulary for every robust fit: the IRLS weights of
  vpRobustWeight(), the loss of vpPoseGravity::refinePose() (vpPoseGravity::setRefineLoss()) and of
  the calibration's second stage (vpLaserConicCalibration::setRobustLoss()). The facades keep their
  former names as aliases (vpPoseGravity::vpRobustLoss, vpPoseGravity::LOSS_HUBER,
  vpLaserConicCalibration::vpLaserConicLoss, vpLaserConicCalibration::LOSS_CAUCHY, ...).
*/
enum class vpRobustLoss {
  NONE,  //!< squared error: plain least squares, maximum likelihood under Gaussian noise (unit weights)
  HUBER, //!< quadratic up to k sigma, linear beyond (k = 1.345: 95 % efficiency under Gaussian noise)
  CAUCHY //!< log(1 + (r / (k sigma))^2) (k = 2.3849: 95 % efficiency), redescending-like, strong against outliers
};

/*!
  \ingroup group_robust
  IRLS weight w(r) = psi(r) / r of residual \e r for the loss at scale \e sigma (> 0): a weighted
  least-squares step with these weights is a Newton-like step on the robust cost. A zero or invalid
  scale, or vpRobustLoss::NONE, gives unit weights (zero for a non-finite residual).
*/
inline double vpRobustWeight(vpRobustLoss loss, double r, double sigma)
{
  if (loss == vpRobustLoss::NONE || !(sigma > 0.0) || !std::isfinite(r))
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
