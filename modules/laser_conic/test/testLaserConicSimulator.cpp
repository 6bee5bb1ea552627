/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpLaserConicSimulator: exact trace geometry (checked against the implicit cone/plane conic,
// not against the simulator's own ray casting), noise and outlier statistics, rendering, input validation.
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>

#include "laser_sim_test_utils.h"

using namespace laser_sim_test;

namespace
{
// Angle between the cone axis and the ray from the apex to the back-projection of p on the plane.
double coneAngleOf(const vpImagePoint &p, const vpCameraParameters &cam, const vpHomogeneousMatrix &cMl,
                   const vpPlane &plane)
{
  double x = 0.0, y = 0.0;
  vpPixelMeterConversion::convertPoint(cam, p, x, y);
  const Eigen::Vector3d ray(x, y, 1.0), n(plane.getA(), plane.getB(), plane.getC());
  const Eigen::Vector3d P = ray * (-plane.getD() / n.dot(ray));
  const Eigen::Vector3d t(cMl[0][3], cMl[1][3], cMl[2][3]), axis(cMl[0][2], cMl[1][2], cMl[2][2]);
  return std::acos(std::max(-1.0, std::min(1.0, axis.dot((P - t).normalized()))));
}
} // namespace

TEST(LaserConicSimulator, CopiesRenderTheSameImages)
{
  // Copies and assignments with and without a ground texture (an empty one must not be copied: ViSP 3.5
  // would memcpy from a null pointer, which the sanitizer build reports).
  vpLaserConicSimulator plain = makeSimulator(groundPose());
  vpLaserConicSimulator textured = makeSimulator(groundPose());
  textured.setGroundTexture(vpImage<vpRGBa>(16, 16, vpRGBa(180, 140, 60, 255)), 0.05, -0.4, -0.4);
  vpLaserConicSimulator plainCopy(plain), texturedCopy(textured), assigned = textured;
  assigned = plain; // drops the texture
  vpImage<vpRGBa> a, b, c, d, e;
  plain.render(a);
  plainCopy.render(b);
  assigned.render(c);
  textured.render(d);
  texturedCopy.render(e);
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(a == c);
  EXPECT_TRUE(d == e);
  EXPECT_FALSE(a == d); // the texture shows
}

TEST(LaserConicSimulator, GroundPlaneFacesTheCamera)
{
  for (double flip : {0.0, M_PI}) {
    const vpHomogeneousMatrix cMg = groundPose() * vpHomogeneousMatrix(0, 0, 0, flip, 0, 0);
    vpLaserConicSimulator sim = makeSimulator(cMg);
    const vpPlane plane = sim.getGroundPlane();
    const double norm =
        std::sqrt(plane.getA() * plane.getA() + plane.getB() * plane.getB() + plane.getC() * plane.getC());
    EXPECT_NEAR(norm, 1.0, 1e-12);
    EXPECT_GT(plane.getD(), 0.0); // camera centre on the positive side: n.0 + D > 0
    // The ground origin and a point of the ground X axis lie on the plane.
    for (double X : {0.0, 0.5}) {
      const double px = cMg[0][0] * X + cMg[0][3], py = cMg[1][0] * X + cMg[1][3], pz = cMg[2][0] * X + cMg[2][3];
      EXPECT_NEAR(plane.getA() * px + plane.getB() * py + plane.getC() * pz + plane.getD(), 0.0, 1e-12);
    }
  }
}

TEST(LaserConicSimulator, TracePointsLieOnTheTrueConic)
{
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> tilt(-25.0, 25.0), height(0.5, 2.0), shift(-0.3, 0.3);
  double worstPixel = 0.0, worstAngle = 0.0;
  size_t total = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const vpHomogeneousMatrix cMg(shift(rng), shift(rng), height(rng), vpMath::rad(tilt(rng)), vpMath::rad(tilt(rng)),
                                  vpMath::rad(tilt(rng)));
    vpLaserConicSimulator sim = makeSimulator(cMg);
    const std::vector<vpImagePoint> points = sim.tracePoints(360);
    const vpPlane plane = sim.getGroundPlane();
    const Eigen::Matrix3d C = pixelConic(camera(), kOpening, laserPose(), plane);
    for (const vpImagePoint &p : points) {
      EXPECT_GE(p.get_u(), 0.0);
      EXPECT_GE(p.get_v(), 0.0);
      EXPECT_LE(p.get_u(), kWidth - 1.0);
      EXPECT_LE(p.get_v(), kHeight - 1.0);
      worstPixel = std::max(worstPixel, sampsonDistance(C, p));
      worstAngle = std::max(worstAngle, std::fabs(coneAngleOf(p, camera(), laserPose(), plane) - 0.5 * kOpening));
    }
    total += points.size();
  }
  EXPECT_GT(total, 50u * 100u); // most of each trace is in the image for these poses
  // Exact data: only double rounding on coordinates of ~1e3 px separates the points from the conic.
  EXPECT_LT(worstPixel, 1e-8);
  EXPECT_LT(worstAngle, 1e-9);
  std::cout << "worst distance to the true conic " << worstPixel << " px, worst cone angle error " << worstAngle
            << " rad" << std::endl;
}

