/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file testLaserConicSelfCalibration.cpp
  \brief Self-calibration from ground frames against the simulator's ground truth: accuracy from a
  flight with +-15 degrees of roll and pitch (distorted lens, 0.5 px noise), GP-3 errors after it,
  the scale constraint, observability refusals, outliers, frame selection and bad input.
*/
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <utility>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/laser_conic/vpLaserConicCalibration.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>

#include "laser_flight_test_utils.h"

namespace
{
using namespace laser_flight_test;

//! The initial guess: the true laser with its axis off by about 1 degree and the apex off by 5 mm.
vpHomogeneousMatrix roughGuess()
{
  return laserPose() * vpHomogeneousMatrix(0.004, -0.003, 0.0, vpMath::rad(0.7), vpMath::rad(-0.7), 0.0);
}

vpLaserConicSelfCalibration makeSelfCal(const std::vector<Frame> &frames, double apexDistance)
{
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(camera());
  selfcal.setLaser(kOpening, roughGuess());
  if (apexDistance > 0.0)
    selfcal.setApexDistance(apexDistance);
  for (const Frame &f : frames)
    selfcal.addFrame(f.points);
  return selfcal;
}

//! Frames of the flight \e s re-drawn with \e frames frames of 300 points: new frames to run GP3 on.
std::vector<Frame> testFrames(FlightSettings s, unsigned int frames, unsigned int seed)
{
  s.frames = frames;
  s.points = 300;
  return flight(s, seed);
}

double trueApexDistance() { return laserPose().getTranslationVector().frobeniusNorm(); }

//! Indices of the lowest and of the highest frame: the two known altitudes of the two-length protocol.
std::pair<size_t, size_t> altitudeExtremes(const std::vector<Frame> &frames)
{
  size_t lo = 0, hi = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    lo = frames[k].altitude < frames[lo].altitude ? k : lo;
    hi = frames[k].altitude > frames[hi].altitude ? k : hi;
  }
  return std::make_pair(lo, hi);
}

//! RMS altitude (m) and attitude (rad) errors of GP3 on \e frames with the laser (A, cMl).
void gp3Errors(const std::vector<Frame> &frames, double A, const vpHomogeneousMatrix &cMl, double &altitudeRms,
               double &attitudeRms, double *altitudeRatio = nullptr)
{
  vpLaserConicPose estimator;
  estimator.setCameraParameters(camera());
  estimator.setLaser(A, cMl);
  double sa = 0.0, st = 0.0, ratio = 0.0;
  unsigned int n = 0;
  for (const Frame &f : frames) {
    vpPlane plane;
    if (!estimator.computePlane(f.points, vpLaserConicPose::GP3, plane))
      continue;
    double h, r, p;
    vpLaserConicPose::computeAltitudeRollPitch(f.truth, h, r, p);
    sa += vpMath::sqr(estimator.getAltitude() - h);
    st += vpMath::sqr(estimator.getRoll() - r) + vpMath::sqr(estimator.getPitch() - p);
    ratio += estimator.getAltitude() / h;
    ++n;
  }
  ASSERT_GT(n, frames.size() * 9 / 10);
  altitudeRms = std::sqrt(sa / n);
  attitudeRms = std::sqrt(st / (2 * n));
  if (altitudeRatio)
    *altitudeRatio = ratio / n;
}

//! Self-calibration of \e frames with the scale from known altitudes: of frame 0 (one length), or of the lowest
//! and the highest frames (two lengths: the protocol that fixes the family of cones, see the class description).
vpLaserConicSelfCalibration knownAltitudeSelfCal(const std::vector<Frame> &frames, bool twoLengths)
{
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, 0.0);
  if (twoLengths) {
    const std::pair<size_t, size_t> range = altitudeExtremes(frames);
    selfcal.setKnownAltitude(static_cast<unsigned int>(range.first), frames[range.first].truth.getD());
    selfcal.setKnownAltitude(static_cast<unsigned int>(range.second), frames[range.second].truth.getD());
  } else {
    selfcal.setKnownAltitude(0, frames[0].truth.getD());
  }
  return selfcal;
}

//! GP3 altitudes of \e frames with the laser (A, cMl), NaN where GP3 finds no plane.
std::vector<double> gp3Altitudes(const std::vector<Frame> &frames, double A, const vpHomogeneousMatrix &cMl)
{
  vpLaserConicPose estimator;
  estimator.setCameraParameters(camera());
  estimator.setLaser(A, cMl);
  std::vector<double> h(frames.size(), std::numeric_limits<double>::quiet_NaN());
  vpPlane plane;
  for (size_t i = 0; i < frames.size(); ++i)
    if (estimator.computePlane(frames[i].points, vpLaserConicPose::GP3, plane))
      h[i] = estimator.getAltitude();
  return h;
}

/*!
  RMS altitude error (m) that the calibration covariance \e C (alpha, beta, apex, A: getCovarianceMatrix())
  predicts for GP3 on the noise-free frames \e clean: sqrt(mean g^T C g), g the derivative of GP3's altitude
  with respect to the laser parameters at the truth (central differences).
*/
double predictedCalibrationAltitude(const std::vector<Frame> &clean, const vpMatrix &C)
{
  const vpColVector z = laserPose().getRotationMatrix().getCol(2);
  const vpTranslationVector t = laserPose().getTranslationVector();
  const double p0[6] = {std::atan2(-z[1], z[2]), std::asin(z[0]), t[0], t[1], t[2], kOpening};
  std::vector<vpColVector> g(clean.size(), vpColVector(6, 0.0));
  for (unsigned int k = 0; k < 6; ++k) {
    const double step = (k < 2 || k == 5) ? 1e-5 : 1e-6;
    std::vector<double> side[2];
    for (int sgn = 0; sgn < 2; ++sgn) {
      double p[6];
      std::copy(p0, p0 + 6, p);
      p[k] += sgn ? -step : step;
      const vpRotationMatrix R =
          vpRotationMatrix(vpRxyzVector(p[0], 0, 0)) * vpRotationMatrix(vpRxyzVector(0, p[1], 0));
      side[sgn] = gp3Altitudes(clean, p[5], vpHomogeneousMatrix(vpTranslationVector(p[2], p[3], p[4]), R));
    }
    for (size_t i = 0; i < clean.size(); ++i)
      g[i][k] = (side[0][i] - side[1][i]) / (2.0 * step);
  }
  double sum = 0.0;
  unsigned int n = 0;
  for (const vpColVector &gi : g) {
    const double v = vpColVector::dotProd(gi, C * gi);
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  }
  return std::sqrt(sum / n);
}

//! New frames of a flight to run GP3 on after a calibration: noisy (60, 300 points) with GP3's errors under the
//! true laser, and noise-free (30) for the propagation of a calibration covariance.
struct Gp3Reference
{
  std::vector<Frame> test, clean;
  double altitudeRms = 0.0, attitudeRms = 0.0;
};

