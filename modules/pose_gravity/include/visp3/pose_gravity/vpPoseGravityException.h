/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpPoseGravityException.h
  \brief The exception of the pose_gravity module (vpPoseGravity, vpImuGravity).
*/
#ifndef VP_POSE_GRAVITY_EXCEPTION_H
#define VP_POSE_GRAVITY_EXCEPTION_H

#include <string>

#include <visp3/core/vpException.h>

/*!
  \ingroup group_pose_gravity
  \brief Error thrown by the classes of the pose_gravity module on invalid input (the message says
  what is wrong).
*/
class VISP_EXPORT vpPoseGravityException : public vpException
{
public:
  //! Error codes.
  enum errorCodeEnum {
    badGravityError = 1,   //!< zero, non-finite or unset gravity vector (or accelerometer reading)
    notEnoughPointError,   //!< fewer points (or IMU samples) than the method needs
    badPointError,         //!< non-finite coordinates
    degeneratePointsError, //!< duplicate or collinear object points where the method cannot use them
    badParameterError,     //!< a setting out of its range (threshold, probability, standard deviation, method)
    badFileError,          //!< unreadable or malformed input file (IMU stream, timestamps, rotation)
    notComputedError       //!< a result asked for before it was computed (e.g. the covariance)
  };
  //! Builds the exception with a code and a message.
  vpPoseGravityException(int errorCode, const std::string &msg) : vpException(errorCode, msg) {}
};

#endif