TEST(LaserConicSimulator, WholeTraceInsideImageGivesEveryRay)
{
  vpLaserConicSimulator sim = makeSimulator();
  EXPECT_EQ(sim.tracePoints(500).size(), 500u);
  EXPECT_TRUE(sim.tracePoints(0).empty());
}

TEST(LaserConicSimulator, OnlyTheForwardNappeIsLit)
{
  // Laser pointing away from the ground: the backward half of the cone would cut the ground, but emits no light.
  vpLaserConicSimulator sim = makeSimulator();
  sim.setLaser(kOpening, laserPose() * vpHomogeneousMatrix(0, 0, 0, M_PI, 0, 0));
  EXPECT_TRUE(sim.tracePoints(360).empty());
}

TEST(LaserConicSimulator, RoughnessMovesPointsOffTheConicReproducibly)
{
  vpLaserConicSimulator sim = makeSimulator();
  const Eigen::Matrix3d C = pixelConic(camera(), kOpening, laserPose(), sim.getGroundPlane());
  const std::vector<vpImagePoint> rough = sim.tracePoints(2000, 0.01);
  ASSERT_EQ(rough.size(), 2000u);
  double meanDistance = 0.0;
  for (const vpImagePoint &p : rough)
    meanDistance += sampsonDistance(C, p) / rough.size();
  // 1 cm of normal offset at 1 m moves a point by up to ~15 px (f = 1500) along the image of the normal, a
  // fraction of it across the curve: a mean of a few pixels, certainly between 0.3 and 15 px.
  EXPECT_GT(meanDistance, 0.3);
  EXPECT_LT(meanDistance, 15.0);
  vpLaserConicSimulator again = makeSimulator();
  const std::vector<vpImagePoint> rough2 = again.tracePoints(2000, 0.01);
  for (size_t i = 0; i < rough.size(); ++i)
    EXPECT_EQ(rough[i], rough2[i]);
}

TEST(LaserConicSimulator, NoiseHasTheRequestedStatistics)
{
  vpLaserConicSimulator sim = makeSimulator();
  const std::vector<vpImagePoint> exact(20000, vpImagePoint(600, 800));
  const double sigma = 0.7;
  const std::vector<vpImagePoint> noisy = sim.addNoise(exact, sigma);
  double mean[2] = {0, 0}, var[2] = {0, 0};
  for (const vpImagePoint &p : noisy) {
    const double d[2] = {p.get_u() - 800.0, p.get_v() - 600.0};
    for (int k = 0; k < 2; ++k) {
      mean[k] += d[k] / noisy.size();
      var[k] += d[k] * d[k] / noisy.size();
    }
  }
  for (int k = 0; k < 2; ++k) {
    // Standard error of the mean sigma/sqrt(N) = 0.005 px: 5 standard errors.
    EXPECT_NEAR(mean[k], 0.0, 5.0 * sigma / std::sqrt(20000.0));
    // Relative standard error of the standard deviation 1/sqrt(2N) = 0.5 %: 3 % is 6 standard errors.
    EXPECT_NEAR(std::sqrt(var[k]) / sigma, 1.0, 0.03);
  }
  EXPECT_EQ(sim.addNoise(exact, 0.0), exact);
}

