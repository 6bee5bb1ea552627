/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// A program of another project that finds the installed VispSensorPose package and uses both
// modules: it must compile against the installed headers, link and give the right answers.
#include <cmath>
#include <iostream>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

namespace
{
bool gravityPoseIsRecovered()
{
  const vpHomogeneousMatrix cMo(0.1, -0.05, 1.2, 0.3, -0.2, 0.5);
  vpColVector g_obj(3);
  g_obj[0] = 0.1;
  g_obj[1] = 0.2;
  g_obj[2] = -1.0;
  const vpColVector g_cam = cMo.getRotationMatrix() * g_obj;
  vpPoseGravity pose;
  pose.setCameraGravity(g_cam);
  pose.setObjectGravity(g_obj);
  const double model[3][3] = {{0, 0, 0}, {0.1, 0.1, 0}, {0.1, 0, 0}};
  for (const auto &m : model) {
    vpPoint P(m[0], m[1], m[2]);
    P.project(cMo);
    pose.addPoint(P);
  }
  vpHomogeneousMatrix estimated;
  if (!pose.computePose(vpPoseGravity::P3P, estimated))
    return false;
  const vpHomogeneousMatrix error = estimated.inverse() * cMo;
  return error.getTranslationVector().frobeniusNorm() < 1e-9;
}

bool laserPlaneIsRecovered()
{
  const vpCameraParameters cam(1200, 1200, 800, 600);
  const double opening = vpMath::rad(34);
  const vpHomogeneousMatrix cMl(0.15, 0, 0, 0, vpMath::rad(-5), 0);
  const double altitude = 1.0; // ground z = 1 m in front of the camera, fronto-parallel
  std::vector<vpImagePoint> points;
  const double half = opening / 2;
  for (int k = 0; k < 50; ++k) {
    const double g = 2 * M_PI * k / 50.0;
    const vpColVector dirL({std::sin(half) * std::cos(g), std::sin(half) * std::sin(g), std::cos(half)});
    const vpColVector dirC = cMl.getRotationMatrix() * dirL;
    const vpTranslationVector apex = cMl.getTranslationVector();
    const double lambda = (altitude - apex[2]) / dirC[2];
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(cam, (apex[0] + lambda * dirC[0]) / altitude,
                                         (apex[1] + lambda * dirC[1]) / altitude, ip);
    points.push_back(ip);
  }
  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);
  estimator.setLaser(opening, cMl);
  vpPlane plane;
  if (!estimator.computePlane(points, vpLaserConicPose::GP3, plane))
    return false;
  return std::abs(estimator.getAltitude() - altitude) < 1e-6;
}
} // namespace

int main()
{
  const bool gravityOk = gravityPoseIsRecovered();
  const bool laserOk = laserPlaneIsRecovered();
  std::cout << "vpPoseGravity through the installed package: " << (gravityOk ? "ok" : "FAILED") << std::endl;
  std::cout << "vpLaserConicPose through the installed package: " << (laserOk ? "ok" : "FAILED") << std::endl;
  return gravityOk && laserOk ? 0 : 1;
}