void gp3Reference(const FlightSettings &s, Gp3Reference &ref)
{
  ref.test = testFrames(s, 60, 12);
  FlightSettings clean = s;
  clean.noise = 0.0;
  ref.clean = testFrames(clean, 30, 12);
  gp3Errors(ref.test, kOpening, laserPose(), ref.altitudeRms, ref.attitudeRms);
}
} // namespace

// The figures of the requirement: 20 frames, roll/pitch +-15 deg, 1000 points, 0.5 px, distorted lens, one
// length (a known altitude). The computed standard deviation (first order: the Cramer-Rao bound of the
// protocol, 0.07-0.08 deg) is what the protocol allows. Over 30 flights (seeds 1001-1030) the RMS axis error was
// 1.16 times it (0.088 deg): along the family of cones the problem is nonlinear (the angle is stationary in the
// axis tilt near phi = 90 deg), the errors have heavier tails than the first order says; 24 of the 30 were within
// 0.1 deg. Hence the bound: 3 standard deviations of the actual spread, 3.5 computed ones.
TEST(LaserConicSelfCalibration, RecoversTheLaserFromTwentyTiltedFrames)
{
  FlightSettings s;
  double worstAxis = 0.0, worstApex = 0.0;
  unsigned int within = 0;
  const unsigned int flights = 5;
  for (unsigned int seed = 1; seed <= flights; ++seed) {
    const std::vector<Frame> frames = flight(s, seed);
    vpLaserConicSelfCalibration selfcal = knownAltitudeSelfCal(frames, false);
    vpHomogeneousMatrix cMl;
    double A = 0.0;
    ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusMessage(selfcal.getStatus()) << ": "
                                         << selfcal.getStatusDetails();
    const double axis = vpMath::deg(axisAngle(cMl, laserPose())),
                 apex = vpMath::deg(apexDirectionAngle(cMl, laserPose()));
    const double axisStd = vpMath::deg(selfcal.getAxisStdDeviation()),
                 apexStd = vpMath::deg(selfcal.getApexDirectionStdDeviation());
    std::cout << "seed " << seed << ": axis error " << axis << " deg (std " << axisStd << "), apex direction " << apex
              << " deg (std " << apexStd << "), RMS " << selfcal.getRmsPixels() << " px, condition "
              << selfcal.getConditionNumber() << std::endl;
    EXPECT_GT(axisStd, 0.04); // the bound of this protocol (see the class description): the 0.1 deg is not a
    EXPECT_LT(axisStd, 0.1);  // matter of the solver
    EXPECT_LT(apexStd, 0.12);
    EXPECT_DOUBLE_EQ(A, kOpening);                  // held: the images do not determine it
    EXPECT_NEAR(selfcal.getRmsPixels(), 0.5, 0.05); // Sampson distance: the noise across the trace
    EXPECT_LT(axis, 3.5 * axisStd);
    EXPECT_LT(apex, 3.5 * apexStd);
    within += axis < 0.1 ? 1 : 0;
    worstAxis = std::max(worstAxis, axis);
    worstApex = std::max(worstApex, apex);
  }
  std::cout << "one length: axis within 0.1 deg in " << within << " of " << flights << " flights; worst axis "
            << worstAxis << " deg, apex direction " << worstApex << " deg" << std::endl;
}

// Protocols that reach 0.1 deg at 3 standard deviations: a second length (known altitudes of the lowest and the
// highest frames, 0.5 m apart), or the same 20 frames over altitudes of 0.4-2.5 m with one length.
TEST(LaserConicSelfCalibration, AxisWithinATenthOfADegree)
{
  for (int protocol = 0; protocol < 2; ++protocol) {
    FlightSettings s;
    if (protocol == 1) {
      s.minAltitude = 0.4;
      s.maxAltitude = 2.5;
    }
    double worst = 0.0, worstStd = 0.0;
    for (unsigned int seed = 1; seed <= 4; ++seed) {
      const std::vector<Frame> frames = flight(s, seed);
      vpLaserConicSelfCalibration selfcal = knownAltitudeSelfCal(frames, protocol == 0);
      vpHomogeneousMatrix cMl;
      double A = 0.0;
      ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
      const double axis = vpMath::deg(axisAngle(cMl, laserPose())),
                   std3 = 3.0 * vpMath::deg(selfcal.getAxisStdDeviation());
      EXPECT_LT(std3, 0.1);
      EXPECT_LT(axis, std3);
      EXPECT_LT(vpMath::deg(apexDirectionAngle(cMl, laserPose())),
                3.0 * vpMath::deg(selfcal.getApexDirectionStdDeviation()));
      worst = std::max(worst, axis);
      worstStd = std::max(worstStd, std3 / 3.0);
    }
    std::cout << (protocol == 0 ? "two known altitudes" : "altitudes 0.4-2.5 m, one known") << ": worst axis error "
              << worst << " deg, largest std " << worstStd << " deg" << std::endl;
  }
}

// GP-3 on new frames after the self-calibration with one length, against GP-3 with the true laser and with the
// guess; the ratio agrees with the one the calibration covariance predicts.
TEST(LaserConicSelfCalibration, Gp3ErrorsAfterSelfCalibration)
{
  FlightSettings s;
  const std::vector<Frame> frames = flight(s, 11);
  Gp3Reference ref;
  gp3Reference(s, ref);
  const std::vector<Frame> &test = ref.test, &cleanTest = ref.clean;
  // Scale from one known altitude.
  vpLaserConicSelfCalibration selfcal = knownAltitudeSelfCal(frames, false);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  // Scale from the ruler (the true apex distance).
  vpLaserConicSelfCalibration ruler = makeSelfCal(frames, trueApexDistance());
  vpHomogeneousMatrix cMlRuler;
  double ARuler = 0.0;
  ASSERT_TRUE(ruler.compute(cMlRuler, ARuler)) << ruler.getStatusDetails();
  const double altTrue = ref.altitudeRms, attTrue = ref.attitudeRms;
  double altSelf, attSelf, altRuler, attRuler, altGuess, attGuess;
  gp3Errors(test, A, cMl, altSelf, attSelf);
  gp3Errors(test, ARuler, cMlRuler, altRuler, attRuler);
  gp3Errors(test, kOpening, roughGuess(), altGuess, attGuess);
  const double predSelf = predictedCalibrationAltitude(cleanTest, selfcal.getCovarianceMatrix()),
               predRuler = predictedCalibrationAltitude(cleanTest, ruler.getCovarianceMatrix());
  std::cout << "GP3 RMS errors: true laser " << 1000 * altTrue << " mm, " << vpMath::deg(attTrue)
            << " deg; self-calibrated, known altitude " << 1000 * altSelf << " mm (calibration part predicted "
            << 1000 * predSelf << " mm), " << vpMath::deg(attSelf) << " deg; self-calibrated, ruler " << 1000 * altRuler
            << " mm (predicted " << 1000 * predRuler << " mm), " << vpMath::deg(attRuler) << " deg; initial guess "
            << 1000 * altGuess << " mm, " << vpMath::deg(attGuess) << " deg" << std::endl;
  // One length leaves the family of cones fixed only by the held angle (see the class description): the
  // calibration part of the altitude error is several times GP-3's own noise, as the covariance predicts.
  EXPECT_GT(predSelf, 2.0 * altTrue);
  EXPECT_GT(predRuler, 10.0 * altTrue);
  EXPECT_LT(altSelf, 3.0 * std::hypot(altTrue, predSelf));
  EXPECT_LT(altRuler, 3.0 * std::hypot(altTrue, predRuler));
  EXPECT_LT(attSelf, 1.6 * attTrue);
  EXPECT_LT(attRuler, 1.6 * attTrue);
  EXPECT_GT(altGuess, 20.0 * altTrue); // the guess is bad enough for the test to mean something
}