TEST(LaserConicSimulator, OutliersReplaceTheRequestedFraction)
{
  vpLaserConicSimulator sim = makeSimulator();
  const std::vector<vpImagePoint> inliers = sim.tracePoints(1000);
  ASSERT_EQ(inliers.size(), 1000u);
  std::vector<bool> isOutlier;
  const std::vector<vpImagePoint> mixed = sim.addOutliers(inliers, 0.3, &isOutlier);
  ASSERT_EQ(mixed.size(), 1000u);
  ASSERT_EQ(isOutlier.size(), 1000u);
  EXPECT_EQ(std::count(isOutlier.begin(), isOutlier.end(), true), 300);

  std::set<std::pair<double, double> > original;
  for (const vpImagePoint &p : inliers)
    original.insert(std::make_pair(p.get_u(), p.get_v()));
  double meanU = 0.0, meanV = 0.0;
  size_t inOrder = 0;
  for (size_t i = 0; i < mixed.size(); ++i) {
    const bool known = original.count(std::make_pair(mixed[i].get_u(), mixed[i].get_v())) > 0;
    EXPECT_EQ(known, !isOutlier[i]); // inliers untouched, outliers new (a uniform draw hits a trace point w.p. 0)
    EXPECT_GE(mixed[i].get_u(), 0.0);
    EXPECT_LE(mixed[i].get_u(), kWidth - 1.0);
    EXPECT_GE(mixed[i].get_v(), 0.0);
    EXPECT_LE(mixed[i].get_v(), kHeight - 1.0);
    if (isOutlier[i]) {
      meanU += mixed[i].get_u() / 300.0;
      meanV += mixed[i].get_v() / 300.0;
    }
    if (mixed[i] == inliers[i])
      ++inOrder;
  }
  // Uniform outliers: mean (W-1)/2 with standard error (W-1)/sqrt(12 * 300); 4 standard errors.
  EXPECT_NEAR(meanU, (kWidth - 1) / 2.0, 4.0 * (kWidth - 1) / std::sqrt(12.0 * 300.0));
  EXPECT_NEAR(meanV, (kHeight - 1) / 2.0, 4.0 * (kHeight - 1) / std::sqrt(12.0 * 300.0));
  EXPECT_LT(inOrder, 50u); // shuffled: a random permutation keeps about one point in place

  std::vector<bool> flags;
  EXPECT_EQ(sim.addOutliers(inliers, 0.0, &flags).size(), 1000u);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), true), 0);
  sim.addOutliers(inliers, 1.0, &flags);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), true), 1000);
  EXPECT_THROW(sim.addOutliers(inliers, 1.5), vpException);
  EXPECT_THROW(sim.addOutliers(inliers, -0.1), vpException);
}

TEST(LaserConicSimulator, SameSeedSameDraws)
{
  vpLaserConicSimulator a = makeSimulator(groundPose(), 3), b = makeSimulator(groundPose(), 3),
                        c = makeSimulator(groundPose(), 4);
  const std::vector<vpImagePoint> pts = a.tracePoints(100);
  EXPECT_EQ(a.addNoise(pts, 1.0), b.addNoise(pts, 1.0));
  EXPECT_NE(b.addNoise(pts, 1.0), c.addNoise(pts, 1.0));
}

TEST(LaserConicSimulator, RenderedStripeFollowsTheTrace)
{
  vpLaserConicSimulator sim = makeSimulator();
  const double stripeWidth = 3.0;
  vpImage<vpRGBa> I;
  const auto start = std::chrono::steady_clock::now();
  sim.render(I, vpImage<vpRGBa>(), stripeWidth, 2.0);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::cout << "render 1600x1200: " << ms << " ms" << std::endl;
  ASSERT_EQ(I.getWidth(), kWidth);
  ASSERT_EQ(I.getHeight(), kHeight);

  auto isRed = [](const vpRGBa &c) { return c.R > 150 && c.R > c.G + 80 && c.R > c.B + 80; };
  // Every exact trace point falls on a red pixel.
  const std::vector<vpImagePoint> trace = sim.tracePoints(2000);
  size_t redOnTrace = 0;
  for (const vpImagePoint &p : trace)
    if (isRed(I[static_cast<unsigned int>(std::lround(p.get_v()))][static_cast<unsigned int>(std::lround(p.get_u()))]))
      ++redOnTrace;
  EXPECT_EQ(redOnTrace, trace.size());

  // No red pixel away from the trace: the profile at 2.5 FWHM is exp(-4 ln2 * 6.25) ~ 3e-8 of the peak.
  const Eigen::Matrix3d C = pixelConic(camera(), kOpening, laserPose(), sim.getGroundPlane());
  size_t red = 0;
  double farthest = 0.0;
  for (unsigned int i = 0; i < I.getHeight(); ++i)
    for (unsigned int j = 0; j < I.getWidth(); ++j)
      if (isRed(I[i][j])) {
        ++red;
        farthest = std::max(farthest, sampsonDistance(C, vpImagePoint(i, j)));
      }
  EXPECT_GT(red, trace.size()); // a stripe a few pixels wide along a curve longer than 2000 px
  EXPECT_LT(farthest, 2.5 * stripeWidth);
  std::cout << red << " red pixels, farthest " << farthest << " px from the trace" << std::endl;

  // The ground is dark and textured: not uniform, and no pixel far from the trace is bright.
  std::set<int> greys;
  for (unsigned int j = 0; j < 200; ++j)
    greys.insert(I[50][j].G);
  EXPECT_GT(greys.size(), 10u);
}

