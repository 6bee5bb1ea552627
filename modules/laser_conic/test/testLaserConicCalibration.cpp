/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpLaserConicCalibration: a known laser pose is recovered from simulated grid views
// (vpLaserConicSimulator gives the laser points of each view), starting from a perturbed guess.
#include <visp3/laser_conic/vpLaserConicCalibration.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <visp3/core/vpMath.h>

namespace
{
const unsigned int kWidth = 1600, kHeight = 1200;
const double kOpening = vpMath::rad(34.0);

vpCameraParameters camera() { return vpCameraParameters(1500.0, 1500.0, 800.0, 600.0); }

// Ground truth: laser 10 cm beside the camera, axis tilted by a few degrees.
vpHomogeneousMatrix trueLaserPose()
{
  return vpHomogeneousMatrix(0.10, 0.02, -0.01, vpMath::rad(3.0), vpMath::rad(-5.0), vpMath::rad(10.0));
}

// Grid poses seen from 0.5 to 1.1 m with tilts up to 25 degrees (seeded), as in a calibration session.
std::vector<vpHomogeneousMatrix> gridPoses(unsigned int nbViews, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> tilt(-25.0, 25.0), depth(0.5, 1.1), shift(-0.1, 0.1), spin(-180.0, 180.0);
  std::vector<vpHomogeneousMatrix> poses;
  for (unsigned int j = 0; j < nbViews; ++j)
    poses.push_back(vpHomogeneousMatrix(shift(rng), shift(rng), depth(rng), vpMath::rad(tilt(rng)),
                                        vpMath::rad(tilt(rng)), vpMath::rad(spin(rng))));
  return poses;
}

// Laser points of each view, exact or with Gaussian image noise of sigma pixels.
std::vector<std::vector<vpImagePoint> > laserPoints(const std::vector<vpHomogeneousMatrix> &poses, double sigma,
                                                    unsigned int pointsPerView = 120)
{
  vpLaserConicSimulator sim;
  sim.setCamera(camera(), kWidth, kHeight);
  sim.setLaser(kOpening, trueLaserPose());
  sim.setSeed(99);
  std::vector<std::vector<vpImagePoint> > points;
  for (const vpHomogeneousMatrix &cMg : poses) {
    sim.setGroundPose(cMg);
    points.push_back(sim.addNoise(sim.tracePoints(pointsPerView), sigma));
  }
  return points;
}

// The truth moved by 5 degrees (axis) and 2 cm (apex): a rough hand measurement.
vpHomogeneousMatrix perturbedGuess()
{
  const vpHomogeneousMatrix tilt(0, 0, 0, vpMath::rad(4.0), vpMath::rad(3.0), 0.0); // 5 degrees
  vpHomogeneousMatrix guess = trueLaserPose() * tilt;
  guess[0][3] += 0.012;
  guess[1][3] -= 0.016; // |(12, -16)| = 20 mm
  return guess;
}

double axisErrorDeg(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  const double dot = a[0][2] * b[0][2] + a[1][2] * b[1][2] + a[2][2] * b[2][2];
  return vpMath::deg(std::acos(std::max(-1.0, std::min(1.0, dot))));
}

double apexErrorMm(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  return 1000.0 * std::sqrt(std::pow(a[0][3] - b[0][3], 2) + std::pow(a[1][3] - b[1][3], 2) +
                            std::pow(a[2][3] - b[2][3], 2));
}

vpLaserConicCalibration makeCalibration(const std::vector<vpHomogeneousMatrix> &poses,
                                        const std::vector<std::vector<vpImagePoint> > &points)
{
  vpLaserConicCalibration calib;
  calib.setCameraParameters(camera());
  calib.setOpeningAngle(kOpening);
  for (size_t j = 0; j < poses.size(); ++j)
    calib.addView(poses[j], points[j]);
  return calib;
}
} // namespace

TEST(LaserConicCalibration, GuessIsReallyPerturbed)
{
  EXPECT_NEAR(axisErrorDeg(perturbedGuess(), trueLaserPose()), 5.0, 0.01);
  EXPECT_NEAR(apexErrorMm(perturbedGuess(), trueLaserPose()), 20.0, 1e-6);
}

