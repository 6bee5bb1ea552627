/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of the shared RANSAC loop: eq. 28 trial counts and a 2D line estimator with outliers.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <set>

#include <visp3/core/vpException.h>
#include <visp3/robust/vpRansac.h>

TEST(RobustRansacTrialCount, MatchesThePaperNumbers)
{
  // Boutteau et al. Sec. 5: p = 0.99, 50 % outliers: 146 samples of 5 points, 35 of 3 points.
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.5, 5, 100000), 146);
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.5, 3, 100000), 35);
}

TEST(RobustRansacTrialCount, EdgeCases)
{
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.0, 3, 1000), 0);
  EXPECT_EQ(vpRansacTrialCount(0.99, 1.0, 3, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.99, 0.999999, 5, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.99, std::nan(""), 3, 1000), 1000);
  EXPECT_EQ(vpRansacTrialCount(0.0, 0.5, 3, 1000), 1);
}

TEST(RobustRansacSampler, RefusesMoreIndicesThanThereAre)
{
  int out[3];
  vpRansacSampler two(2, 1), none(0, 1);
  EXPECT_THROW(two.draw(3, out), vpException); // hung: no third distinct index
  EXPECT_THROW(none.draw(1, out), vpException);
  EXPECT_THROW(two.draw(-1, out), vpException);
  EXPECT_NO_THROW(two.draw(2, out));
  EXPECT_NE(out[0], out[1]);
}

TEST(RobustRansacSampler, DrawsDistinctIndicesReproducibly)
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

// Line data: nOut uniform outliers first, then noisy inliers of y = 0.5 x - 2.
LineEstimator makeLineData(int n, int nOut, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-10, 10);
  std::normal_distribution<double> noise(0, 0.01);
  LineEstimator est;
  for (int i = 0; i < n; ++i) {
    const double xi = u(rng);
    est.x.push_back(xi);
    est.y.push_back(i < nOut ? u(rng) * 5 : 0.5 * xi - 2.0 + noise(rng));
  }
  return est;
}
} // namespace