// The protocol that meets 1.2x: 20 frames (+-15 deg, 0.8-1.3 m) with the altitudes of the lowest and the highest
// frame known. Over 4 flights, the RMS ratio of GP-3's altitude error to the true calibration's, and the ratio the
// calibration covariance predicts (the expected value), are within 1.2.
TEST(LaserConicSelfCalibration, Gp3WithinTwentyPercentWithTwoLengths)
{
  FlightSettings s;
  Gp3Reference ref;
  gp3Reference(s, ref);
  const std::vector<Frame> &test = ref.test, &cleanTest = ref.clean;
  const double altTrue = ref.altitudeRms, attTrue = ref.attitudeRms;
  double sumRatio2 = 0.0, sumPredicted2 = 0.0;
  const unsigned int flights = 4;
  for (unsigned int seed = 1; seed <= flights; ++seed) {
    const std::vector<Frame> frames = flight(s, 200 + seed);
    vpLaserConicSelfCalibration selfcal = knownAltitudeSelfCal(frames, true);
    vpHomogeneousMatrix cMl;
    double A = 0.0;
    ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
    double alt, att;
    gp3Errors(test, A, cMl, alt, att);
    const double predicted = predictedCalibrationAltitude(cleanTest, selfcal.getCovarianceMatrix());
    std::cout << "seed " << seed << ": GP3 altitude RMS " << 1000 * alt << " mm (true laser " << 1000 * altTrue
              << " mm, ratio " << alt / altTrue << "; predicted ratio " << std::hypot(1.0, predicted / altTrue)
              << "), attitude " << vpMath::deg(att) << " deg (true " << vpMath::deg(attTrue) << ")" << std::endl;
    EXPECT_LT(alt / altTrue, 1.35); // one flight: the calibration error is one draw
    EXPECT_LT(att, 1.2 * attTrue);
    sumRatio2 += vpMath::sqr(alt / altTrue);
    sumPredicted2 += 1.0 + vpMath::sqr(predicted / altTrue);
  }
  const double ratio = std::sqrt(sumRatio2 / flights), predicted = std::sqrt(sumPredicted2 / flights);
  std::cout << "two lengths: altitude RMS ratio " << ratio << " over " << flights << " flights (predicted " << predicted
            << ")" << std::endl;
  EXPECT_LT(ratio, 1.2);
  EXPECT_LT(predicted, 1.2);
}

// The same frames calibrated as chessboard views (the ground poses known, vpLaserConicCalibration) and by
// self-calibration (the planes unknown): the figures of the tutorial's comparison.
TEST(LaserConicSelfCalibration, ComparisonWithTheChessboardCalibration)
{
  FlightSettings s;
  s.points = 300; // the grid calibration's bundle adjustment has one unknown per point: kept fast
  const std::vector<Frame> frames = flight(s, 1);
  vpLaserConicCalibration grid;
  grid.setCameraParameters(camera());
  grid.setOpeningAngle(kOpening);
  grid.setOpeningAngleEstimation(true);
  for (const Frame &f : frames)
    grid.addView(f.cMg, f.points);
  vpHomogeneousMatrix cMlGrid = roughGuess();
  ASSERT_TRUE(grid.compute(cMlGrid)) << grid.getStatusDetails();
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, 0.0);
  selfcal.setKnownAltitude(0, frames[0].truth.getD());
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  selfcal.setMaxAngularStdDeviation(vpMath::rad(0.3));
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  const double gridAxis = vpMath::deg(axisAngle(cMlGrid, laserPose())),
               selfAxis = vpMath::deg(axisAngle(cMl, laserPose()));
  const double gridApex = 1000 * (cMlGrid.getTranslationVector() - laserPose().getTranslationVector()).frobeniusNorm();
  const double selfApex = 1000 * (cMl.getTranslationVector() - laserPose().getTranslationVector()).frobeniusNorm();
  std::cout << "chessboard views: axis " << gridAxis << " deg, apex " << gridApex << " mm, opening angle "
            << vpMath::deg(grid.getOpeningAngle() - kOpening) << " deg (estimated); self-calibration: axis " << selfAxis
            << " deg (std " << vpMath::deg(selfcal.getAxisStdDeviation()) << "), apex " << selfApex
            << " mm, opening angle held" << std::endl;
  EXPECT_LT(gridAxis, 0.01);
  EXPECT_LT(gridAxis, selfAxis);
  EXPECT_LT(gridApex, selfApex);
}

// A knock that turned the mount about the apex: with the previous apex held, only the axis is estimated,
// and far better than with the apex free.
TEST(LaserConicSelfCalibration, HeldApexDeterminesTheAxis)
{
  FlightSettings s;
  s.points = 300;
  s.frames = 40;
  s.cMl = laserPose() * vpHomogeneousMatrix(0, 0, 0, vpMath::rad(1.0), 0, 0); // knocked
  const std::vector<Frame> frames = flight(s, 111);
  const std::vector<Frame> test = testFrames(s, 60, 112);
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(camera());
  selfcal.setLaser(kOpening, laserPose()); // the calibration before the knock
  selfcal.setApexHeld(true);
  for (const Frame &f : frames)
    selfcal.addFrame(f.points);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  double altTrue, attTrue, altSelf, attSelf;
  gp3Errors(test, kOpening, s.cMl, altTrue, attTrue);
  gp3Errors(test, A, cMl, altSelf, attSelf);
  std::cout << "apex held: axis error " << vpMath::deg(axisAngle(cMl, s.cMl)) << " deg (std "
            << vpMath::deg(selfcal.getAxisStdDeviation()) << "); GP3 RMS errors: true laser " << 1000 * altTrue
            << " mm, " << vpMath::deg(attTrue) << " deg; self-calibrated " << 1000 * altSelf << " mm, "
            << vpMath::deg(attSelf) << " deg" << std::endl;
  EXPECT_LT(vpMath::deg(axisAngle(cMl, s.cMl)), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()) + 1e-3);
}