TEST(LaserConicSimulator, RenderIsSeededAndUsesTheGivenTexture)
{
  vpLaserConicSimulator a = makeSimulator(), b = makeSimulator();
  vpImage<vpRGBa> Ia, Ib;
  a.render(Ia);
  b.render(Ib);
  EXPECT_TRUE(Ia == Ib);

  // A uniform green texture without noise: the ground is that green everywhere but on the stripe.
  vpImage<vpRGBa> green(64, 64, vpRGBa(0, 90, 0, 255));
  vpLaserConicSimulator c = makeSimulator();
  vpImage<vpRGBa> Ic;
  c.render(Ic, green, 3.0, 0.0);
  EXPECT_EQ(Ic[5][5].G, 90);
  EXPECT_EQ(Ic[5][5].R, 0);
}

TEST(LaserConicSimulator, RendersAnOpenTraceUpToTheHorizon)
{
  // Optical axis and cone axis parallel to the ground, 0.3 m above it: the horizon is the middle row and
  // the trace is a hyperbola branch whose image runs up to a vanishing point on the horizon.
  const vpHomogeneousMatrix cMg(0, 0.3, 0, vpMath::rad(-90), 0, 0);
  vpLaserConicSimulator sim;
  sim.setCamera(camera(), kWidth, kHeight);
  sim.setLaser(kOpening, vpHomogeneousMatrix(0.05, 0, 0, 0, 0, 0));
  sim.setGroundPose(cMg);
  sim.setSeed(8);
  vpImage<vpRGBa> I;
  sim.render(I, vpImage<vpRGBa>(), 3.0, 0.0);

  auto isRed = [](const vpRGBa &c) { return c.R > 150 && c.R > c.G + 80 && c.R > c.B + 80; };
  const std::vector<vpImagePoint> trace = sim.tracePoints(4000);
  ASSERT_GT(trace.size(), 100u);
  size_t onRed = 0;
  for (const vpImagePoint &p : trace) {
    EXPECT_GT(p.get_v(), 600.0 - 1e-6); // below the horizon
    if (isRed(I[static_cast<unsigned int>(std::lround(p.get_v()))][static_cast<unsigned int>(std::lround(p.get_u()))]))
      ++onRed;
  }
  EXPECT_EQ(onRed, trace.size());
  // The sky (above the horizon) is the plain far grey, no laser.
  for (unsigned int j = 0; j < kWidth; j += 50) {
    EXPECT_EQ(I[100][j].R, 20);
    EXPECT_EQ(I[100][j].G, 20);
  }
}

