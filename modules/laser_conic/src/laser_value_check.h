/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_value_check.h
  \brief Private checks of the values the laser_conic setters take: a vpLaserConicException
  (badValueError unless said otherwise) with the caller's message when the value is refused, so that a
  check is written once (the settings of vpLaserConicPose and of the two calibration classes).
*/
#ifndef VP_LASER_VALUE_CHECK_H
#define VP_LASER_VALUE_CHECK_H

#include <cmath>
#include <string>

#include <visp3/laser_conic/vpLaserConicException.h>

namespace vsp::laser_value_check
{
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
} // namespace vsp::laser_value_check

#endif