// A mount knocked by several degrees, the calibration before the knock as the initial guess: the check that a
// calibration explains each trace refused every frame from 2 degrees on (STATUS_NOT_ENOUGH_FRAMES, 0 of 40
// frames used), though repairing a knocked mount is what the self-calibration is for. From 8 degrees on the joint
// problem started from the knocked laser's planes ended at the iteration limit (8) or degenerate (12): it is run
// again from the grid's best axis.
TEST(LaserConicSelfCalibration, AMountKnockedByDegreesIsRecalibrated)
{
  for (double knock : {3.0, 5.0, 8.0, 12.0}) {
    FlightSettings s;
    s.points = 300;
    s.frames = 40;
    s.cMl = laserPose() * vpHomogeneousMatrix(0, 0, 0, vpMath::rad(knock), 0, 0);
    vpLaserConicSelfCalibration selfcal;
    selfcal.setCameraParameters(camera());
    selfcal.setLaser(kOpening, laserPose()); // the calibration before the knock
    selfcal.setApexHeld(true);
    for (const Frame &f : flight(s, 111))
      selfcal.addFrame(f.points);
    vpHomogeneousMatrix cMl;
    double A = 0.0;
    ASSERT_TRUE(selfcal.compute(cMl, A)) << knock << " deg: " << selfcal.getStatusDetails();
    unsigned int used = 0;
    for (bool u : selfcal.getFrameUsed())
      used += u ? 1 : 0;
    std::cout << "knocked by " << knock << " deg: " << used << " of 40 frames used, axis error "
              << vpMath::deg(axisAngle(cMl, s.cMl)) << " deg (std " << vpMath::deg(selfcal.getAxisStdDeviation()) << ")"
              << std::endl;
    EXPECT_GE(used, 30u);
    EXPECT_LT(vpMath::deg(axisAngle(cMl, s.cMl)), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()) + 1e-3);
  }
}

// A ruler off by 10 %: the whole scene scales, altitudes are 10 % larger than with the right ruler, the
// attitude and the axis are unchanged.
TEST(LaserConicSelfCalibration, WrongRulerScalesTheAltitudes)
{
  FlightSettings s;
  const std::vector<Frame> frames = flight(s, 21);
  const std::vector<Frame> test = testFrames(s, 40, 22);
  vpLaserConicSelfCalibration right = makeSelfCal(frames, trueApexDistance()),
                              wrong = makeSelfCal(frames, 1.1 * trueApexDistance());
  vpHomogeneousMatrix cMl, cMlWrong;
  double A = 0.0, AWrong = 0.0;
  ASSERT_TRUE(right.compute(cMl, A)) << right.getStatusDetails();
  ASSERT_TRUE(wrong.compute(cMlWrong, AWrong)) << wrong.getStatusDetails();
  EXPECT_LT(vpMath::deg(axisAngle(cMl, cMlWrong)), 1e-4);
  vpLaserConicPose a, b;
  a.setCameraParameters(camera());
  b.setCameraParameters(camera());
  a.setLaser(A, cMl);
  b.setLaser(AWrong, cMlWrong);
  double worstRatio = 0.0, worstAttitude = 0.0;
  for (const Frame &f : test) {
    vpPlane pa, pb;
    if (!a.computePlane(f.points, vpLaserConicPose::GP3, pa) || !b.computePlane(f.points, vpLaserConicPose::GP3, pb))
      continue;
    worstRatio = std::max(worstRatio, std::abs(b.getAltitude() / a.getAltitude() - 1.1));
    worstAttitude =
        std::max(worstAttitude, std::abs(b.getRoll() - a.getRoll()) + std::abs(b.getPitch() - a.getPitch()));
  }
  std::cout << "ruler +10 %: altitude ratio within " << worstRatio << " of 1.1, attitude within "
            << vpMath::deg(worstAttitude) << " deg" << std::endl;
  EXPECT_LT(worstRatio, 1e-3);
  EXPECT_LT(vpMath::deg(worstAttitude), 0.01);
}

// One known altitude is the scale instead of a ruler: the apex distance is recovered.
TEST(LaserConicSelfCalibration, KnownAltitudeGivesTheScale)
{
  FlightSettings s;
  const std::vector<Frame> frames = flight(s, 31);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, 0.0);
  selfcal.setKnownAltitude(4, frames[4].truth.getD());
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  const double distance = cMl.getTranslationVector().frobeniusNorm();
  std::cout << "known altitude: apex distance " << 1000 * distance << " mm (true " << 1000 * trueApexDistance()
            << "), std " << 1000 * selfcal.getStdDeviations()[4] << " mm along z" << std::endl;
  EXPECT_NEAR(distance, trueApexDistance(), 0.03 * trueApexDistance());
  EXPECT_LT(vpMath::deg(axisAngle(cMl, laserPose())), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()));
  EXPECT_NEAR(selfcal.getFramePlanes()[4].getD(), frames[4].truth.getD(), 1e-9); // held
  const std::vector<Frame> test = testFrames(s, 60, 12);
  double altTrue, attTrue, altSelf, attSelf;
  gp3Errors(test, kOpening, laserPose(), altTrue, attTrue);
  gp3Errors(test, A, cMl, altSelf, attSelf);
  std::cout << "GP3 RMS errors: true laser " << 1000 * altTrue << " mm, " << vpMath::deg(attTrue)
            << " deg; self-calibrated with a known altitude " << 1000 * altSelf << " mm, " << vpMath::deg(attSelf)
            << " deg" << std::endl;
}

// Frames at one attitude (a hover, altitudes within +-5 %) do not determine the laser: refused, with the spread.
// The only length is the altitude of a frame that GP-3 finds no plane in (its points are no trace): the frame
// is left out, and with it the scale. Refused for that reason, named, not for the attitudes (which it blamed:
// a spread of 6.6 / 9.2 degrees, enough).
TEST(LaserConicSelfCalibration, ALengthOnAFrameLeftOutIsNamed)
{
  FlightSettings s;
  s.points = 300;
  s.frames = 20;
  std::vector<Frame> frames = flight(s, 115);
  vpUniRand random(7);
  Frame noise = frames.front();
  for (vpImagePoint &p : noise.points)
    p = vpImagePoint(random.uniform(0.0, 600.0), random.uniform(0.0, 800.0));
  frames.insert(frames.begin(), noise);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, 0.0);
  selfcal.setKnownAltitude(0, 1.0);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  EXPECT_FALSE(selfcal.compute(cMl, A));
  EXPECT_FALSE(selfcal.getFrameUsed()[0]);
  EXPECT_EQ(selfcal.getStatus(), vpLaserConicSelfCalibration::STATUS_DEGENERATE_FRAMES);
  std::cout << selfcal.getStatusDetails() << std::endl;
  EXPECT_NE(selfcal.getStatusDetails().find("no length: the frames given a known altitude (0)"), std::string::npos);
}

