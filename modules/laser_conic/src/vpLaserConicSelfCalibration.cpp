/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicSelfCalibration.cpp
  \brief Facade of the self-calibration from ground frames: validation, initial planes, scale, status and
  outputs; the steps of the solve are in laser_selfcal_steps.cpp.
*/
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>

#include <cmath>
#include <sstream>

#include <visp3/core/vpMath.h>

#include "laser_selfcal_steps.h"
#include "laser_value_check.h"

using vsp::laser_value_check::require;
using vsp::laser_value_check::requireNonNegative;
using vsp::laser_value_check::requirePositive;

namespace
{

void checkPoints(const std::vector<vpImagePoint> &points)
{
  require(points.size() >= 5,
          "vpLaserConicSelfCalibration: a frame needs at least 5 laser points, got " + std::to_string(points.size()),
          vpLaserConicException::notEnoughPointError);
  // Beyond a million pixels a point is no image point, and at 1e200 the residual overflowed to 0: such points
  // counted as perfect inliers (45 % of each frame: STATUS_OK, RMS 0.07 px for 0.5 px of noise).
  for (const vpImagePoint &p : points)
    require(std::fabs(p.get_u()) <= 1e6 && std::fabs(p.get_v()) <= 1e6,
            "vpLaserConicSelfCalibration: a laser point is not finite or beyond 1e6 px",
            vpLaserConicException::badPointError);
}
} // namespace

vpLaserConicSelfCalibration::vpLaserConicSelfCalibration()
  : m_cam(), m_hasCam(false), m_hasLaser(false), m_estimateAngle(false), m_holdApex(false), m_openingAngle(0.0),
    m_apexDistance(0.0), m_maxStd(vpMath::rad(0.1)), m_maxRms(3.0), m_maxFrames(40), m_cMl(), m_frames(),
    m_status(STATUS_NOT_COMPUTED), m_details(), m_fig()
{
}

void vpLaserConicSelfCalibration::setCameraParameters(const vpCameraParameters &cam)
{
  vsp::laser_value_check::requireUsableCamera(cam, "vpLaserConicSelfCalibration");
  m_cam = cam;
  m_hasCam = true;
  m_status = STATUS_NOT_COMPUTED;
}

void vpLaserConicSelfCalibration::setLaser(double openingAngle, const vpHomogeneousMatrix &cMl)
{
  vsp::laser_value_check::requireLaserMounting(openingAngle, cMl, "vpLaserConicSelfCalibration");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
  m_hasLaser = true;
  m_status = STATUS_NOT_COMPUTED;
}

void vpLaserConicSelfCalibration::setApexDistance(double metres)
{
  requireNonNegative(metres, "vpLaserConicSelfCalibration: the apex distance must be finite and >= 0");
  m_apexDistance = metres;
  m_status = STATUS_NOT_COMPUTED;
}

void vpLaserConicSelfCalibration::setKnownAltitude(unsigned int frame, double altitude)
{
  require(frame < m_frames.size(), "vpLaserConicSelfCalibration: no frame " + std::to_string(frame));
  requirePositive(altitude, "vpLaserConicSelfCalibration: a known altitude must be positive and finite");
  m_frames[frame].knownAltitude = altitude;
  m_status = STATUS_NOT_COMPUTED;
}

void vpLaserConicSelfCalibration::setMaxFrames(unsigned int n)
{
  require(n >= 3, "vpLaserConicSelfCalibration: at least 3 frames are needed");
  m_maxFrames = n;
}

void vpLaserConicSelfCalibration::setMaxAngularStdDeviation(double radians)
{
  requirePositive(radians, "vpLaserConicSelfCalibration: the angular standard deviation limit must be positive");
  m_maxStd = radians;
}

void vpLaserConicSelfCalibration::setMaxRmsPixels(double pixels)
{
  requirePositive(pixels, "vpLaserConicSelfCalibration: the RMS limit must be positive and finite");
  m_maxRms = pixels;
}

unsigned int vpLaserConicSelfCalibration::addFrame(const std::vector<vpImagePoint> &points)
{
  checkPoints(points);
  FrameData f;
  f.points = points;
  m_frames.push_back(f);
  m_status = STATUS_NOT_COMPUTED;
  return static_cast<unsigned int>(m_frames.size() - 1);
}

unsigned int vpLaserConicSelfCalibration::addFrame(const std::vector<vpImagePoint> &points, const vpPlane &roughPlane)
{
  checkPoints(points);
  const double norm =
      std::sqrt(vpMath::sqr(roughPlane.getA()) + vpMath::sqr(roughPlane.getB()) + vpMath::sqr(roughPlane.getC()));
  require(norm > 0.0 && std::isfinite(norm) && roughPlane.getD() > 0.0 && std::isfinite(roughPlane.getD()) &&
              roughPlane.getC() < 0.0,
          "vpLaserConicSelfCalibration: the rough plane must be a finite ground plane in front of the camera "
          "(normal towards the camera, d > 0)");
  FrameData f;
  f.points = points;
  f.hasPlane = true;
  f.plane = roughPlane;
  m_frames.push_back(f);
  m_status = STATUS_NOT_COMPUTED;
  return static_cast<unsigned int>(m_frames.size() - 1);
}

