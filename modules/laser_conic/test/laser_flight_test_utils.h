/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_flight_test_utils.h
  \brief Simulated flights over a ground plane for the self-calibration and drift tests: a wide-angle
  camera with barrel distortion, the 34 degree laser 10 cm beside it, frames at random altitudes and
  attitudes, trace points from vpLaserConicSimulator with Gaussian pixel noise.
*/
#ifndef VP_LASER_FLIGHT_TEST_UTILS_H
#define VP_LASER_FLIGHT_TEST_UTILS_H

#include <random>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPlane.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

namespace laser_flight_test
{
const unsigned int kWidth = 1600, kHeight = 1200;
const double kOpening = vpMath::rad(34.0);

//! 1000 px focal length, barrel distortion kdu = 0.1 (with its fitted kud).
inline vpCameraParameters camera()
{
  return vpLaserConicSimulator::fitInverseDistortion(vpCameraParameters(1000.0, 1000.0, 805.0, 596.0, 0.0, 0.1), kWidth,
                                                     kHeight);
}

//! The true laser: apex 10 cm beside the camera, axis tilted by a few degrees.
inline vpHomogeneousMatrix laserPose()
{
  return vpHomogeneousMatrix(0.10, 0.02, 0.0, vpMath::rad(3.0), vpMath::rad(-5.0), 0.0);
}

//! Ground frame (plane Z = 0, +Z towards the camera) for a camera at \e altitude with attitude (roll, pitch).
inline vpHomogeneousMatrix groundPose(double altitude, double roll, double pitch)
{
  const vpRotationMatrix R = vpRotationMatrix(vpRxyzVector(roll, 0, 0)) * vpRotationMatrix(vpRxyzVector(0, pitch, 0));
  const vpColVector g = vpColVector(R * vpColVector(std::vector<double>{0.0, 0.0, 1.0}));
  const vpRotationMatrix cRg = R * vpRotationMatrix(vpRxyzVector(M_PI, 0, 0));
  return vpHomogeneousMatrix(vpTranslationVector(altitude * g[0], altitude * g[1], altitude * g[2]), cRg);
}

//! One frame of a flight: trace points (pixels) and the true ground plane.
struct Frame
{
  std::vector<vpImagePoint> points;
  vpPlane truth;
  vpHomogeneousMatrix cMg; //!< the ground frame (plane Z = 0): a chessboard's pose, for the grid calibration
  double altitude = 0.0, roll = 0.0, pitch = 0.0;
};

//! Settings of a flight.
struct FlightSettings
{
  unsigned int frames = 20, points = 1000;
  double maxTilt = vpMath::rad(15.0);          //!< roll and pitch uniform in +-maxTilt (0: all at tilt0)
  double roll0 = 0.0, pitch0 = 0.0;            //!< mean attitude
  double minAltitude = 0.8, maxAltitude = 1.3; //!< metres
  double noise = 0.5;                          //!< pixels
  double outliers = 0.0;                       //!< fraction of points replaced by outliers
  double openingAngle = kOpening;
  vpHomogeneousMatrix cMl = laserPose();
};

//! A flight of \e s.frames frames drawn from \e seed.
inline std::vector<Frame> flight(const FlightSettings &s, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> tilt(-1.0, 1.0), alt(s.minAltitude, s.maxAltitude);
  vpLaserConicSimulator sim;
  sim.setCamera(camera(), kWidth, kHeight);
  sim.setLaser(s.openingAngle, s.cMl);
  sim.setSeed(seed);
  std::vector<Frame> out;
  while (out.size() < s.frames) {
    Frame f;
    f.altitude = alt(rng);
    f.roll = s.roll0 + s.maxTilt * tilt(rng);
    f.pitch = s.pitch0 + s.maxTilt * tilt(rng);
    f.cMg = groundPose(f.altitude, f.roll, f.pitch);
    sim.setGroundPose(f.cMg);
    f.points = sim.addNoise(sim.tracePoints(s.points), s.noise);
    if (s.outliers > 0.0)
      f.points = sim.addOutliers(f.points, s.outliers);
    if (f.points.size() < s.points * 9 / 10)
      continue; // trace leaving the image: not an ordinary frame of this rig
    f.truth = sim.getGroundPlane();
    out.push_back(f);
  }
  return out;
}

//! Angle (rad) between the third columns of two rotations (the cone axes).
inline double axisAngle(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  const vpColVector za = a.getRotationMatrix().getCol(2), zb = b.getRotationMatrix().getCol(2);
  return std::acos(std::min(1.0, vpColVector::dotProd(za, zb)));
}

//! Angle (rad) between the apex directions of two laser poses.
inline double apexDirectionAngle(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  vpColVector ta = a.getTranslationVector(), tb = b.getTranslationVector();
  return std::acos(std::min(1.0, vpColVector::dotProd(ta.normalize(), tb.normalize())));
}
} // namespace laser_flight_test

#endif