TEST(LaserConicSimulator, BadSettingsThrow)
{
  vpLaserConicSimulator unset;
  vpImage<vpRGBa> I;
  EXPECT_THROW(unset.tracePoints(10), vpException);
  EXPECT_THROW(unset.render(I), vpException);
  EXPECT_THROW(unset.addOutliers(std::vector<vpImagePoint>(3), 0.5), vpException);

  vpLaserConicSimulator sim = makeSimulator();
  EXPECT_THROW(sim.setCamera(vpCameraParameters(0.0, 1500, 800, 600), kWidth, kHeight), vpException);
  EXPECT_THROW(sim.setCamera(camera(), 0, kHeight), vpException);
  EXPECT_THROW(sim.setLaser(0.0, laserPose()), vpLaserConicException);
  EXPECT_THROW(sim.setLaser(M_PI, laserPose()), vpLaserConicException);
  EXPECT_THROW(sim.setLaser(std::numeric_limits<double>::quiet_NaN(), laserPose()), vpLaserConicException);
  vpHomogeneousMatrix nan = laserPose();
  nan[0][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(sim.setLaser(kOpening, nan), vpLaserConicException);
  EXPECT_THROW(sim.setGroundPose(nan), vpLaserConicException);
  // Camera centre on the ground plane (ground plane through the optical centre).
  EXPECT_THROW(sim.setGroundPose(vpHomogeneousMatrix(0.3, 0, 0, vpMath::rad(90), 0, 0)), vpLaserConicException);
  EXPECT_THROW(sim.tracePoints(10, -1.0), vpException);
  EXPECT_THROW(sim.addNoise(std::vector<vpImagePoint>(3), -1.0), vpException);
  EXPECT_THROW(sim.render(I, vpImage<vpRGBa>(), 0.0), vpException);
  EXPECT_THROW(sim.render(I, vpImage<vpRGBa>(), 3.0, -1.0), vpException);
  // A failed setter leaves the simulator usable.
  EXPECT_EQ(sim.tracePoints(100).size(), 100u);
}

namespace
{
//! Pixel of a ground point (frame g) through the exact inverse of the camera's pixel-to-metre model.
vpImagePoint groundPixel(const vpCameraParameters &cam, const vpHomogeneousMatrix &cMg, double X, double Y)
{
  const vpColVector P = cMg * vpColVector({X, Y, 0.0, 1.0});
  return laser_test::exactPixel(cam, P[0] / P[2], P[1] / P[2]);
}

const vpRGBa &at(const vpImage<vpRGBa> &I, const vpImagePoint &p)
{
  return I[static_cast<unsigned int>(std::lround(p.get_v()))][static_cast<unsigned int>(std::lround(p.get_u()))];
}
} // namespace

TEST(LaserConicSimulator, FitInverseDistortionInvertsTheModel)
{
  const vpCameraParameters cam = wideCamera();
  EXPECT_LT(cam.get_kud(), 0.0); // barrel kdu > 0 is undone by kud < 0
  // Round trip meter -> pixel (kud) -> meter (kdu) over the image: a fitted inverse, not an exact one.
  double worst = 0.0;
  for (double x = -0.7; x <= 0.7; x += 0.05)
    for (double y = -0.55; y <= 0.55; y += 0.05) {
      double u = 0.0, v = 0.0, x2 = 0.0, y2 = 0.0;
      vpMeterPixelConversion::convertPoint(cam, x, y, u, v);
      if (u < 0 || v < 0 || u > kWidth - 1 || v > kHeight - 1)
        continue;
      vpPixelMeterConversion::convertPoint(cam, u, v, x2, y2);
      worst = std::max(worst, std::hypot(x2 - x, y2 - y) * cam.get_px());
    }
  std::cout << "kud " << cam.get_kud() << ", fitted kdu " << cam.get_kdu() << ": worst round trip " << worst << " px"
            << std::endl;
  // The single-coefficient models are not inverses of each other: several pixels in the corners.
  EXPECT_LT(worst, 15.0);
  EXPECT_GT(worst, 0.5);
}

TEST(LaserConicSimulator, DistortedTracePointsConvertExactlyToTheTrueTrace)
{
  // With distortion, vpPixelMeterConversion maps each trace pixel onto the normalized point of the true
  // trace: its ray meets the plane on the laser cone (cone angle = half opening angle to rounding).
  vpLaserConicSimulator sim = makeSimulator();
  sim.setCamera(wideCamera(), kWidth, kHeight);
  const std::vector<vpImagePoint> points = sim.tracePoints(720);
  ASSERT_GT(points.size(), 600u);
  double worst = 0.0;
  for (const vpImagePoint &p : points)
    worst =
        std::max(worst, std::fabs(coneAngleOf(p, wideCamera(), laserPose(), sim.getGroundPlane()) - 0.5 * kOpening));
  EXPECT_LT(worst, 1e-12);
}

TEST(LaserConicSimulator, DistortedRenderFollowsTheDistortedTrace)
{
  vpLaserConicSimulator sim =
      makeSimulator(vpHomogeneousMatrix(0.05, -0.03, 0.9, vpMath::rad(10), vpMath::rad(-8), 0.3));
  sim.setCamera(wideCamera(), kWidth, kHeight);
  vpImage<vpRGBa> I;
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.noise = 0.0;
  sim.render(I, settings);
  auto isRed = [](const vpRGBa &c) { return c.R > 150 && c.R > c.G + 80 && c.R > c.B + 80; };
  const std::vector<vpImagePoint> trace = sim.tracePoints(2000);
  ASSERT_GT(trace.size(), 1500u);
  size_t onRed = 0;
  for (const vpImagePoint &p : trace)
    onRed += isRed(at(I, p)) ? 1 : 0;
  EXPECT_EQ(onRed, trace.size());
  // The undistorted trace is elsewhere: a distortion-free render would miss the distorted points.
  vpLaserConicSimulator pinhole =
      makeSimulator(vpHomogeneousMatrix(0.05, -0.03, 0.9, vpMath::rad(10), vpMath::rad(-8), 0.3));
  pinhole.setCamera(vpCameraParameters(1000.0, 1000.0, 805.0, 596.0), kWidth, kHeight);
  vpImage<vpRGBa> J;
  pinhole.render(J, settings);
  size_t onRedPinhole = 0;
  for (const vpImagePoint &p : trace)
    onRedPinhole += isRed(at(J, p)) ? 1 : 0;
  EXPECT_LT(onRedPinhole, trace.size() / 2);
}

TEST(LaserConicSimulator, ChessboardAndTextureLieAtTheirGroundCoordinates)
{
  const vpCameraParameters cam = wideCamera();
  const vpHomogeneousMatrix cMg(-0.12, -0.08, 0.7, vpMath::rad(15), vpMath::rad(-10), 0.4);
  vpLaserConicSimulator sim = makeSimulator(cMg);
  sim.setCamera(cam, kWidth, kHeight);
  const double s = 0.03;
  sim.setGroundChessboard(9, 6, s);
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.noise = 0.0;
  settings.laserOn = false;
  vpImage<vpRGBa> I;
  sim.render(I, settings);
  dumpIfRequested("sim_chessboard", I);
  // Centre of each square: black when (kx + ky) is even.
  for (unsigned int kx = 0; kx < 9; ++kx)
    for (unsigned int ky = 0; ky < 6; ++ky) {
      const vpRGBa &c = at(I, groundPixel(cam, cMg, (kx + 0.5) * s, (ky + 0.5) * s));
      if ((kx + ky) % 2 == 0)
        EXPECT_LT(c.G, 40) << kx << " " << ky;
      else
        EXPECT_GT(c.G, 200) << kx << " " << ky;
    }
  // Around an inner corner, 1 mm inside each quadrant: the anti-aliased edge is at the true corner within
  // a fraction of a pixel (1 mm is about 1.4 px here), so each quadrant already has its colour.
  for (unsigned int kx = 1; kx < 9; ++kx)
    for (unsigned int ky = 1; ky < 6; ++ky)
      for (int q = 0; q < 4; ++q) {
        const double dx = (q & 1) ? 0.0015 : -0.0015, dy = (q & 2) ? 0.0015 : -0.0015;
        const bool black = ((kx - (dx < 0 ? 1 : 0)) + (ky - (dy < 0 ? 1 : 0))) % 2 == 0;
        const vpRGBa &c = at(I, groundPixel(cam, cMg, kx * s + dx, ky * s + dy));
        if (black)
          EXPECT_LT(c.G, 122) << kx << " " << ky << " " << q;
        else
          EXPECT_GT(c.G, 122) << kx << " " << ky << " " << q;
      }

  // A 2 x 2 texture of 5 cm texels at (0.3, 0.1): each texel centre shows its colour.
  vpImage<vpRGBa> texture(2, 2);
  texture[0][0] = vpRGBa(0, 0, 200, 255);
  texture[0][1] = vpRGBa(0, 200, 0, 255);
  texture[1][0] = vpRGBa(200, 200, 0, 255);
  texture[1][1] = vpRGBa(0, 200, 200, 255);
  sim.setGroundChessboard(0, 0, 0.0);
  sim.setGroundTexture(texture, 0.05, -0.3, 0.1);
  sim.render(I, settings);
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j) {
      const vpRGBa &c = at(I, groundPixel(cam, cMg, -0.3 + (j + 0.25) * 0.05 + 0.0125, 0.1 + (i + 0.5) * 0.05));
      EXPECT_NEAR(c.R, texture[i][j].R, 30) << i << j;
      EXPECT_NEAR(c.G, texture[i][j].G, 30) << i << j;
      EXPECT_NEAR(c.B, texture[i][j].B, 30) << i << j;
    }
  EXPECT_THROW(sim.setGroundTexture(texture, 0.0), vpLaserConicException);
  EXPECT_THROW(sim.setGroundChessboard(3, 0, 0.03), vpLaserConicException);
}