TEST(LaserConicSelfCalibration, OneAttitudeIsRefused)
{
  FlightSettings s;
  s.maxTilt = 0.0;
  s.roll0 = vpMath::rad(4.0);
  s.pitch0 = vpMath::rad(-3.0);
  s.minAltitude = 0.95;
  s.maxAltitude = 1.05;
  const std::vector<Frame> frames = flight(s, 41);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  vpHomogeneousMatrix cMl = roughGuess(), before = cMl;
  double A = 1.0;
  EXPECT_FALSE(selfcal.compute(cMl, A));
  EXPECT_EQ(selfcal.getStatus(), vpLaserConicSelfCalibration::STATUS_DEGENERATE_FRAMES);
  std::cout << selfcal.getStatusDetails() << std::endl;
  EXPECT_NE(selfcal.getStatusDetails().find("attitude spread"), std::string::npos);
  EXPECT_GT(vpMath::deg(selfcal.getAxisStdDeviation()), 0.1);
  // The same frame twenty times: the normal matrix is singular. Its covariance was all zeros, which read as
  // parameters known exactly; it is NaN (A, held, has no row to fill).
  vpLaserConicSelfCalibration same = makeSelfCal(std::vector<Frame>(20, frames.front()), trueApexDistance());
  EXPECT_FALSE(same.compute(cMl, A));
  EXPECT_EQ(same.getStatus(), vpLaserConicSelfCalibration::STATUS_DEGENERATE_FRAMES);
  EXPECT_TRUE(std::isinf(same.getAxisStdDeviation()));
  const vpColVector sd = same.getStdDeviations();
  for (unsigned int i = 0; i < 5; ++i)
    EXPECT_TRUE(std::isnan(sd[i])) << i;
  for (unsigned int i = 0; i < 4; ++i) // the previous calibration is untouched
    for (unsigned int j = 0; j < 4; ++j)
      EXPECT_EQ(cMl[i][j], before[i][j]);
  EXPECT_EQ(A, 1.0);
}

// Small tilts (+-2 deg): refused with the spread needed, which is of the order of what works.
TEST(LaserConicSelfCalibration, SmallTiltSaysHowMuchSpreadIsMissing)
{
  FlightSettings s;
  s.maxTilt = vpMath::rad(1.0);
  const std::vector<Frame> frames = flight(s, 51);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  selfcal.setMaxAngularStdDeviation(vpMath::rad(0.01));
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  EXPECT_FALSE(selfcal.compute(cMl, A));
  EXPECT_EQ(selfcal.getStatus(), vpLaserConicSelfCalibration::STATUS_DEGENERATE_FRAMES);
  std::cout << selfcal.getStatusDetails() << std::endl;
  EXPECT_NE(selfcal.getStatusDetails().find("of spread needed"), std::string::npos);
}

//! The cone of the one-parameter family of \e laser's that share its apex and its two tangent planes through the
//! camera centre, with the full opening angle \e A: its axis turned in the bisector plane (see the class description).
static vpHomogeneousMatrix familyMember(const vpHomogeneousMatrix &laser, double A0, double A, double &phi,
                                        double &phiA)
{
  const vpColVector P = laser.getTranslationVector(), u = laser.getRotationMatrix().getCol(2);
  const vpColVector l = P / P.frobeniusNorm();
  phi = std::acos(vpColVector::dotProd(u, l)); // axis to the camera-apex line
  // The tangent planes contain l at the angle psi0 from the bisector plane span(l, u): sin(A/2) = sin(phi) cos(psi0).
  const double sinPhiA = std::sin(0.5 * A) * std::sin(phi) / std::sin(0.5 * A0);
  phiA = phi > M_PI / 2 ? M_PI - std::asin(sinPhiA) : std::asin(sinPhiA); // the member on the same side of 90 deg
  const vpColVector k = vpColVector::crossProd(l, u).normalize();
  const vpThetaUVector turn(k[0] * (phiA - phi), k[1] * (phiA - phi), k[2] * (phiA - phi));
  return vpHomogeneousMatrix(vpTranslationVector(P), vpRotationMatrix(turn) * laser.getRotationMatrix());
}

// The opening angle is not observable from images of a plane: the cones with the same apex and the same two
// tangent planes through the camera centre explain every trace exactly, each with its own planes. Noise-free
// frames, the angle held 0.05 and 0.2 degree too small: the fit is exact (0 px) with the axis of the predicted
// family member, and the altitudes are wrong (a held angle error is not seen in the residuals).
TEST(LaserConicSelfCalibration, WrongHeldAngleIsExplainedByTheConeFamily)
{
  FlightSettings s;
  s.noise = 0.0;
  const std::vector<Frame> frames = flight(s, 61);
  for (double dA : {-0.05, -0.2}) {
    const double A = kOpening + vpMath::rad(dA);
    double phi = 0.0, phiA = 0.0;
    const vpHomogeneousMatrix member = familyMember(laserPose(), kOpening, A, phi, phiA);
    vpLaserConicSelfCalibration selfcal;
    selfcal.setCameraParameters(camera());
    selfcal.setLaser(A, laserPose()); // the true apex and axis, the angle off
    selfcal.setApexHeld(true);
    selfcal.setMaxAngularStdDeviation(vpMath::rad(10.0));
    for (const Frame &f : frames)
      selfcal.addFrame(f.points);
    vpHomogeneousMatrix cMl;
    double Aout = 0.0;
    ASSERT_TRUE(selfcal.compute(cMl, Aout)) << selfcal.getStatusDetails();
    const double h = selfcal.getFramePlanes()[0].getD(), hTrue = frames[0].truth.getD();
    std::cout << "held angle " << dA << " deg: RMS " << selfcal.getRmsPixels() << " px; axis turned "
              << vpMath::deg(axisAngle(cMl, laserPose())) << " deg (family member " << vpMath::deg(phiA - phi)
              << " deg, first order tan(phi) / (2 tan(A/2)) dA = "
              << std::tan(phi) / (2.0 * std::tan(0.5 * kOpening)) * dA << " deg, phi " << vpMath::deg(phi)
              << " deg); altitude of frame 0 " << h << " m (true " << hTrue << ")" << std::endl;
    EXPECT_LT(selfcal.getRmsPixels(), 1e-3);                                  // exact fit: nothing in the images tells
    EXPECT_LT(vpMath::deg(axisAngle(cMl, member)), 1e-3);                     // the predicted member of the family
    EXPECT_GT(vpMath::deg(axisAngle(cMl, laserPose())), 10.0 * std::abs(dA)); // the axis moved far more
    EXPECT_LT(vpMath::deg(apexDirectionAngle(cMl, laserPose())), 1e-6);       // held
    EXPECT_GT(std::abs(h / hTrue - 1.0), 0.05);                               // altitudes off by >= 5 %
  }
  // A flight with noise, the angle estimated: the normal matrix of (axis, apex direction, angle) is singular
  // (the family's tangent direction), but regular with the angle held.
  s.noise = 0.5;
  vpLaserConicSelfCalibration selfcal = makeSelfCal(flight(s, 61), trueApexDistance());
  selfcal.setOpeningAngleEstimation(true);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  EXPECT_FALSE(selfcal.compute(cMl, A));
  const double freeCondition = selfcal.getConditionNumber();
  selfcal.setOpeningAngleEstimation(false);
  EXPECT_TRUE(selfcal.compute(cMl, A));
  std::cout << "condition number: angle estimated " << freeCondition << ", held " << selfcal.getConditionNumber()
            << std::endl;
  EXPECT_GT(freeCondition, 1e13);
  EXPECT_LT(selfcal.getConditionNumber(), 1e7);
}

