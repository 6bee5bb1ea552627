/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_value_check.h
  \brief Private checks of the numbers the laser_conic setters take: a vpLaserConicException
  (badValueError) with the caller's message when the value is out of range.
*/
#ifndef VP_LASER_VALUE_CHECK_H
#define VP_LASER_VALUE_CHECK_H

#include <cmath>

#include <visp3/laser_conic/vpLaserConicException.h>

namespace vsp::laser_value_check
{
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
