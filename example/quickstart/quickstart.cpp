/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example quickstart.cpp
  The README's quick-start snippets on simulated data: vpPoseGravity next to vpPose, and
  vpLaserConicPose on a rendered laser frame. Exits non-zero when a result is off its ground truth.
*/
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>
#include <visp3/pose_gravity/vpPoseGravity.h>
#include <visp3/vision/vpPose.h>

namespace
{
//! Translation error (m) and rotation error (deg) between two poses.
void poseError(const vpHomogeneousMatrix &estimated, const vpHomogeneousMatrix &truth, double &dt, double &dr)
{
  const vpHomogeneousMatrix delta = estimated.inverse() * truth;
  dt = delta.getTranslationVector().frobeniusNorm();
  dr = vpMath::deg(vpThetaUVector(delta.getRotationMatrix()).getTheta());
}

//! Four points of a 10 cm square seen by a camera, with 0.5 px of noise (f = 800 px).
std::vector<vpPoint> simulatedPoints(const vpHomogeneousMatrix &cMo, std::mt19937 &rng)
{
  std::normal_distribution<double> noise(0.0, 0.5 / 800.0);
  const double square[4][2] = {{0.0, 0.0}, {0.1, 0.1}, {0.1, 0.0}, {0.0, 0.1}};
  std::vector<vpPoint> points;
  for (const auto &xy : square) {
    vpPoint P(xy[0], xy[1], 0.0);
    P.project(cMo);
    P.set_x(P.get_x() + noise(rng));
    P.set_y(P.get_y() + noise(rng));
    points.push_back(P);
  }
  return points;
}

bool gravityQuickStart()
{
  std::mt19937 rng(7);
  const vpCameraParameters cam(800, 800, 320, 240);
  const vpHomogeneousMatrix cMo_true(0.05, -0.03, 0.6, vpMath::rad(20), vpMath::rad(-15), vpMath::rad(30));
  // Gravity is -Z in the object frame; the camera IMU measures the same direction in its own frame.
  vpColVector g_obj(3);
  g_obj[2] = -9.81;
  const vpColVector g_cam = cMo_true.getRotationMatrix() * g_obj;
  const std::vector<vpPoint> points = simulatedPoints(cMo_true, rng);

  // --- README snippet: vpPoseGravity next to vpPose ---
  vpPose pose; // classical: 4 points or more
  pose.addPoints(points);
  vpHomogeneousMatrix cMo_classic;
  pose.computePose(vpPose::DEMENTHON_VIRTUAL_VS, cMo_classic);

  vpPoseGravity gpose;           // with two IMUs: 3 points are enough
  gpose.setCameraGravity(g_cam); // gravity measured in the camera frame (any norm)
  gpose.setObjectGravity(g_obj); // gravity measured in the object frame
  gpose.addPoints(points);
  vpHomogeneousMatrix cMo;
  if (gpose.computePose(vpPoseGravity::P3P, cMo)) { // also LEAST_SQUARES (n >= 3), RANSAC (outliers)
    gpose.setImageStdDev(0.5 / cam.get_px());       // optional maximum-likelihood refinement (Ceres);
    gpose.setGravityStdDev(0.01);                   // with a gravity sigma the tilt is refined too
    gpose.refinePose(cMo);
  } else {
    std::cout << vpPoseGravity::getStatusMessage(gpose.getStatus()) << std::endl;
    return false;
  }
  std::cout << "residual " << gpose.computeResidual(cMo) << std::endl;
  // --- end of snippet ---

  double dt = 0.0, dr = 0.0, dtClassic = 0.0, drClassic = 0.0;
  poseError(cMo, cMo_true, dt, dr);
  poseError(cMo_classic, cMo_true, dtClassic, drClassic);
  std::cout << "vpPoseGravity P3P + refinePose: " << dt * 1e3 << " mm, " << dr << " deg\n"
            << "vpPose DEMENTHON_VIRTUAL_VS:    " << dtClassic * 1e3 << " mm, " << drClassic << " deg" << std::endl;
  // 0.5 px on a 130 px target at 0.6 m: a few millimetres and a fraction of a degree.
  return dt < 0.01 && dr < 1.0;
}

bool laserQuickStart()
{
  const vpCameraParameters cam(1000, 1000, 800, 600);
  const vpHomogeneousMatrix cMl(0.15, 0.02, 0.0, 0.0, vpMath::rad(-8), 0.0);
  const double altitude = 1.0, roll = vpMath::rad(10), pitch = vpMath::rad(-5);
  // Ground frame: its +Z (the plane normal) points towards the camera, 1 m away.
  const vpHomogeneousMatrix cMg = vpHomogeneousMatrix(0, 0, 0, roll, 0, 0) * vpHomogeneousMatrix(0, 0, 0, 0, pitch, 0) *
                                  vpHomogeneousMatrix(0, 0, altitude, 0, 0, 0) *
                                  vpHomogeneousMatrix(0, 0, 0, M_PI, 0, 0);
  vpLaserConicSimulator sim;
  sim.setCamera(cam, 1600, 1200);
  sim.setLaser(vpMath::rad(34), cMl);
  sim.setGroundPose(cMg);
  sim.setSeed(3);
  vpImage<vpRGBa> I;
  sim.render(I);

  // --- README snippet: vpLaserConicPose ---
  vpLaserConicDetector detector;                         // red stripe: ridge of R - max(G, B), sub-pixel centres
  std::vector<vpImagePoint> points = detector.detect(I); // I: vpImage<vpRGBa>
  detector.setSearchRegion(points, 20.0);                // optional: next frame within 20 px of this trace

  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);       // with or without distortion (vpPixelMeterConversion, kdu)
  estimator.setLaser(vpMath::rad(34), cMl); // full opening angle; cone apex at the origin of l, axis +Z
  estimator.setRansacThreshold(2.0);        // pixels: separates gross outliers; the final fit adapts its scale
  estimator.setCovarianceComputation(true); // 3x3 covariance of (altitude, roll, pitch)
  vpPlane cPlane;                           // ground plane in the camera frame, normal towards the camera
  if (estimator.computePlane(points, vpLaserConicPose::GP3, cPlane)) { // or PLANE_PAIR, PP5, PP3
    std::cout << estimator.getAltitude() << " m, roll " << vpMath::deg(estimator.getRoll()) << ", pitch "
              << vpMath::deg(estimator.getPitch()) << " deg, " << estimator.getRansacNbInliers() << " inliers, "
              << "calibration health " << estimator.getCalibrationHealth() // ~1 when the rig calibration fits
              << std::endl;
    vpMatrix C = estimator.getCovarianceMatrix(); // e.g. for a Kalman filter update
    vpLaserConicPose::draw(I, estimator, points); // overlay: inliers green, outliers red, conic, caption
  } else {
    std::cout << vpLaserConicPose::getStatusMessage(estimator.getStatus()) << std::endl;
  }
  // --- end of snippet ---