// Estimating the angle with a ruler only is refused; a second length (two known altitudes of frames at different
// heights, or the ruler and one known altitude: the family and the scale are two unknowns) determines it.
TEST(LaserConicSelfCalibration, OpeningAngleNeedsTwoLengths)
{
  FlightSettings s;
  const std::vector<Frame> frames = flight(s, 61);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  selfcal.setOpeningAngleEstimation(true);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  EXPECT_FALSE(selfcal.compute(cMl, A));
  EXPECT_EQ(selfcal.getStatus(), vpLaserConicSelfCalibration::STATUS_DEGENERATE_FRAMES);
  std::cout << selfcal.getStatusDetails() << std::endl;
  EXPECT_NE(selfcal.getStatusDetails().find("opening angle is not determined"), std::string::npos);

  vpLaserConicSelfCalibration two = makeSelfCal(frames, 0.0);
  two.setOpeningAngleEstimation(true);
  const std::pair<size_t, size_t> range = altitudeExtremes(frames);
  two.setKnownAltitude(static_cast<unsigned int>(range.first), frames[range.first].truth.getD());
  two.setKnownAltitude(static_cast<unsigned int>(range.second), frames[range.second].truth.getD());
  ASSERT_TRUE(two.compute(cMl, A)) << two.getStatusDetails();
  std::cout << "with 2 known altitudes (" << frames[range.first].altitude << ", " << frames[range.second].altitude
            << " m): angle error " << vpMath::deg(A - kOpening) << " deg, std "
            << vpMath::deg(two.getStdDeviations()[5]) << std::endl;
  EXPECT_LT(std::abs(vpMath::deg(A - kOpening)), 3.0 * vpMath::deg(two.getStdDeviations()[5]));
  EXPECT_LT(std::abs(vpMath::deg(A - kOpening)), 0.05);
  EXPECT_LT(vpMath::deg(axisAngle(cMl, laserPose())), 3.0 * vpMath::deg(two.getAxisStdDeviation()) + 1e-3);

  // The ruler and one known altitude are two lengths too.
  selfcal.setKnownAltitude(static_cast<unsigned int>(range.first), frames[range.first].truth.getD());
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  std::cout << "with the ruler and 1 known altitude: angle error " << vpMath::deg(A - kOpening) << " deg, std "
            << vpMath::deg(selfcal.getStdDeviations()[5]) << std::endl;
  EXPECT_LT(std::abs(vpMath::deg(A - kOpening)), 3.0 * vpMath::deg(selfcal.getStdDeviations()[5]));
  EXPECT_LT(std::abs(vpMath::deg(A - kOpening)), 0.05);
}

namespace
{
//! The self-calibration of frames with 10 % of outliers each: the laser within 4 standard deviations, 85-93 % inliers.
void expectTenPercentOfOutliersRejected(vpLaserConicSelfCalibration &selfcal)
{
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  EXPECT_LT(vpMath::deg(axisAngle(cMl, laserPose())), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()));
  EXPECT_LT(vpMath::deg(apexDirectionAngle(cMl, laserPose())),
            4.0 * vpMath::deg(selfcal.getApexDirectionStdDeviation()));
  EXPECT_LT(selfcal.getNbInliers(), 0.93 * selfcal.getNbPoints());
  EXPECT_GT(selfcal.getNbInliers(), 0.85 * selfcal.getNbPoints());
}
} // namespace

// 10 % outliers in every frame: rejected.
TEST(LaserConicSelfCalibration, RejectsOutlierPoints)
{
  FlightSettings s;
  s.outliers = 0.1;
  const std::vector<Frame> frames = flight(s, 71);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  expectTenPercentOfOutliersRejected(selfcal);
}

//! Axis standard deviation of the self-calibration on \e frames (those of \e pick), no limit on it.
double axisStd(const std::vector<Frame> &frames, const std::vector<size_t> &pick)
{
  std::vector<Frame> chosen;
  for (size_t k : pick)
    chosen.push_back(frames[k]);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(chosen, trueApexDistance());
  selfcal.setMaxAngularStdDeviation(vpMath::rad(10.0));
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  return selfcal.compute(cMl, A) ? selfcal.getAxisStdDeviation() : std::numeric_limits<double>::infinity();
}

// 200 frames, 180 of them nearly level: the 20 chosen by information determine the laser better than the 20
// tilted ones or 20 evenly spread in time (the level frames' altitude differences are informative too).
TEST(LaserConicSelfCalibration, ChoosesInformativeFrames)
{
  FlightSettings level;
  level.frames = 180;
  level.points = 200;
  level.maxTilt = vpMath::rad(1.0);
  std::vector<Frame> frames = flight(level, 81);
  FlightSettings tilted = level;
  tilted.frames = 20;
  tilted.maxTilt = vpMath::rad(15.0);
  const std::vector<Frame> more = flight(tilted, 82);
  frames.insert(frames.end(), more.begin(), more.end());
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  selfcal.setMaxFrames(20);
  selfcal.setMaxAngularStdDeviation(vpMath::rad(0.3));
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  std::vector<size_t> used, lastTwenty, even;
  for (size_t k = 0; k < frames.size(); ++k) {
    if (selfcal.getFrameUsed()[k])
      used.push_back(k);
    if (k >= 180)
      lastTwenty.push_back(k);
    if (k % 10 == 0)
      even.push_back(k);
  }
  const double chosenStd = axisStd(frames, used), tiltedStd = axisStd(frames, lastTwenty),
               evenStd = axisStd(frames, even);
  std::cout << used.size() << " frames used; axis error " << vpMath::deg(axisAngle(cMl, laserPose()))
            << " deg; axis std " << vpMath::deg(chosenStd) << " deg (the 20 tilted frames: " << vpMath::deg(tiltedStd)
            << ", 20 evenly spread: " << vpMath::deg(evenStd) << ")" << std::endl;
  EXPECT_EQ(used.size(), 20u);
  EXPECT_NEAR(chosenStd, selfcal.getAxisStdDeviation(), 1e-12);
  EXPECT_LT(chosenStd, tiltedStd);
  EXPECT_LT(chosenStd, 0.75 * evenStd); // measured 0.11 against 0.17 deg (tilted 0.18)
  EXPECT_LT(vpMath::deg(axisAngle(cMl, laserPose())), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()));
}

