/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicException.h
  \brief Exception thrown by every class of the laser_conic module.
*/
#ifndef VP_LASER_CONIC_EXCEPTION_H
#define VP_LASER_CONIC_EXCEPTION_H

#include <string>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>

/*!
  \ingroup group_laser_conic
  \brief Error thrown by the laser_conic module on invalid input (the message says what is wrong).
*/
class VISP_EXPORT vpLaserConicException : public vpException
{
public:
  //! Error codes.
  enum errorCodeEnum {
    badLaserError = 1,   //!< opening angle out of (0, pi), non-finite or degenerate laser pose
    badCameraError,      //!< camera parameters unset or not positive
    notEnoughPointError, //!< fewer points than the method needs
    badPointError,       //!< non-finite coordinates
    badValueError,       //!< any other invalid setting
    notComputedError //!< a result asked for that the last computation did not produce (e.g. a covariance not requested)
  };
  //! Builds the exception with a code and a message.
  vpLaserConicException(int errorCode, const std::string &msg) : vpException(errorCode, msg) {}
};

#endif