TEST(LaserConicSimulator, HardSettingsRenderWhatTheyDescribe)
{
  vpLaserConicSimulator sim = makeSimulator();
  const std::vector<vpImagePoint> trace = sim.tracePoints(500);
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.noise = 0.0;
  vpImage<vpRGBa> I;

  // A saturating stripe: white core on the curve.
  settings.laserPower = 1400.0;
  settings.whiteCore = 0.6;
  settings.bloom = 0.05;
  sim.render(I, settings);
  dumpIfRequested("sim_saturated", I);
  size_t white = 0;
  for (const vpImagePoint &p : trace) {
    const vpRGBa &c = at(I, p);
    white += (c.R == 255 && c.G > 240 && c.B > 240) ? 1 : 0;
  }
  EXPECT_GT(white, trace.size() * 9 / 10);

  // A dim stripe: red dominant but dark (V 45-110 as in real photographs).
  settings.laserPower = 70.0;
  settings.whiteCore = 0.0;
  settings.bloom = 0.0;
  sim.render(I, settings);
  dumpIfRequested("sim_dim", I);
  for (const vpImagePoint &p : trace) {
    const vpRGBa &c = at(I, p);
    EXPECT_LT(c.R, 150);
    EXPECT_GT(c.R, c.G + 30);
  }

  // No laser: no red at all on the dark floor; occluders hide the floor.
  settings.laserOn = false;
  settings.occluders.push_back(
      {vpImagePoint(0, 0), vpImagePoint(0, 100), vpImagePoint(100, 100), vpImagePoint(100, 0)});
  sim.render(I, settings);
  for (const vpImagePoint &p : trace)
    EXPECT_LT(at(I, p).R, at(I, p).G + 20);
  EXPECT_EQ(I[50][50].R, settings.occluderColour.R);

  // A red disc at the ground origin is red in the image.
  settings.occluders.clear();
  const vpLaserConicSimulator::vpDistractor disc = vpLaserConicSimulator::vpDistractor::disc(-0.05, 0.03, 0.1);
  settings.distractors.push_back(disc);
  sim.render(I, settings);
  const vpRGBa &c = at(I, groundPixel(camera(), groundPose(), disc.x, disc.y));
  EXPECT_EQ(c.R, disc.colour.R);
  EXPECT_EQ(c.G, disc.colour.G);

  // Settings out of range.
  settings.ambient = -1.0;
  EXPECT_THROW(sim.render(I, settings), vpLaserConicException);
  settings.ambient = 1.0;
  settings.bloomWidth = 0.0;
  EXPECT_THROW(sim.render(I, settings), vpLaserConicException);
}

