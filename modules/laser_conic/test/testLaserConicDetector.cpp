/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpLaserConicDetector on images rendered by vpLaserConicSimulator: accuracy of the sub-pixel
// centres against the exact image conic of the simulation, recall along the curve, rejection of blobs.
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>

#include "laser_sim_test_utils.h"

using namespace laser_sim_test;

namespace
{
struct DetectionStats
{
  double maxError = 0.0, meanError = 0.0, recall = 0.0;
  size_t nbPoints = 0;
  double milliseconds = 0.0;
};

// Renders one frame, detects, and compares with the exact trace.
DetectionStats detectAndCompare(const vpHomogeneousMatrix &cMg, unsigned int seed, double stripeWidth, double noise,
                                vpLaserConicDetector &detector)
{
  vpLaserConicSimulator sim = makeSimulator(cMg, seed);
  vpImage<vpRGBa> I;
  sim.render(I, vpImage<vpRGBa>(), stripeWidth, noise);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<vpImagePoint> points = detector.detect(I);
  DetectionStats stats;
  stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats.nbPoints = points.size();
  const Eigen::Matrix3d C = pixelConic(sim.getGroundPlane());
  for (const vpImagePoint &p : points) {
    const double e = sampsonDistance(C, p);
    if (e > 0.5 && std::getenv("VSP_DEBUG")) std::cout << "bad " << p.get_u() << " " << p.get_v() << " " << e << std::endl;
    stats.maxError = std::max(stats.maxError, e);
    stats.meanError += e / std::max<size_t>(1, points.size());
  }
  // Recall: fraction of exact trace points (away from the border, where runs are truncated) with a detection
  // within 1.5 px; the detections are about one per pixel of curve, so a hole shows as a miss.
  const std::vector<vpImagePoint> trace = sim.tracePoints(3000);
  size_t found = 0, considered = 0;
  for (const vpImagePoint &q : trace) {
    if (q.get_u() < 10 || q.get_v() < 10 || q.get_u() > kWidth - 11 || q.get_v() > kHeight - 11)
      continue;
    ++considered;
    for (const vpImagePoint &p : points)
      if (vpImagePoint::distance(p, q) < 1.5) {
        ++found;
        break;
      }
  }
  stats.recall = considered ? static_cast<double>(found) / considered : 0.0;
  return stats;
}

std::vector<vpHomogeneousMatrix> groundPoses()
{
  return {vpHomogeneousMatrix(0.05, -0.03, 1.0, vpMath::rad(10), vpMath::rad(-8), 0.3),
          vpHomogeneousMatrix(0.0, 0.0, 0.6, vpMath::rad(-20), vpMath::rad(5), 0.0),
          vpHomogeneousMatrix(-0.1, 0.05, 1.4, vpMath::rad(25), vpMath::rad(20), 1.0)};
}

/*!
  Renders the trace on each ground pose (seeds from \e firstSeed) and checks the detections: more than
  1000 points (about one per pixel of curve), every one within 0.5 px of the exact conic, a mean distance
  below \e maxMeanError px, and more than 99 % of the trace found.
*/
void checkDetections(const char *what, unsigned int firstSeed, double stripeWidth, double noise, double maxMeanError)
{
  vpLaserConicDetector detector;
  unsigned int seed = firstSeed;
  for (const vpHomogeneousMatrix &cMg : groundPoses()) {
    const DetectionStats stats = detectAndCompare(cMg, seed++, stripeWidth, noise, detector);
    std::cout << what << ": " << stats.nbPoints << " points, max error " << stats.maxError << " px, mean "
              << stats.meanError << " px, recall " << stats.recall << ", detect " << stats.milliseconds << " ms"
              << std::endl;
    EXPECT_GT(stats.nbPoints, 1000u) << what;
    EXPECT_LT(stats.maxError, 0.5) << what;
    EXPECT_LT(stats.meanError, maxMeanError) << what;
    EXPECT_GT(stats.recall, 0.99) << what;
  }
}
} // namespace

TEST(LaserConicDetector, FindsTheCleanRenderedTraceWithSubPixelAccuracy)
{
  // Clean render: blur but no sensor noise. The stripe is symmetric across the curve, so the weighted
  // centre is off the curve only by the curvature of the stripe, the truncation of the run at the mask
  // threshold and the textured ground under the stripe (grain of ~20 grey levels under a ~250 level
  // peak): measured at most 0.28 px, 0.03 px on average.
  checkDetections("clean", 1, 3.0, 0.0, 0.06);
}

