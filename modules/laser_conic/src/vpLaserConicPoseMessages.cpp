/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpLaserConicPose: the names of the methods and the messages of the statuses.
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/core/vpMath.h>

#include "laser_robust_fit.h"

std::string vpLaserConicPose::getMethodName(vpLaserConicMethod method)
{
  switch (method) {
  case PLANE_PAIR:
    return "PLANE_PAIR";
  case PP5:
    return "PP5";
  case PP3:
    return "PP3";
  case GP3:
    return "GP3";
  }
  return "unknown";
}

std::string vpLaserConicPose::getStatusMessage(vpLaserConicStatus status)
{
  switch (status) {
  case STATUS_NOT_COMPUTED:
    return "no estimate computed yet";
  case STATUS_OK:
    return "plane found";
  case STATUS_COLLINEAR_POINTS:
    return "all points are collinear: they cannot lie on the image of the laser ellipse";
  case STATUS_NOT_AN_ELLIPSE:
    return "the least-squares conic of the points is not an ellipse";
  case STATUS_NO_CONSENSUS:
    return "no consensus: no hypothesis is supported by enough points";
  case STATUS_CAMERA_INSIDE_CONE:
    return "no epipolar tangent to the laser cone: the camera centre lies inside the laser cone";
  case STATUS_NO_PLANE_PAIR:
    return "no ground plane in the plane pair of the image conic: the conic does not match the laser cone "
           "(no real plane pair, or no plane with both optical centres on its side)";
  case STATUS_PLANE_NOT_FINITE:
    return "the estimated plane is not finite";
  case STATUS_PLANE_BEHIND:
    return "the plane is behind the system: the laser or the camera cannot see its trace there";
  case STATUS_SHORT_ARC:
    return "the trace found covers too short an arc of the laser cone: its tilt is weakly constrained";
  case STATUS_CALIBRATION_MISMATCH:
    return "the calibration does not explain the trace: the plane it constrains misses the points far beyond their "
           "noise (usual causes: the half opening angle given for the full one, lMc given for cMl, u and v swapped, "
           "intrinsics of another camera or resolution)";
  case STATUS_WEAK_TRACE:
    return "the trace found fixes the plane far less than the whole ring would: a short arc whose conic follows "
           "the noise, or a piece of a curve of the scene taken for the trace";
  case STATUS_NO_PARALLAX:
    return "the trace hardly moves with the plane, whose attitude it leaves uncertain: the laser's apex is too "
           "close to the camera for the distance of the ground (a baseline given in the wrong unit, or a ground "
           "beyond the rig's range)";
  }
  return "unknown status";
}

std::string vpLaserConicPose::parallaxDetails(const vsp::laser_robust_fit::Result &result) const
{
  const double baseline = m_cMl.getTranslationVector().frobeniusNorm();
  const double altitude = std::abs(result.plane(3)) / result.plane.head<3>().norm();
  const double focal = 0.5 * (m_cam.get_px() + m_cam.get_py());
  std::ostringstream msg;
  msg.precision(3);
  msg << " (attitude " << vpMath::deg(result.attitudeDeviation) << " deg uncertain over " << result.inliers.size()
      << " points, each taken as " << std::max(result.sigma, vsp::laser_robust_fit::kMinTraceError)
      << " px uncertain (the trace's scatter, " << vsp::laser_robust_fit::kMinTraceError << " px at least), "
      << vpMath::deg(m_maxAttitudeUncertainty) << " deg allowed, setMaxAttitudeUncertainty(); a baseline of "
      << 1000.0 * baseline << " mm at " << altitude << " m moves the ring by about " << focal * baseline / altitude
      << " px)";
  return msg.str();
}

std::string vpLaserConicPose::weakTraceDetails(const vsp::laser_robust_fit::Result &result) const
{
  std::ostringstream msg;
  msg.precision(3);
  msg << " (" << result.inliers.size() << " points, read over " << vpMath::deg(result.coverage) << " deg: ";
  if (m_maxAltitudeDilution > 0.0 && !(result.altitudeDilution <= m_maxAltitudeDilution))
    msg << "the altitude " << result.altitudeDilution << " times as uncertain as from the whole ring, "
        << m_maxAltitudeDilution << " allowed; setMaxAltitudeDilution())";
  else
    msg << "the attitude " << vpMath::deg(result.attitudeDeviation) << " deg uncertain, "
        << vpMath::deg(result.wholeAttitudeDeviation) << " deg from the whole ring, "
        << vpMath::deg(m_maxAttitudeUncertainty) << " deg allowed; setMaxAttitudeUncertainty())";
  return msg.str();
}
