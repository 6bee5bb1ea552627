/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laserRigSetup.h
  \brief The simulated camera/circular-laser rig shared by the laser evaluation programs and the
  generator of data/laser_sequence, so that the synthetic study and the sequence use the same rig,
  and the estimator options of the evaluation programs.
*/
#ifndef VSP_LASER_RIG_SETUP_H
#define VSP_LASER_RIG_SETUP_H

#include <cmath>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRxyzVector.h>

#include "vpCommandLine.h"

namespace vspLaserRig
{
//! Image size of the paper's uEye camera.
const unsigned int kWidth = 1600;
const unsigned int kHeight = 1200;
/*! Focal length in pixels. The paper does not give it; 1000 px (horizontal field of view 77 deg)
    keeps the whole trace in the image for altitudes 0.5-1.5 m and tilts up to 20 deg. */
const double kFocal = 1000.0;
//! Full opening angle of the laser (Z-Laser circle optic of the paper).
const double kOpeningAngleDeg = 34.0;

//! Camera intrinsics: square pixels, principal point at the image centre, no distortion.
inline vpCameraParameters camera() { return vpCameraParameters(kFocal, kFocal, kWidth / 2.0, kHeight / 2.0); }

/*! Laser pose in the camera frame: apex 15 cm to the right of and 2 cm below the camera centre,
    axis tilted by 8 deg towards the optical axis (so that the trace is centred at about 1 m), like a
    hand-held rig where both sensors look down. */
inline vpHomogeneousMatrix laserPose() { return vpHomogeneousMatrix(0.15, 0.02, 0.0, 0.0, vpMath::rad(-8.0), 0.0); }

/*!
  Pose cMg of a ground frame (ground plane Z = 0, +Z towards the camera) for a camera at \e altitude
  (m) with the attitude convention of vpLaserConicPose: the downward unit normal in the camera frame
  is g = Rx(roll) Ry(pitch) e_z. \e yaw (rotation about the ground normal) and the horizontal
  position (\e groundX, \e groundY of the camera foot in the ground frame) only move the texture.
*/
inline vpHomogeneousMatrix groundPose(double altitude, double roll, double pitch, double yaw = 0.0,
                                      double groundX = 0.0, double groundY = 0.0)
{
  // cRg maps the ground +Z to -g (towards the camera): Rx(roll) Ry(pitch) Rz(yaw) Rx(pi).
  const vpRotationMatrix Rx(vpRxyzVector(roll, 0.0, 0.0));
  const vpRotationMatrix Ry(vpRxyzVector(0.0, pitch, 0.0));
  const vpRotationMatrix Rz(vpRxyzVector(0.0, 0.0, yaw));
  const vpRotationMatrix Rflip(vpRxyzVector(M_PI, 0.0, 0.0));
  const vpRotationMatrix cRg = Rx * Ry * Rz * Rflip;
  // The camera foot (altitude * g in the camera frame) is the ground point (groundX, groundY, 0).
  const vpColVector g = vpColVector(Rx * Ry * vpColVector(std::vector<double>{0.0, 0.0, 1.0}));
  vpColVector foot(3);
  foot[0] = groundX;
  foot[1] = groundY;
  foot[2] = 0.0;
  const vpColVector t = altitude * g - vpColVector(cRg * foot);
  return vpHomogeneousMatrix(vpTranslationVector(t[0], t[1], t[2]), cRg);
}
/*!
  Options of the RANSAC estimators shared by the evaluation programs: --threshold (pixels, \e note
  says what the program does with it) and --no-local-optimisation (keeps the best minimal-sample model).
*/
inline void addEstimatorOptions(vpCommandLine &cli, double &threshold, bool &localOptimisation, const std::string &note)
{
  cli.addDouble("--threshold", threshold, "PX", "RANSAC threshold in pixels (default 2" + note + ")",
                vpCommandLine::POSITIVE);
  cli.addFlag("--no-local-optimisation", localOptimisation,
              "keep the best minimal-sample model (no least-squares refit on its inliers)", false);
}
} // namespace vspLaserRig

#endif