TEST(LaserConicCalibration, RecoversTheLaserPoseFromExactPoints)
{
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(8, 1);
  const std::vector<std::vector<vpImagePoint> > points = laserPoints(poses, 0.0);
  vpLaserConicCalibration calib = makeCalibration(poses, points);
  calib.setInitialGuess(perturbedGuess());
  vpHomogeneousMatrix cMl;
  const double rms = calib.calibrate(cMl);
  const double axisErr = axisErrorDeg(cMl, trueLaserPose()), apexErr = apexErrorMm(cMl, trueLaserPose());
  std::cout << "exact points: rms " << rms << " m (initial " << calib.getInitialRms() << " m), axis error " << axisErr
            << " deg, apex error " << apexErr << " mm" << std::endl;
  // Exact data: the model is exact, so only the solver tolerances limit the result.
  EXPECT_LT(rms, 1e-7);
  EXPECT_LT(axisErr, 0.05);
  EXPECT_LT(apexErr, 0.5);
  EXPECT_GT(calib.getInitialRms(), 1e-3); // the guess was millimetres off on the grids
  // The returned rotation is Rx(alpha) Ry(beta): a rotation matrix whose Z axis is the cone axis.
  EXPECT_TRUE(cMl.isAnHomogeneousMatrix(1e-9));

  // Grid points for figures: one list per view, predicted on top of measured.
  const auto measured = calib.getMeasuredGridPoints(), predicted = calib.getPredictedGridPoints();
  ASSERT_EQ(measured.size(), poses.size());
  ASSERT_EQ(predicted.size(), poses.size());
  for (size_t j = 0; j < poses.size(); ++j) {
    ASSERT_EQ(measured[j].size(), points[j].size());
    ASSERT_EQ(predicted[j].size(), points[j].size());
    for (size_t i = 0; i < measured[j].size(); ++i) {
      EXPECT_NEAR(measured[j][i].first, predicted[j][i].first, 1e-6);
      EXPECT_NEAR(measured[j][i].second, predicted[j][i].second, 1e-6);
    }
  }
}

TEST(LaserConicCalibration, GuessCanBeGivenAsTheArgument)
{
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(6, 2);
  vpLaserConicCalibration calib = makeCalibration(poses, laserPoints(poses, 0.0));
  vpHomogeneousMatrix cMl = perturbedGuess();
  calib.calibrate(cMl);
  EXPECT_LT(axisErrorDeg(cMl, trueLaserPose()), 0.05);
  EXPECT_LT(apexErrorMm(cMl, trueLaserPose()), 0.5);
}

TEST(LaserConicCalibration, RecoversTheLaserPoseFromNoisyPoints)
{
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(10, 3);
  vpLaserConicCalibration calib = makeCalibration(poses, laserPoints(poses, 0.5));
  calib.setInitialGuess(perturbedGuess());
  vpHomogeneousMatrix cMl;
  const double rms = calib.calibrate(cMl);
  const double axisErr = axisErrorDeg(cMl, trueLaserPose()), apexErr = apexErrorMm(cMl, trueLaserPose());
  std::cout << "0.5 px noise: rms " << rms << " m, axis error " << axisErr << " deg, apex error " << apexErr << " mm"
            << std::endl;
  // 0.5 px at 0.5-1.1 m with f = 1500 px is 0.2-0.4 mm on the grid: measured RMS residuals 0.26-0.34 mm.
  // With 1200 such points the cone is well determined: over 20 noise/pose seeds the errors were at most
  // 0.0065 deg and 0.11 mm (this seed: ~0.01 deg, ~0.16 mm); the bounds keep a margin of 3 or more.
  EXPECT_LT(rms, 0.5e-3);
  EXPECT_LT(axisErr, 0.05);
  EXPECT_LT(apexErr, 0.5);
}

TEST(LaserConicCalibration, ConvergesFromARoughGuess)
{
  // 20 degrees and 6 cm off: the first stage puts every point on its nearest ray of the wrong cone, from
  // where Levenberg-Marquardt still reaches the truth (exact points: same bounds as above).
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(8, 5);
  vpLaserConicCalibration calib = makeCalibration(poses, laserPoints(poses, 0.0));
  vpHomogeneousMatrix guess = trueLaserPose() * vpHomogeneousMatrix(0, 0, 0, vpMath::rad(16.0), vpMath::rad(12.0), 0);
  guess[0][3] -= 0.06;
  calib.setInitialGuess(guess);
  vpHomogeneousMatrix cMl;
  calib.calibrate(cMl);
  EXPECT_LT(axisErrorDeg(cMl, trueLaserPose()), 0.05);
  EXPECT_LT(apexErrorMm(cMl, trueLaserPose()), 0.5);
}