void vpLaserConicSelfCalibration::clearFrames()
{
  m_frames.clear();
  m_status = STATUS_NOT_COMPUTED;
}

std::string vpLaserConicSelfCalibration::getStatusMessage(vpSelfCalibrationStatus status)
{
  switch (status) {
  case STATUS_NOT_COMPUTED:
    return "not computed";
  case STATUS_OK:
    return "ok";
  case STATUS_NOT_ENOUGH_FRAMES:
    return "not enough frames with a ground plane (at least 3)";
  case STATUS_DEGENERATE_FRAMES:
    return "degenerate frames: their attitudes relative to the ground do not span enough to determine the laser";
  case STATUS_NO_CONVERGENCE:
    return "no convergence (iteration limit reached)";
  case STATUS_SOLVER_FAILURE:
    return "solver failure or non-finite result";
  case STATUS_TOO_MANY_OUTLIERS:
    return "too many outliers: fewer than half the points fit the laser";
  case STATUS_LARGE_RESIDUALS:
    return "large residuals: the laser does not fit the traces (camera model, points)";
  }
  return "unknown status";
}

vpColVector vpLaserConicSelfCalibration::getStdDeviations() const
{
  return vsp::laser_value_check::stdDeviationsOf(m_fig.covariance, 6);
}

bool vpLaserConicSelfCalibration::fail(vpSelfCalibrationStatus status, const std::string &details)
{
  m_status = status;
  m_details = details;
  return false;
}

void vpLaserConicSelfCalibration::checkReady() const
{
  require(m_hasCam, "vpLaserConicSelfCalibration: setCameraParameters() was not called",
          vpLaserConicException::badCameraError);
  require(m_hasLaser, "vpLaserConicSelfCalibration: setLaser() (initial guess) was not called",
          vpLaserConicException::badLaserError);
  require(!m_frames.empty(), "vpLaserConicSelfCalibration: no frame", vpLaserConicException::notEnoughPointError);
  bool known = false;
  for (const FrameData &f : m_frames)
    known = known || f.knownAltitude > 0.0;
  require(m_apexDistance > 0.0 || known || m_holdApex,
          "vpLaserConicSelfCalibration: no scale constraint: images do not determine the apex distance; give "
          "setApexDistance() (ruler, previous baseline) or setKnownAltitude()");
}

bool vpLaserConicSelfCalibration::compute(vpHomogeneousMatrix &cMl, double &openingAngle)
{
  checkReady();
  m_status = STATUS_NOT_COMPUTED;
  m_details.clear();
  m_fig = Figures();
  return solve(cMl, openingAngle);
}

bool vpLaserConicSelfCalibration::solve(vpHomogeneousMatrix &cMl, double &openingAngle)
{
  using namespace vpLaserSelfCal;
  Steps steps(m_cam, m_openingAngle, m_cMl);
  std::vector<InputFrame> inputs(m_frames.size());
  for (size_t i = 0; i < m_frames.size(); ++i) {
    inputs[i].points = &m_frames[i].points;
    inputs[i].hasPlane = m_frames[i].hasPlane;
    inputs[i].plane = m_frames[i].plane;
    inputs[i].knownAltitude = m_frames[i].knownAltitude;
  }
  StepsSettings settings;
  settings.apexDistance = m_apexDistance;
  settings.estimateAngle = m_estimateAngle;
  settings.holdApex = m_holdApex;
  settings.maxFrames = m_maxFrames;
  settings.maxStd = m_maxStd;
  const StepsOutcome out = steps.run(inputs, settings);
  m_fig = out; // the figures as a whole (the outcome's base)
  // Known altitudes as the only length, none of their frames used (no plane with the initial laser): the scale
  // was free, and the refusal blamed the attitudes' spread.
  std::ostringstream dropped;
  bool knownUsed = false;
  for (size_t i = 0; i < m_frames.size(); ++i)
    if (m_frames[i].knownAltitude > 0.0) {
      const bool used = i < out.used.size() && out.used[i];
      knownUsed = knownUsed || used;
      if (!used)
        dropped << (dropped.tellp() > 0 ? ", " : "") << i;
    }
  if (!(m_apexDistance > 0.0) && !m_holdApex && !knownUsed)
    return fail(STATUS_DEGENERATE_FRAMES, "no length: the frames given a known altitude (" + dropped.str() +
                                              ") were left out (no plane with the initial laser); give "
                                              "setApexDistance() or the altitude of a frame used");
  if (out.status != STATUS_OK)
    return fail(static_cast<vpSelfCalibrationStatus>(out.status), out.details);
  if (m_fig.rms > m_maxRms) {
    std::ostringstream os;
    os << "inlier RMS " << m_fig.rms << " px > " << m_maxRms << " px";
    return fail(STATUS_LARGE_RESIDUALS, os.str());
  }
  cMl = out.cMl;
  openingAngle = out.openingAngle;
  m_status = STATUS_OK;
  return true;
}