TEST(LaserConicSimulator, EveryEstimatorRecoversTheExactPlaneFromDistortedTracePoints)
{
  // The simulator's distorted pixels and the estimators' vpPixelMeterConversion are the same lens model:
  // exact points give the exact plane (to rounding) for every method.
  for (const vpHomogeneousMatrix &cMg :
       {groundPose(), vpHomogeneousMatrix(-0.1, 0.05, 0.7, vpMath::rad(-15), vpMath::rad(12), 1.0)}) {
    vpLaserConicSimulator sim = makeSimulator(cMg);
    sim.setCamera(wideCamera(), kWidth, kHeight);
    const std::vector<vpImagePoint> points = sim.tracePoints(400);
    ASSERT_GT(points.size(), 300u);
    const vpPlane truth = sim.getGroundPlane();
    for (vpLaserConicPose::vpLaserConicMethod method :
         {vpLaserConicPose::GP3, vpLaserConicPose::PP3, vpLaserConicPose::PP5, vpLaserConicPose::PLANE_PAIR}) {
      vpLaserConicPose estimator;
      estimator.setCameraParameters(wideCamera());
      estimator.setLaser(kOpening, laserPose());
      estimator.setRansacSeed(1);
      vpPlane plane;
      ASSERT_TRUE(estimator.computePlane(points, method, plane)) << method;
      const double dot = plane.getA() * truth.getA() + plane.getB() * truth.getB() + plane.getC() * truth.getC();
      EXPECT_NEAR(dot, 1.0, 1e-9) << method;
      EXPECT_NEAR(plane.getD(), truth.getD(), 1e-9) << method;
    }
  }
}