TEST(RobustRansacLoop, RecoversALineThroughSixtyPercentOutliers)
{
  const int n = 500, nOut = 300;
  const LineEstimator est = makeLineData(n, nOut, 42);
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

TEST(RobustRansacLoop, RefusesTooFewData)
{
  LineEstimator est;
  est.x = {1.0};
  est.y = {2.0};
  LineEstimator::Model best;
  vpRansacReport report;
  EXPECT_FALSE(vpRansacLoop(est, vpRansacOptions(), best, report));
  EXPECT_EQ(report.trials, 0);
}

// A confidence that is not a probability is refused like a bad threshold: NaN gave one trial, and a
// model of outliers returned as a success.
TEST(RobustRansacLoop, RefusesAConfidenceThatIsNotAProbability)
{
  const LineEstimator est = makeLineData(200, 100, 21);
  for (double p : {std::numeric_limits<double>::quiet_NaN(), 0.0, -0.5, 1.5}) {
    vpRansacOptions opt;
    opt.threshold = 0.05;
    opt.probability = p;
    LineEstimator::Model best;
    vpRansacReport report;
    EXPECT_FALSE(vpRansacLoop(est, opt, best, report)) << "probability " << p;
    EXPECT_EQ(report.trials, 0);
  }
}

// A pretest subset is rounded up to whole blocks of vpRansacPretestBlock: with few data it is switched off
// rather than drawn larger than the data (pretestSize 1-3 and 4-15 data read past the data before).
TEST(RobustRansacLoop, APretestLargerThanTheDataOnceRoundedIsSwitchedOff)
{
  const LineEstimator est = makeLineData(12, 2, 22);
  vpRansacOptions plain, pretest;
  plain.threshold = pretest.threshold = 0.05;
  pretest.pretestSize = 2;
  LineEstimator::Model a, b;
  vpRansacReport ra, rb;
  ASSERT_TRUE(vpRansacLoop(est, plain, a, ra));
  ASSERT_TRUE(vpRansacLoop(est, pretest, b, rb));
  EXPECT_EQ(rb.inliers, ra.inliers); // the same loop: no pretest on 12 data
  EXPECT_EQ(rb.trials, ra.trials);
}

TEST(RobustRansacScore, EarlyStopNeverChangesTheRanking)
{
  const LineEstimator est = makeLineData(500, 300, 11);
  const double thr2 = 0.05 * 0.05;
  LineEstimator::Model good, bad;
  good.a = 0.5;
  good.b = -2.0;
  bad.a = -1.0;
  bad.b = 3.0;
  const std::pair<int, double> fullGood = vpRansacScore(est, good, thr2), fullBad = vpRansacScore(est, bad, thr2);
  EXPECT_GE(fullGood.first, 200); // every inlier, and the odd outlier that falls near the line
  EXPECT_LE(fullGood.first, 210);
  EXPECT_LT(fullBad.first, 20);
  // Against a bar the model cannot reach the scoring stops early: the count stays below the bar.
  const std::pair<int, double> stopped = vpRansacScore(est, bad, thr2, fullGood.first);
  EXPECT_LT(stopped.first, fullGood.first);
  EXPECT_LE(stopped.first, fullBad.first);
  // Against a bar it reaches, the score is the full one.
  const std::pair<int, double> reached = vpRansacScore(est, good, thr2, fullGood.first);
  EXPECT_EQ(reached, fullGood);
}

TEST(RobustRansacScore, InlierListsAgreeWithCounts)
{
  const LineEstimator est = makeLineData(500, 300, 12);
  const double thr2 = 0.05 * 0.05;
  LineEstimator::Model good;
  good.a = 0.5;
  good.b = -2.0;
  std::vector<int> listed;
  vpRansacInliers(est, good, thr2, listed);
  std::vector<int> buffer(500, -1);
  const std::pair<int, double> sc = vpRansacScore(est, good, thr2, 0, buffer.data());
  ASSERT_EQ(static_cast<int>(listed.size()), sc.first);
  for (int k = 0; k < sc.first; ++k) {
    EXPECT_EQ(buffer[k], listed[k]);
    EXPECT_LT(est.residual(good, listed[k]), 0.05);
  }
}

TEST(RobustRansacLoop, ReportedInliersAreTheConsensusOfTheBestModel)
{
  const LineEstimator est = makeLineData(500, 300, 13);
  for (int rounds : {1, 3}) {
    vpRansacOptions opt;
    opt.threshold = 0.05;
    opt.seed = 5;
    opt.localRounds = rounds;
    LineEstimator::Model best;
    vpRansacReport report;
    ASSERT_TRUE(vpRansacLoop(est, opt, best, report));
    std::vector<int> listed;
    vpRansacInliers(est, best, opt.threshold * opt.threshold, listed);
    EXPECT_EQ(report.inliers, listed) << rounds << " rounds";
    EXPECT_EQ(report.inlierCount, static_cast<int>(listed.size()));
    EXPECT_EQ(report.score, vpRansacScore(est, best, opt.threshold * opt.threshold).second);
    EXPECT_NEAR(best.a, 0.5, 2e-3);
    EXPECT_NEAR(best.b, -2.0, 5e-3);
  }
}

TEST(RobustRansacSampler, DrawsSingleIndicesInRange)
{
  vpRansacSampler a(3, 11), b(3, 11);
  for (int t = 0; t < 1000; ++t) {
    const int k = a.index(7);
    ASSERT_GE(k, 0);
    ASSERT_LT(k, 7);
    ASSERT_EQ(k, b.index(7)); // the same seed, the same draws
  }
  EXPECT_THROW(a.index(0), vpException);
  EXPECT_THROW(a.index(-2), vpException);
}

namespace
{
// LineEstimator over data that come in groups, drawing both points of a sample from the group of a point drawn
// at random (vpRansacLoop()'s optional drawSample()); counts its draws.
struct GroupedLineEstimator : LineEstimator
{
  std::vector<int> group;                 //!< group of each datum
  std::vector<std::vector<int> > members; //!< the data of each group
  mutable int draws = 0;
  void drawSample(vpRansacSampler &sampler, int *s) const
  {
    ++draws;
    s[0] = sampler.index(size());
    const std::vector<int> &same = members[static_cast<size_t>(group[static_cast<size_t>(s[0])])];
    do
      s[1] = same[static_cast<size_t>(sampler.index(static_cast<int>(same.size())))];
    while (s[1] == s[0]);
  }
};

// 20 points of y = 0.5 x - 2 (group 0), then 64 groups of 10 points each on a line of its own (x spread over
// [-10, 10], noise 0.01): the line is 3 % of the data, any two points drawn at random lie on it once in 1100
// samples.
GroupedLineEstimator makeGroupedLines(unsigned int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-10, 10), slope(-3, 3);
  std::normal_distribution<double> noise(0, 0.01);
  GroupedLineEstimator est;
  for (int g = 0; g <= 64; ++g) {
    const double a = g == 0 ? 0.5 : slope(rng), b = g == 0 ? -2.0 : u(rng);
    est.members.emplace_back();
    for (int i = 0; i < (g == 0 ? 20 : 10); ++i) {
      const double xi = u(rng);
      est.members.back().push_back(est.size());
      est.group.push_back(g);
      est.x.push_back(xi);
      est.y.push_back(a * xi + b + noise(rng));
    }
  }
  return est;
}

// The line through two of its points (no local optimisation): the slope within 0.01 (noise 0.01 over points
// a few units apart), its 20 points inliers (a few of the other lines' points may cross it).
bool onTheLine(const LineEstimator::Model &m, const vpRansacReport &report)
{
  return std::abs(m.a - 0.5) < 0.01 && std::abs(m.b + 2.0) < 0.05 && report.inlierCount >= 20;
}
} // namespace

