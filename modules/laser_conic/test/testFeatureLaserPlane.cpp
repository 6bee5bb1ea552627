/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpFeatureLaserPlane: its interaction matrix against finite differences of a moving camera, its two
// constructors against each other, and a vpServo task with a vpFeaturePoint that lands on a pad.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpFeatureLaserPlane.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

namespace
{
//! The ground z = 0 of the world seen from the camera at wMc.
vpPlane groundInCamera(const vpHomogeneousMatrix &wMc)
{
  const vpRotationMatrix R = wMc.getRotationMatrix();
  const vpTranslationVector t = wMc.getTranslationVector();
  // n_w . (R X_c + t) = 0 with n_w = (0, 0, 1)
  return vpPlane(R[2][0], R[2][1], R[2][2], t[2]);
}

//! A camera looking down from \e altitude, tilted by up to 25 deg.
vpHomogeneousMatrix randomPose(std::mt19937 &rng, double altitude)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const vpHomogeneousMatrix down(0.0, 0.0, altitude, M_PI, 0.0, 0.0);
  return down * vpHomogeneousMatrix(0.0, 0.0, 0.0, vpMath::rad(25) * u(rng), vpMath::rad(25) * u(rng), M_PI * u(rng));
}

vpFeatureLaserPlane featureAt(const vpHomogeneousMatrix &wMc)
{
  vpFeatureLaserPlane s;
  s.buildFrom(groundInCamera(wMc));
  return s;
}
} // namespace

// ds/dt = L v: each column of L against a central difference of the feature when the camera moves by
// one velocity component (vpExponentialMap, camera frame, as vpServo's velocities) for 1e-6 s.
TEST(LaserConicFeatureLaserPlane, InteractionMatchesFiniteDifferences)
{
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const vpHomogeneousMatrix wMc = randomPose(rng, 0.3 + 2.0 * (trial % 5) / 4.0);
    vpFeatureLaserPlane s = featureAt(wMc);
    const vpMatrix L = s.interaction();
    ASSERT_EQ(L.getRows(), 3u);
    ASSERT_EQ(L.getCols(), 6u);
    const double eps = 1e-6;
    for (unsigned int j = 0; j < 6; ++j) {
      vpColVector v(6, 0.0);
      v[j] = 1.0;
      const vpFeatureLaserPlane plus = featureAt(wMc * vpExponentialMap::direct(v, eps));
      const vpFeatureLaserPlane minus = featureAt(wMc * vpExponentialMap::direct(-v, eps));
      for (unsigned int i = 0; i < 3; ++i)
        EXPECT_NEAR((plus[i] - minus[i]) / (2 * eps), L[i][j], 1e-7) << "row " << i << " column " << j;
    }
  }
}

// The plane and the (altitude, roll, pitch) of vpLaserConicPose give the same feature; a selection gives its rows.
TEST(LaserConicFeatureLaserPlane, BuildFromAltitudeRollPitchMatchesPlane)
{
  std::mt19937 rng(4);
  for (int trial = 0; trial < 20; ++trial) {
    const vpHomogeneousMatrix wMc = randomPose(rng, 1.5);
    const vpPlane plane = groundInCamera(wMc);
    double h, roll, pitch;
    vpLaserConicPose::computeAltitudeRollPitch(plane, h, roll, pitch);
    vpFeatureLaserPlane a, b;
    a.buildFrom(plane);
    b.buildFrom(h, roll, pitch);
    EXPECT_NEAR(a.get_h(), 1.5, 1e-12);
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_NEAR(a[i], b[i], 1e-12);
    EXPECT_NEAR(a.get_gz(), b.get_gz(), 1e-12);
    EXPECT_EQ(a.interaction(vpFeatureLaserPlane::selectGx() | vpFeatureLaserPlane::selectGy()).getRows(), 2u);
    vpFeatureLaserPlane level;
    level.buildFrom(1.0, 0.0, 0.0);
    const vpColVector e = a.error(level, vpFeatureLaserPlane::selectAltitude());
    ASSERT_EQ(e.getRows(), 1u);
    EXPECT_NEAR(e[0], 0.5, 1e-12);
  }
  vpFeatureLaserPlane f;
  EXPECT_THROW(f.buildFrom(0.0, 0.0, 0.0), vpLaserConicException);
  EXPECT_THROW(f.buildFrom(1.0, NAN, 0.0), vpLaserConicException);
  // Beyond a quarter turn the ground is behind the camera: degrees given as radians, most often.
  EXPECT_THROW(f.buildFrom(1.0, 0.0, 10.0), vpLaserConicException);
  EXPECT_THROW(f.buildFrom(1.0, -M_PI_2, 0.0), vpLaserConicException);
  EXPECT_NO_THROW(f.buildFrom(1.0, 1.5, -1.5));
  EXPECT_THROW(f.buildFrom(vpPlane(0, 0, 0, 1)), vpLaserConicException);
  EXPECT_THROW(f.buildFrom(vpPlane(0, 0, 1, 0)), vpLaserConicException);
}

// One vpServo task: the laser plane (altitude, roll, pitch) and a vpFeaturePoint on a pad at the world
// origin (x, y). From 2 m, 1.5 m off the pad and tilted by 20 deg, the camera lands 0.3 m above the pad, level.
TEST(LaserConicFeatureLaserPlane, ServoWithPointLandsOnPad)
{
  vpSimulatorCamera robot;
  robot.setSamplingTime(0.04);
  robot.setMaxTranslationVelocity(3.0); // no saturation: the exponential decrease of the error is checked
  robot.setMaxRotationVelocity(3.0);
  const vpHomogeneousMatrix wMc0 = vpHomogeneousMatrix(1.0, -1.1, 2.0, M_PI, 0.0, 0.0) *
                                   vpHomogeneousMatrix(0, 0, 0, vpMath::rad(12), vpMath::rad(-15), 0.3);
  robot.setPosition(wMc0);
  vpFeatureLaserPlane s, sd;
  sd.buildFrom(0.3, 0.0, 0.0);
  vpFeaturePoint p, pd;
  pd.buildFrom(0.0, 0.0, 0.3);
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.8);
  task.addFeature(s, sd);
  task.addFeature(p, pd);
  for (int it = 0; it < 400; ++it) { // lambda dt = 0.032 per iteration: e^-12.8 ~ 3e-6 left
    const vpHomogeneousMatrix wMc = robot.getPosition();
    s.buildFrom(groundInCamera(wMc));
    const vpColVector pad = wMc.inverse() * vpColVector({0.0, 0.0, 0.0, 1.0});
    p.buildFrom(pad[0] / pad[2], pad[1] / pad[2], pad[2]);
    robot.setVelocity(vpRobot::CAMERA_FRAME, task.computeControlLaw());
  }
  EXPECT_LT(task.getError().frobeniusNorm(), 1e-4);
  const vpHomogeneousMatrix wMc = robot.getPosition();
  double h, roll, pitch;
  vpLaserConicPose::computeAltitudeRollPitch(groundInCamera(wMc), h, roll, pitch);
  EXPECT_NEAR(h, 0.3, 1e-4);
  EXPECT_NEAR(roll, 0.0, 1e-4);
  EXPECT_NEAR(pitch, 0.0, 1e-4);
  EXPECT_NEAR(wMc[0][3], 0.0, 1e-4); // above the pad
  EXPECT_NEAR(wMc[1][3], 0.0, 1e-4);
  task.kill();
}
