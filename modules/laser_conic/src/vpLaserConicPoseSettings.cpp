/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpLaserConicPose: the settings, each validated at the API edge.
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <cmath>
#include <sstream>

void vpLaserConicPose::setArcCoverageThreshold(double radians)
{
  if (!std::isfinite(radians) || radians < 0.0 || radians > 2.0 * M_PI)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicPose: the arc coverage threshold must be in [0, 2 pi] rad");
  m_minCoverage = radians;
}

void vpLaserConicPose::setCameraParameters(const vpCameraParameters &cam)
{
  const double values[6] = {cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(), cam.get_kud(), cam.get_kdu()};
  for (double v : values)
    if (!std::isfinite(v))
      throw vpLaserConicException(vpLaserConicException::badCameraError,
                                  "vpLaserConicPose: camera parameters must be finite");
  if (!(cam.get_px() > 0.0) || !(cam.get_py() > 0.0))
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicPose: focal lengths px and py must be positive");
  if (cam.get_projModel() != vpCameraParameters::perspectiveProjWithoutDistortion &&
      cam.get_projModel() != vpCameraParameters::perspectiveProjWithDistortion)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicPose: only the perspective projection models (with or without "
                                "distortion) are supported");
  m_cam = cam;
  m_hasCam = true;
}

void vpLaserConicPose::setLaser(double openingAngle, const vpHomogeneousMatrix &cMl)
{
  if (!std::isfinite(openingAngle) || !(openingAngle > 0.0) || !(openingAngle < M_PI)) {
    std::ostringstream msg;
    msg << "vpLaserConicPose: laser opening angle " << openingAngle << " rad is not in (0, pi)";
    throw vpLaserConicException(vpLaserConicException::badLaserError, msg.str());
  }
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (!std::isfinite(cMl[i][j]))
        throw vpLaserConicException(vpLaserConicException::badLaserError,
                                    "vpLaserConicPose: the laser pose cMl is not finite");
  if (!cMl.isAnHomogeneousMatrix())
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicPose: the laser pose cMl is not a rigid transformation");
  const double baseline = std::sqrt(cMl[0][3] * cMl[0][3] + cMl[1][3] * cMl[1][3] + cMl[2][3] * cMl[2][3]);
  if (!(baseline >= 1e-9))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicPose: the laser apex is at the camera centre (zero baseline): "
                                "the ground plane is then unobservable");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
  m_hasLaser = true;
}

void vpLaserConicPose::setRansacThreshold(double pixels)
{
  if (!std::isfinite(pixels) || !(pixels > 0.0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicPose: the RANSAC threshold must be a positive number of pixels");
  m_threshold = pixels;
}

void vpLaserConicPose::setRansacMaxTrials(int trials)
{
  if (trials <= 0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicPose: the RANSAC trial budget must be positive");
  m_maxTrials = trials;
}

void vpLaserConicPose::setRansacProbability(double p)
{
  if (!std::isfinite(p) || !(p > 0.0) || !(p < 1.0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicPose: the RANSAC probability must be in (0, 1)");
  m_probability = p;
}

void vpLaserConicPose::setRansacSeed(unsigned int seed) { m_seed = seed; }

void vpLaserConicPose::setLocalOptimisation(bool enable) { m_localOptimisation = enable; }

void vpLaserConicPose::setCovarianceInflation(double varianceScale)
{
  if (!(varianceScale > 0.0) || !std::isfinite(varianceScale))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "setCovarianceInflation: the variance scale must be finite and > 0");
  m_covarianceInflation = varianceScale;
}