TEST(RobustRansacLoop, AnEstimatorThatDrawsItsOwnSamplesIsUsed)
{
  // 100 samples each: two points of one group lie on the line once in 33 draws (the first point on it), two
  // points drawn one by one once in 1100 (a 9 % chance per run to find it).
  int grouped = 0, uniform = 0;
  for (unsigned int seed = 1; seed <= 20; ++seed) {
    const GroupedLineEstimator est = makeGroupedLines(seed);
    vpRansacOptions opt;
    opt.threshold = 0.05;
    opt.seed = seed;
    opt.maxTrials = 100;
    opt.localOptimisation = false;
    LineEstimator::Model best;
    vpRansacReport report;
    ASSERT_TRUE(vpRansacLoop(est, opt, best, report));
    EXPECT_EQ(est.draws, report.trials); // every sample came from drawSample()
    grouped += onTheLine(best, report) ? 1 : 0;
    const LineEstimator &plain = est; // the same data without drawSample(): samples drawn one by one
    ASSERT_TRUE(vpRansacLoop(plain, opt, best, report));
    uniform += onTheLine(best, report) ? 1 : 0;
  }
  EXPECT_GE(grouped, 19); // 1 - 0.97^100: each run finds it with probability 0.95
  EXPECT_LE(uniform, 6);  // 20 runs at 9 %: 1.8 expected
  std::cout << "line found by grouped samples in " << grouped << " of 20 runs, by uniform samples in " << uniform
            << std::endl;
}

namespace
{
// LineEstimator's data with a drawSample() that writes \e bad as its second index (-1: the first again).
struct BadSampleEstimator : LineEstimator
{
  int bad = 0;
  void drawSample(vpRansacSampler &sampler, int *s) const
  {
    s[0] = sampler.index(size());
    s[1] = bad < 0 ? s[0] : bad;
  }
};
} // namespace

TEST(RobustRansacLoop, RefusesAnEstimatorsSampleOutsideItsDataOrRepeated)
{
  BadSampleEstimator est;
  static_cast<LineEstimator &>(est) = makeLineData(50, 10, 3);
  vpRansacOptions opt;
  opt.threshold = 0.05;
  LineEstimator::Model best;
  vpRansacReport report;
  est.bad = 50; // one past the data
  EXPECT_THROW(vpRansacLoop(est, opt, best, report), vpException);
  est.bad = -1; // the first index again
  EXPECT_THROW(vpRansacLoop(est, opt, best, report), vpException);
}