TEST(LaserConicDetector, FindsTheNoisyRenderedTrace)
{
  // Sensor noise of 3 grey levels on a stripe of ~250 levels moves a weighted centre of ~5 pixels by
  // a few hundredths of a pixel; the mask edge pixels flicker, which adds a little more: measured at
  // most 0.30 px, 0.045 px on average.
  checkDetections("noisy", 10, 4.0, 3.0, 0.08);
}

TEST(LaserConicDetector, SamplingStepThinsThePoints)
{
  vpLaserConicSimulator sim = makeSimulator(groundPoses()[0], 3);
  vpImage<vpRGBa> I;
  sim.render(I);
  vpLaserConicDetector detector;
  const size_t all = detector.detect(I).size();
  detector.setSamplingStep(4);
  const std::vector<vpImagePoint> sparse = detector.detect(I);
  // One row/column in four: about a quarter of the points (the lines at a multiple of 4 are a fair sample).
  EXPECT_NEAR(static_cast<double>(sparse.size()) / all, 0.25, 0.03);
  for (const vpImagePoint &p : sparse) {
    const bool onRow = std::fmod(p.get_i(), 4.0) == 0.0, onColumn = std::fmod(p.get_j(), 4.0) == 0.0;
    EXPECT_TRUE(onRow || onColumn);
  }
}

TEST(LaserConicDetector, MaskMarksTheStripe)
{
  vpLaserConicSimulator sim = makeSimulator(groundPoses()[0], 4);
  vpImage<vpRGBa> I;
  sim.render(I);
  vpLaserConicDetector detector;
  const std::vector<vpImagePoint> points = detector.detect(I);
  const vpImage<unsigned char> &mask = detector.getMask();
  ASSERT_EQ(mask.getWidth(), kWidth);
  ASSERT_EQ(mask.getHeight(), kHeight);
  for (const vpImagePoint &p : points)
    EXPECT_EQ(mask[static_cast<unsigned int>(std::lround(p.get_i()))][static_cast<unsigned int>(std::lround(p.get_j()))],
              255);
}

TEST(LaserConicDetector, RejectsBlobsAndIgnoresOtherColours)
{
  vpImage<vpRGBa> I(200, 300, vpRGBa(40, 40, 40, 255));
  // A red square wider than the maximum stripe width, a green and a white vertical stripe.
  for (unsigned int i = 50; i < 110; ++i)
    for (unsigned int j = 50; j < 110; ++j)
      I[i][j] = vpRGBa(255, 20, 20, 255);
  for (unsigned int i = 0; i < 200; ++i)
    for (unsigned int j = 200; j < 204; ++j) {
      I[i][j] = vpRGBa(20, 255, 20, 255);
      I[i][j + 20] = vpRGBa(255, 255, 255, 255);
    }
  vpLaserConicDetector detector;
  EXPECT_TRUE(detector.detect(I).empty());

  // A thin vertical red stripe, 3 px wide with a symmetric profile centred at u = 150.5: rows measure it.
  for (unsigned int i = 0; i < 200; ++i) {
    I[i][149] = vpRGBa(200, 20, 20, 255);
    I[i][150] = vpRGBa(255, 20, 20, 255);
    I[i][151] = vpRGBa(255, 20, 20, 255);
    I[i][152] = vpRGBa(200, 20, 20, 255);
  }
  const std::vector<vpImagePoint> points = detector.detect(I);
  ASSERT_FALSE(points.empty());
  for (const vpImagePoint &p : points)
    EXPECT_NEAR(p.get_u(), 150.5, 1e-9);
  // One point per row (the columns inside the stripe run from border to border: truncated, rejected).
  EXPECT_EQ(points.size(), 200u);
}

TEST(LaserConicDetector, EmptyImageGivesNoPoint)
{
  vpLaserConicDetector detector;
  vpImage<vpRGBa> empty;
  EXPECT_TRUE(detector.detect(empty).empty());
  EXPECT_EQ(detector.getMask().getSize(), 0u);
}

TEST(LaserConicDetector, BadSettingsThrow)
{
  vpLaserConicDetector detector;
  EXPECT_THROW(detector.setHueRange(-1, 170), vpException);
  EXPECT_THROW(detector.setHueRange(10, 180), vpException);
  EXPECT_THROW(detector.setMinSaturationValue(256, 80), vpException);
  EXPECT_THROW(detector.setMinSaturationValue(80, -1), vpException);
  EXPECT_THROW(detector.setMaxStripeWidth(0), vpException);
  EXPECT_THROW(detector.setSamplingStep(0), vpException);
}