TEST(LaserConicCalibration, CalibratesFromRenderedAndDetectedImages)
{
  // The whole chain: rendered images (stripe 3 px, sensor noise 2 grey levels), HSV detection, calibration.
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(6, 6);
  vpLaserConicSimulator sim;
  sim.setCamera(camera(), kWidth, kHeight);
  sim.setLaser(kOpening, trueLaserPose());
  sim.setSeed(5);
  vpLaserConicDetector detector;
  detector.setSamplingStep(2);
  vpLaserConicCalibration calib;
  calib.setCameraParameters(camera());
  calib.setOpeningAngle(kOpening);
  for (const vpHomogeneousMatrix &cMg : poses) {
    sim.setGroundPose(cMg);
    vpImage<vpRGBa> I;
    sim.render(I);
    calib.addView(cMg, detector.detect(I));
  }
  calib.setInitialGuess(perturbedGuess());
  vpHomogeneousMatrix cMl;
  const double rms = calib.calibrate(cMl);
  const double axisErr = axisErrorDeg(cMl, trueLaserPose()), apexErr = apexErrorMm(cMl, trueLaserPose());
  std::cout << "rendered images: rms " << rms << " m, axis error " << axisErr << " deg, apex error " << apexErr
            << " mm" << std::endl;
  // The detected centres are within 0.2 px of the curve, 0.03 px on average (see the detector test), about
  // 15 times better than the 0.5 px noise case above: measured 0.02 mm RMS, 2e-4 deg, 5e-3 mm; the bounds
  // are 5 times tighter than above and still far from the measurements.
  EXPECT_LT(rms, 0.1e-3);
  EXPECT_LT(axisErr, 0.01);
  EXPECT_LT(apexErr, 0.1);
}

TEST(LaserConicCalibration, BadInputThrows)
{
  const std::vector<vpHomogeneousMatrix> poses = gridPoses(3, 4);
  const std::vector<std::vector<vpImagePoint> > points = laserPoints(poses, 0.0);
  vpHomogeneousMatrix cMl = perturbedGuess();

  vpLaserConicCalibration noCamera;
  noCamera.setOpeningAngle(kOpening);
  noCamera.addView(poses[0], points[0]);
  EXPECT_THROW(noCamera.calibrate(cMl), vpLaserConicException);

  vpLaserConicCalibration noAngle;
  noAngle.setCameraParameters(camera());
  noAngle.addView(poses[0], points[0]);
  EXPECT_THROW(noAngle.calibrate(cMl), vpLaserConicException);

  vpLaserConicCalibration noView;
  noView.setCameraParameters(camera());
  noView.setOpeningAngle(kOpening);
  EXPECT_THROW(noView.calibrate(cMl), vpLaserConicException);

  vpLaserConicCalibration calib;
  EXPECT_THROW(calib.setCameraParameters(vpCameraParameters(-1.0, 1500, 800, 600)), vpLaserConicException);
  EXPECT_THROW(calib.setOpeningAngle(0.0), vpLaserConicException);
  EXPECT_THROW(calib.setOpeningAngle(M_PI), vpLaserConicException);
  EXPECT_THROW(calib.setOpeningAngle(std::numeric_limits<double>::infinity()), vpLaserConicException);
  const std::vector<vpImagePoint> four(points[0].begin(), points[0].begin() + 4);
  EXPECT_THROW(calib.addView(poses[0], four), vpLaserConicException);
  std::vector<vpImagePoint> withNan = points[0];
  withNan[2].set_u(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(calib.addView(poses[0], withNan), vpLaserConicException);
  vpHomogeneousMatrix nanPose = poses[0];
  nanPose[2][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(calib.addView(nanPose, points[0]), vpLaserConicException);
  EXPECT_THROW(calib.setInitialGuess(nanPose), vpLaserConicException);
  EXPECT_EQ(calib.getNbViews(), 0u);

  // A point that back-projects behind the camera on its grid: grid plane seen edge-on beyond the point.
  calib.setCameraParameters(camera());
  calib.setOpeningAngle(kOpening);
  calib.addView(vpHomogeneousMatrix(0, 0, 1, vpMath::rad(90), 0, 0), points[0]);
  EXPECT_THROW(calib.calibrate(cMl), vpLaserConicException);
  calib.clearViews();
  EXPECT_EQ(calib.getNbViews(), 0u);

  // A non-finite argument used as the guess.
  calib.addView(poses[0], points[0]);
  EXPECT_THROW(calib.calibrate(nanPose), vpLaserConicException);
}