// The frames left out of the joint problem (setMaxFrames()) had their planes at the scale of the initial laser, the
// guess: their altitudes off by the guess's error on the apex distance while the frames used had theirs right.
TEST(LaserConicSelfCalibration, FramesLeftOutHavePlanesOfTheCalibratedLaser)
{
  FlightSettings s;
  s.frames = 30;
  const std::vector<Frame> frames = flight(s, 131);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, trueApexDistance());
  selfcal.setMaxFrames(12);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  double worstUsed = 0.0, worstLeftOut = 0.0;
  unsigned int leftOut = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    const double error = std::abs(selfcal.getFramePlanes()[k].getD() / frames[k].truth.getD() - 1.0);
    if (selfcal.getFrameUsed()[k])
      worstUsed = std::max(worstUsed, error);
    else {
      worstLeftOut = std::max(worstLeftOut, error);
      ++leftOut;
    }
  }
  std::cout << leftOut << " frames left out; altitude error " << 100.0 * worstLeftOut << " % at worst (frames used "
            << 100.0 * worstUsed << " %)" << std::endl;
  EXPECT_EQ(leftOut, 18u);
  EXPECT_LT(worstLeftOut, 2.0 * worstUsed + 0.005);
}

namespace
{
//! A self-calibration of \e frames each given its true plane 5 % off in distance (a rough plane), the true ruler.
vpLaserConicSelfCalibration withRoughPlanes(const std::vector<Frame> &frames)
{
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(camera());
  selfcal.setLaser(kOpening, roughGuess());
  selfcal.setApexDistance(trueApexDistance());
  selfcal.setMaxAngularStdDeviation(vpMath::rad(0.3));
  for (const Frame &f : frames) {
    vpPlane rough = f.truth;
    rough.setD(1.05 * rough.getD());
    selfcal.addFrame(f.points, rough);
  }
  return selfcal;
}
} // namespace

// Frames given with their rough planes (e.g. the estimates made in flight): no plane search, same result.
TEST(LaserConicSelfCalibration, FramesWithRoughPlanes)
{
  FlightSettings s;
  s.points = 300;
  const std::vector<Frame> frames = flight(s, 121);
  vpLaserConicSelfCalibration selfcal = withRoughPlanes(frames);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
  EXPECT_LT(vpMath::deg(axisAngle(cMl, laserPose())), 4.0 * vpMath::deg(selfcal.getAxisStdDeviation()));
  const vpPlane plane = selfcal.getFramePlanes()[3]; // a copy: the vector is returned by value
  vpLaserConicSelfCalibration searched = makeSelfCal(frames, trueApexDistance());
  searched.setMaxAngularStdDeviation(vpMath::rad(0.3));
  vpHomogeneousMatrix cMlSearched;
  ASSERT_TRUE(searched.compute(cMlSearched, A));
  std::cout << "rough planes: altitude " << plane.getD() << " (true " << frames[3].truth.getD() << ", planes searched "
            << searched.getFramePlanes()[3].getD() << "), axes " << vpMath::deg(axisAngle(cMl, cMlSearched))
            << " deg apart" << std::endl;
  // The same minimum from both starts (6 % off the true altitude here: the altitude/axis trade-off a ruler
  // leaves, 0.15 deg of axis standard deviation with 300 points per frame; see the class description).
  EXPECT_LT(vpMath::deg(axisAngle(cMl, cMlSearched)), 1e-4);
  EXPECT_NEAR(plane.getD(), searched.getFramePlanes()[3].getD(), 1e-5);
  EXPECT_THROW(selfcal.addFrame(frames[0].points, vpPlane(0, 0, 0, 1)), vpLaserConicException);
  EXPECT_THROW(selfcal.addFrame(frames[0].points, vpPlane(0, 0, -1, std::numeric_limits<double>::quiet_NaN())),
               vpLaserConicException);
  EXPECT_THROW(selfcal.addFrame(frames[0].points, vpPlane(0, 0, 1, 1)), vpLaserConicException); // behind
}

// Frames given with rough planes and 10 % outliers each (a plane from the flight's own estimates, the trace as
// detected): the first solve, its weights all 1, took the outliers at full weight, and the self-calibration
// stopped at the iteration limit.
TEST(LaserConicSelfCalibration, RoughPlanesWithOutliers)
{
  FlightSettings s;
  s.points = 300;
  s.outliers = 0.1;
  const std::vector<Frame> frames = flight(s, 122);
  vpLaserConicSelfCalibration selfcal = withRoughPlanes(frames);
  expectTenPercentOfOutliersRejected(selfcal);
}