  // The truth from the simulated ground pose, with the estimator's own convention.
  const vpColVector n = cMg.getRotationMatrix().getCol(2);
  const double d = -vpColVector::dotProd(n, vpColVector(cMg.getTranslationVector()));
  double trueAltitude = 0.0, trueRoll = 0.0, truePitch = 0.0;
  vpLaserConicPose::computeAltitudeRollPitch(vpPlane(n[0], n[1], n[2], d), trueAltitude, trueRoll, truePitch);
  const double dAlt = std::abs(estimator.getAltitude() - trueAltitude);
  const double dAngle = std::max(std::abs(estimator.getRoll() - trueRoll), std::abs(estimator.getPitch() - truePitch));
  std::cout << "laser GP3: altitude error " << dAlt * 1e3 << " mm, attitude error " << vpMath::deg(dAngle) << " deg"
            << std::endl;
  // Sub-pixel detection of a rendered stripe: millimetres and a tenth of a degree at 1 m.
  return points.size() > 100 && dAlt < 0.01 && vpMath::deg(dAngle) < 0.5;
}
} // namespace

int main()
{
  try {
    const bool gravityOk = gravityQuickStart();
    const bool laserOk = laserQuickStart();
    std::cout << (gravityOk && laserOk ? "quick start: ok" : "quick start: FAILED") << std::endl;
    return gravityOk && laserOk ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "quick start: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
