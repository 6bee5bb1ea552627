/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_value_check.h
  \brief Private checks of the values the laser_conic setters take, and the standard deviations the
  calibrations report (stdDeviationsOf()): a vpLaserConicException
  (badValueError unless said otherwise) with the caller's message when the value is refused. The
  laser_conic setters check their values through these (the detector through its check(), which names the
  class), so that a check, the camera's and the opening angle's among them, is written once.
*/
#ifndef VP_LASER_VALUE_CHECK_H
#define VP_LASER_VALUE_CHECK_H

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/laser_conic/vpLaserConicException.h>

#include "laser_pose_check.h"

namespace vsp::laser_value_check
{
/*!
  The standard deviations of the \e n first parameters of \e covariance: the square roots of its diagonal,
  a NaN kept as NaN (a failed or singular estimate's covariance; std::max(0, NaN) would read it as 0, known
  exactly).
*/
inline vpColVector stdDeviationsOf(const vpMatrix &covariance, unsigned int n)
{
  vpColVector sigma(n, 0.0);
  for (unsigned int k = 0; k < n; ++k) {
    const double v = covariance[k][k];
    sigma[k] = std::isnan(v) ? v : std::sqrt(std::max(0.0, v));
  }
  return sigma;
}

/*!
  Whether \e roll and \e pitch (rad, vpLaserConicPose's convention) describe a ground the camera looks at: both
  within (-pi/2, pi/2), as every estimate gives them (the downward normal's z component cos(roll) cos(pitch) is
  positive). Angles outside are no attitude over the ground; most often degrees passed as radians.
*/
inline bool isGroundAttitude(double roll, double pitch)
{
  return std::fabs(roll) < M_PI_2 && std::fabs(pitch) < M_PI_2;
}

//! Throws vpLaserConicException with \e code and \e message unless \e ok (the checks that are not ranges).
inline void require(bool ok, const std::string &message,
                    vpLaserConicException::errorCodeEnum code = vpLaserConicException::badValueError)
{
  if (!ok)
    throw vpLaserConicException(code, message);
}

//! Throws vpLaserConicException::badValueError with \e message unless \e value is finite and > 0.
inline void requirePositive(double value, const char *message)
{
  if (!std::isfinite(value) || !(value > 0.0))
    throw vpLaserConicException(vpLaserConicException::badValueError, message);
}

//! Throws vpLaserConicException::badValueError with \e message unless \e value is finite and >= 0.
inline void requireNonNegative(double value, const char *message)
{
  if (!std::isfinite(value) || value < 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError, message);
}
/*!
  Throws vpLaserConicException::badLaserError, the message beginning with \e who and giving the value, unless
  \e openingAngle, the cone's full opening angle, is finite and in (0, pi) radians.
*/
inline void requireOpeningAngle(double openingAngle, const std::string &who)
{
  if (std::isfinite(openingAngle) && openingAngle > 0.0 && openingAngle < M_PI)
    return;
  std::ostringstream message;
  message << who << ": the laser's full opening angle " << openingAngle << " rad is not in (0, pi)";
  throw vpLaserConicException(vpLaserConicException::badLaserError, message.str());
}

/*!
  Throws vpLaserConicException::badCameraError, the message beginning with \e who, unless \e cam can be used
  by the laser classes: px, py, u0, v0, kud and kdu finite, px and py positive, one of the two perspective
  models (the laser classes convert pixels with kdu and project with kud; the Kannala-Brandt model is not
  one they apply). The same check for every class, so that no class computes silently with a camera another
  refuses.
*/
inline void requireUsableCamera(const vpCameraParameters &cam, const std::string &who)
{
  const double values[6] = {cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(), cam.get_kud(), cam.get_kdu()};
  for (double v : values)
    require(std::isfinite(v), who + ": camera parameters must be finite", vpLaserConicException::badCameraError);
  require(cam.get_px() > 0.0 && cam.get_py() > 0.0, who + ": focal lengths px and py must be positive",
          vpLaserConicException::badCameraError);
  require(cam.get_projModel() == vpCameraParameters::perspectiveProjWithoutDistortion ||
              cam.get_projModel() == vpCameraParameters::perspectiveProjWithDistortion,
          who + ": only the perspective projection models (with or without distortion) are supported",
          vpLaserConicException::badCameraError);
}

/*!
  Throws vpLaserConicException::badLaserError, the message beginning with \e who, unless the laser pose \e cMl
  is a finite rigid transformation (laser_pose_check::isFinitePose()).
*/
inline void requireLaserPose(const vpHomogeneousMatrix &cMl, const std::string &who)
{
  require(laser_pose_check::isFinitePose(cMl), who + ": the laser pose cMl is not a finite rigid transformation",
          vpLaserConicException::badLaserError);
}

/*!
  The laser of a class that estimates from images: requireOpeningAngle(), requireLaserPose(), and the apex
  away from the camera centre (at it, the imaged conic is that of the cone alone, whatever the ground: the
  ground plane is unobservable). Throws vpLaserConicException::badLaserError, the message beginning with \e who.
*/
inline void requireLaserMounting(double openingAngle, const vpHomogeneousMatrix &cMl, const std::string &who)
{
  requireOpeningAngle(openingAngle, who);
  requireLaserPose(cMl, who);
  require(cMl.getTranslationVector().frobeniusNorm() >= 1e-9,
          who + ": the laser apex is at the camera centre (zero baseline): the ground plane is then unobservable",
          vpLaserConicException::badLaserError);
}
} // namespace vsp::laser_value_check

#endif
