/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserSequenceCalibration.h
  \brief The --from-sequence mode of vsp-laser-calibrate: self-calibration of the laser from ordinary
  frames of the ground (vpLaserConicSelfCalibration), from a points CSV or from images.
*/
#ifndef VSP_LASER_SEQUENCE_CALIBRATION_H
#define VSP_LASER_SEQUENCE_CALIBRATION_H

namespace vspLaserSequenceCalibration
{
//! True when the command line asks for the sequence mode (--from-sequence among the arguments).
bool requested(int argc, char **argv);
//! The sequence mode (its own options; see vsp-laser-calibrate.cpp). \return the exit status.
int run(int argc, char **argv);
} // namespace vspLaserSequenceCalibration

#endif
