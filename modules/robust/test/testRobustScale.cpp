/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpRobustScale.h: residual scale, re-collection and IRLS weights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <visp3/robust/vpRobustScale.h>

// 1.4826 MAD of N(0, sigma^2) residuals estimates sigma: its relative standard error is about
// 1.1 / sqrt(N) = 1.1 % for N = 10^4, so 5 % is a 4-sigma bound; 30 % gross outliers far away move the
// median by less than a factor 1.6 (the median of |r| becomes the 0.71 quantile of the inliers').
TEST(RobustScale, MadOfGaussianResiduals)
{
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 0.7);
  std::vector<double> r(10000);
  for (double &v : r)
    v = g(rng);
  EXPECT_NEAR(vpRobustMadScale(r), 0.7, 0.05 * 0.7);
  std::vector<double> contaminated = r;
  for (size_t i = 0; i < 3000; ++i)
    contaminated[i] = 1000.0;
  const double s = vpRobustMadScale(contaminated);
  EXPECT_GT(s, 0.7);
  EXPECT_LT(s, 1.6 * 0.7);
}

TEST(RobustScale, MadEdgeCases)
{
  EXPECT_EQ(vpRobustMadScale(std::vector<double>()), 0.0);
  EXPECT_EQ(vpRobustMadScale(std::vector<double>{std::numeric_limits<double>::quiet_NaN()}), 0.0);
  EXPECT_DOUBLE_EQ(vpRobustMadScale(std::vector<double>{-1.0, 3.0}), 1.4826 * 2.0); // median of {1, 3}
  EXPECT_DOUBLE_EQ(vpRobustMadScale(std::vector<double>{2.0, -5.0, 1.0}), 1.4826 * 2.0);
}

// The histogram selection of vpRobustMadScale() is exact: the same median as sorting, for random
// sizes (odd and even) and value sets that stress it: ties, a few huge values (all others in the
// first bin), NaN, signed zeros, a range of denormals and one of a few ulps.
TEST(RobustScale, MadIsTheExactMedian)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 0.5);
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<double> r(1 + rng() % 2500);
    const int kind = trial % 7;
    for (double &v : r) {
      v = g(rng);
      if (kind == 1)
        v = std::round(4.0 * v); // many ties
      else if (kind == 2 && rng() % 10 == 0)
        v = 1e9;
      else if (kind == 3 && rng() % 20 == 0)
        v = std::numeric_limits<double>::quiet_NaN();
      else if (kind == 4)
        v = (rng() % 2) ? -0.0 : 0.25 * (rng() % 3);
      else if (kind == 5)
        v = (rng() % 5) * 1e-310;
      else if (kind == 6)
        v = 1.0 + (rng() % 3) * 1e-16;
    }
    std::vector<double> sorted;
    for (double v : r)
      if (std::isfinite(v))
        sorted.push_back(std::abs(v));
    std::sort(sorted.begin(), sorted.end());
    const size_t m = sorted.size();
    const double median = m == 0 ? 0.0 : (m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]));
    ASSERT_EQ(vpRobustMadScale(r), 1.4826 * median) << "trial " << trial << ", " << r.size() << " values";
  }
}

TEST(RobustScale, CollectAndWeights)
{
  std::vector<int> inliers;
  vpRobustCollect({0.5, -2.5, std::numeric_limits<double>::quiet_NaN(), 1.9, -0.1}, 2.0, inliers);
  EXPECT_EQ(inliers, (std::vector<int>{0, 3, 4}));
  // Huber: unit weight up to 1.345 sigma, then k / |r|.
  EXPECT_EQ(vpRobustWeight(vpRobustLoss::HUBER, 1.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(vpRobustWeight(vpRobustLoss::HUBER, -2.69, 1.0), 0.5);
  // Cauchy: 1 / (1 + (r / 2.3849 sigma)^2), one half at 2.3849 sigma.
  EXPECT_DOUBLE_EQ(vpRobustWeight(vpRobustLoss::CAUCHY, 2.3849 * 3.0, 3.0), 0.5);
  EXPECT_EQ(vpRobustWeight(vpRobustLoss::CAUCHY, 5.0, 0.0), 1.0); // no scale: unit weights
  EXPECT_EQ(vpRobustWeight(vpRobustLoss::HUBER, std::numeric_limits<double>::infinity(), 1.0), 0.0);
  // No loss: plain least squares, unit weights at any residual (zero for a non-finite one).
  EXPECT_EQ(vpRobustWeight(vpRobustLoss::NONE, 50.0, 1.0), 1.0);
  EXPECT_EQ(vpRobustWeight(vpRobustLoss::NONE, std::numeric_limits<double>::quiet_NaN(), 1.0), 0.0);
}