TEST(LaserConicSelfCalibration, BadInput)
{
  FlightSettings s;
  s.frames = 3;
  const std::vector<Frame> frames = flight(s, 91);
  vpLaserConicSelfCalibration selfcal = makeSelfCal(frames, 0.0);
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  EXPECT_THROW(selfcal.compute(cMl, A), vpLaserConicException); // no scale constraint
  std::vector<vpImagePoint> nan = frames[0].points;
  nan[3].set_u(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(selfcal.addFrame(nan), vpLaserConicException);
  std::vector<vpImagePoint> huge = frames[0].points; // counted as perfect inliers (the residual overflowed)
  huge[3] = vpImagePoint(1e200, 1e200);
  EXPECT_THROW(selfcal.addFrame(huge), vpLaserConicException);
  EXPECT_THROW(selfcal.addFrame(std::vector<vpImagePoint>()), vpLaserConicException);
  EXPECT_THROW(selfcal.addFrame(std::vector<vpImagePoint>(frames[0].points.begin(), frames[0].points.begin() + 4)),
               vpLaserConicException);
  EXPECT_THROW(selfcal.setKnownAltitude(7, 1.0), vpLaserConicException);
  EXPECT_THROW(selfcal.setKnownAltitude(0, -1.0), vpLaserConicException);
  EXPECT_THROW(selfcal.setApexDistance(std::numeric_limits<double>::quiet_NaN()), vpLaserConicException);
  EXPECT_THROW(selfcal.setLaser(0.0, laserPose()), vpLaserConicException);
  EXPECT_THROW(selfcal.setLaser(kOpening, vpHomogeneousMatrix()), vpLaserConicException); // apex at the camera
  EXPECT_THROW(selfcal.setMaxFrames(2), vpLaserConicException);
  vpLaserConicSelfCalibration empty;
  EXPECT_THROW(empty.compute(cMl, A), vpLaserConicException);

  // Two frames with a plane and one whose points are not a trace: not enough frames, outputs untouched.
  vpLaserConicSelfCalibration two = makeSelfCal(std::vector<Frame>(frames.begin(), frames.begin() + 2), 0.1);
  std::vector<vpImagePoint> line;
  for (int i = 0; i < 50; ++i)
    line.emplace_back(100.0 + i, 200.0 + 2.0 * i);
  two.addFrame(line);
  vpHomogeneousMatrix kept = roughGuess();
  EXPECT_FALSE(two.compute(kept, A));
  EXPECT_EQ(two.getStatus(), vpLaserConicSelfCalibration::STATUS_NOT_ENOUGH_FRAMES);
  EXPECT_EQ(kept[0][3], roughGuess()[0][3]);

  // A length of 1e200 m: Ceres cannot evaluate the residuals. A solver failure, not the iteration limit
  // (STATUS_NO_CONVERGENCE after "0 iterations" before).
  vpLaserConicSelfCalibration farApex = makeSelfCal(frames, 1e200);
  EXPECT_FALSE(farApex.compute(kept, A));
  EXPECT_EQ(farApex.getStatus(), vpLaserConicSelfCalibration::STATUS_SOLVER_FAILURE) << farApex.getStatusDetails();
}

namespace
{
//! One protocol of the study below: a flight and the lengths given.
struct Protocol
{
  const char *name;
  unsigned int frames, maxFrames, flights;
  double minAltitude, maxAltitude, tiltDeg;
  int lengths; //!< 0: ruler; 1: frame 0's altitude; 2: the lowest and highest frames' altitudes; 3: ruler + lowest
};

void studyRow(const Protocol &p, const std::vector<Frame> &test, const std::vector<Frame> &cleanTest, double altTrue)
{
  FlightSettings s;
  s.frames = p.frames;
  s.minAltitude = p.minAltitude;
  s.maxAltitude = p.maxAltitude;
  s.maxTilt = vpMath::rad(p.tiltDeg);
  double axis2 = 0.0, std2 = 0.0, ratio2 = 0.0, predicted2 = 0.0, ms = 0.0;
  unsigned int within = 0;
  for (unsigned int seed = 1; seed <= p.flights; ++seed) {
    const std::vector<Frame> frames = flight(s, 1000 + seed);
    vpLaserConicSelfCalibration selfcal = p.lengths == 0 || p.lengths == 3
                                              ? makeSelfCal(frames, trueApexDistance())
                                              : knownAltitudeSelfCal(frames, p.lengths == 2);
    if (p.lengths == 3) {
      const size_t lowest = altitudeExtremes(frames).first;
      selfcal.setKnownAltitude(static_cast<unsigned int>(lowest), frames[lowest].truth.getD());
    }
    selfcal.setMaxFrames(p.maxFrames);
    selfcal.setMaxAngularStdDeviation(vpMath::rad(5.0));
    vpHomogeneousMatrix cMl;
    double A = 0.0;
    const double t0 = vpTime::measureTimeMs();
    ASSERT_TRUE(selfcal.compute(cMl, A)) << selfcal.getStatusDetails();
    ms += vpTime::measureTimeMs() - t0;
    const double axis = vpMath::deg(axisAngle(cMl, laserPose()));
    double alt, att;
    gp3Errors(test, A, cMl, alt, att);
    const double predicted = predictedCalibrationAltitude(cleanTest, selfcal.getCovarianceMatrix());
    axis2 += axis * axis;
    std2 += vpMath::sqr(vpMath::deg(selfcal.getAxisStdDeviation()));
    within += axis < 0.1 ? 1 : 0;
    ratio2 += vpMath::sqr(alt / altTrue);
    predicted2 += 1.0 + vpMath::sqr(predicted / altTrue);
  }
  const double n = p.flights;
  std::printf("| %s | %.3f | %.3f | %u/%u | %.2f | %.2f | %.0f |\n", p.name, std::sqrt(std2 / n), std::sqrt(axis2 / n),
              within, p.flights, std::sqrt(ratio2 / n), std::sqrt(predicted2 / n), ms / n);
}
} // namespace

// The protocol study of the class description (disabled: about 30 s; run with
// --gtest_also_run_disabled_tests --gtest_filter='*ProtocolStudy*'). Per protocol: the computed axis standard
// deviation (RMS over the flights), the RMS axis error, the flights within 0.1 deg, the RMS ratio of GP-3's
// altitude error on 60 new frames to the true laser's, the ratio the covariance predicts, the time of compute().
TEST(LaserConicSelfCalibration, DISABLED_ProtocolStudy)
{
  FlightSettings s;
  Gp3Reference ref;
  gp3Reference(s, ref);
  const Protocol protocols[] = {
      {"20 frames, +-15 deg, 0.8-1.3 m, one known altitude", 20, 40, 30, 0.8, 1.3, 15.0, 1},
      {"same, ruler", 20, 40, 3, 0.8, 1.3, 15.0, 0},
      {"same, +-25 deg", 20, 40, 3, 0.8, 1.3, 25.0, 1},
      {"same, 0.4-2.5 m", 20, 40, 3, 0.4, 2.5, 15.0, 1},
      {"100 frames, all used", 100, 100, 2, 0.8, 1.3, 15.0, 1},
      {"200 frames, all used", 200, 200, 2, 0.8, 1.3, 15.0, 1},
      {"500 frames, 40 chosen by information", 500, 40, 2, 0.8, 1.3, 15.0, 1},
      {"500 frames, all used", 500, 500, 2, 0.8, 1.3, 15.0, 1},
      {"20 frames, two known altitudes (lowest, highest)", 20, 40, 4, 0.8, 1.3, 15.0, 2},
      {"20 frames, ruler + lowest frame's altitude", 20, 40, 4, 0.8, 1.3, 15.0, 3},
  };
  std::printf("| protocol | axis std (deg) | axis error RMS (deg) | within 0.1 deg | GP-3 altitude ratio | predicted | "
              "ms |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Protocol &p : protocols)
    studyRow(p, ref.test, ref.clean, ref.altitudeRms);
}
