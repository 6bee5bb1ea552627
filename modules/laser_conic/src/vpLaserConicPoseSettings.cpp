/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpLaserConicPose: the settings, each validated at the API edge.
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <cmath>

#include "laser_value_check.h"

using vsp::laser_value_check::require;
using vsp::laser_value_check::requirePositive;
using vsp::laser_value_check::requireUsableCamera;

void vpLaserConicPose::setArcCoverageThreshold(double radians)
{
  require(std::isfinite(radians) && !(radians < 0.0) && !(radians > 2.0 * M_PI),
          "vpLaserConicPose: the arc coverage threshold must be in [0, 2 pi] rad");
  m_minCoverage = radians;
}

void vpLaserConicPose::setMaxAltitudeDilution(double factor)
{
  require(std::isfinite(factor) && !(factor < 0.0),
          "vpLaserConicPose: the largest altitude dilution must be finite and >= 0");
  m_maxAltitudeDilution = factor;
}

void vpLaserConicPose::setMaxAttitudeUncertainty(double radians)
{
  require(std::isfinite(radians) && !(radians < 0.0),
          "vpLaserConicPose: the largest attitude uncertainty must be finite and >= 0");
  m_maxAttitudeUncertainty = radians;
}

void vpLaserConicPose::setCameraParameters(const vpCameraParameters &cam)
{
  requireUsableCamera(cam, "vpLaserConicPose");
  m_cam = cam;
  m_hasCam = true;
}

void vpLaserConicPose::setLaser(double openingAngle, const vpHomogeneousMatrix &cMl)
{
  vsp::laser_value_check::requireLaserMounting(openingAngle, cMl, "vpLaserConicPose");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
  m_hasLaser = true;
}

void vpLaserConicPose::setRansacThreshold(double pixels)
{
  requirePositive(pixels, "vpLaserConicPose: the RANSAC threshold must be a positive number of pixels");
  m_threshold = pixels;
}

void vpLaserConicPose::setRansacMaxTrials(int trials)
{
  require(trials > 0, "vpLaserConicPose: the RANSAC trial budget must be positive");
  m_maxTrials = trials;
}

void vpLaserConicPose::setRansacProbability(double p)
{
  require(std::isfinite(p) && p > 0.0 && p < 1.0, "vpLaserConicPose: the RANSAC probability must be in (0, 1)");
  m_probability = p;
}

void vpLaserConicPose::setRansacSeed(unsigned int seed) { m_seed = seed; }

void vpLaserConicPose::setLocalOptimisation(bool enable) { m_localOptimisation = enable; }

void vpLaserConicPose::setCovarianceInflation(double varianceScale)
{
  requirePositive(varianceScale, "setCovarianceInflation: the variance scale must be finite and > 0");
  m_covarianceInflation = varianceScale;
}
