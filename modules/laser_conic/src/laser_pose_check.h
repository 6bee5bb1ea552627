/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_pose_check.h
  \brief Private check of the rigid transformations the laser_conic classes take as input.
*/
#ifndef VP_LASER_POSE_CHECK_H
#define VP_LASER_POSE_CHECK_H

#include <cmath>

#include <visp3/core/vpHomogeneousMatrix.h>

namespace vsp::laser_pose_check
{
/*!
  True when every entry of \e M is finite and \e M is a rigid transformation up to 1e-6 (a pose read
  from a file or composed from several keeps that much rounding).
*/
inline bool isFinitePose(const vpHomogeneousMatrix &M)
{
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (!std::isfinite(M[i][j]))
        return false;
  return M.isAnHomogeneousMatrix(1e-6);
}
} // namespace vsp::laser_pose_check

#endif
