/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of the shared RANSAC loop: eq. 28 trial counts and a 2D line estimator with outliers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include <visp3/robust/vpRansac.h>

TEST(RansacTrialCount, MatchesThePaperNumbers)
{
  // Boutteau et al. Sec. 5: p = 0.99, 50 % outliers: 146 samples of 5 points, 35 of 3 points.
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.5, 5, 100000), 146);
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.5, 3, 100000), 35);
}

TEST(RansacTrialCount, EdgeCases)
{
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.0, 3, 1000), 0);
  EXPECT_EQ(vpRansacTrialCount(0.99, 1.0, 3, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.999999, 5, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.99, std::nan(""), 3, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.0, 0.5, 3, 1000), 1);
}

TEST(RansacSampler, DrawsDistinctIndicesReproducibly)
{
  vpRansacSampler a(5, 7), b(5, 7);
  for (int t = 0; t < 1000; ++t) {
    int sa[5], sb[5];
    a.draw(5, sa);
    b.draw(5, sb);
    std::set<int> distinct(sa, sa + 5);
    ASSERT_EQ(distinct.size(), 5u);
    for (int i = 0; i < 5; ++i) {
      ASSERT_EQ(sa[i], sb[i]);
      ASSERT_GE(sa[i], 0);
      ASSERT_LT(sa[i], 5);
    }
  }
}

namespace
{
// y = a x + b from two points; refit by least squares on the inliers.
struct LineEstimator
{
  struct Model
  {
    double a = 0, b = 0;
  };
  static constexpr int kSampleSize = 2;
  static constexpr int kMaxModels = 1;
  std::vector<double> x, y;
  int size() const { return static_cast<int>(x.size()); }
  int solveMinimal(const int *s, Model *m) const
  {
    const double dx = x[s[1]] - x[s[0]];
    if (std::abs(dx) < 1e-12)
      return 0;
    m[0].a = (y[s[1]] - y[s[0]]) / dx;
    m[0].b = y[s[0]] - m[0].a * x[s[0]];
    return 1;
  }
  double residual(const Model &m, int i) const { return std::abs(m.a * x[i] + m.b - y[i]); }
  bool refine(const std::vector<int> &in, Model &m) const
  {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int i : in) {
      sx += x[i];
      sy += y[i];
      sxx += x[i] * x[i];
      sxy += x[i] * y[i];
    }
    const double k = double(in.size()), det = k * sxx - sx * sx;
    if (std::abs(det) < 1e-12)
      return false;
    m.a = (k * sxy - sx * sy) / det;
    m.b = (sy - m.a * sx) / k;
    return true;
  }
};
} // namespace

TEST(RansacLoop, RecoversALineThroughSixtyPercentOutliers)
{
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-10, 10);
  std::normal_distribution<double> noise(0, 0.01);
  LineEstimator est;
  const int n = 500, nOut = 300;
  for (int i = 0; i < n; ++i) {
    const double xi = u(rng);
    est.x.push_back(xi);
    est.y.push_back(i < nOut ? u(rng) * 5 : 0.5 * xi - 2.0 + noise(rng));
  }
  vpRansacOptions opt;
  opt.threshold = 0.05;
  opt.seed = 3;
  LineEstimator::Model best;
  vpRansacReport report;
  ASSERT_TRUE(vpRansacLoop(est, opt, best, report));
  EXPECT_NEAR(best.a, 0.5, 2e-3);
  EXPECT_NEAR(best.b, -2.0, 5e-3);
  EXPECT_GE(report.inlierCount, n - nOut);
  EXPECT_LE(report.inlierCount, n - nOut + 10); // a handful of outliers may fall near the line
  EXPECT_LT(report.trials, opt.maxTrials);      // the adaptive count stopped the loop early
}

TEST(RansacLoop, RefusesTooFewData)
{
  LineEstimator est;
  est.x = {1.0};
  est.y = {2.0};
  LineEstimator::Model best;
  vpRansacReport report;
  EXPECT_FALSE(vpRansacLoop(est, vpRansacOptions(), best, report));
  EXPECT_EQ(report.trials, 0);
}
