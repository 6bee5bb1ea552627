/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_calibration_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vsp::laser_calibration_check
{
double misfit(const vsp::laser_robust_fit::Result &result)
{
  if (!std::isfinite(result.rmsConstrained))
    return std::numeric_limits<double>::quiet_NaN();
  const double excess = result.rmsConstrained * result.rmsConstrained - result.rmsFree * result.rmsFree;
  return excess > 0.0 ? std::sqrt(excess) : 0.0;
}

namespace
{
//! Noise scale (pixels) of a fit: the larger of its robust scale and its free fit's RMS.
double noiseScale(const vsp::laser_robust_fit::Result &result) { return std::max(result.sigma, result.rmsFree); }
} // namespace

double tolerance(const vsp::laser_robust_fit::Result &result)
{
  return std::max(kNoiseFactor * noiseScale(result), kFloorPixels);
}

bool explained(const vsp::laser_robust_fit::Result &result)
{
  const double m = misfit(result);
  return !(m > tolerance(result)); // NaN: no constrained fit to judge
}

bool suspect(const vsp::laser_robust_fit::Result &result)
{
  const double m = misfit(result);
  return m > kSuspectFactor * noiseScale(result) && m > kSuspectFloorPixels;
}

double localNoise(const vsp::laser_estimators::PointList &points, const std::vector<int> &indices,
                  const Eigen::Matrix3d &conic, double focal, double spacing)
{
  Eigen::Vector2d centre;
  if (!vsp::laser_robust_fit::ellipseCentre(conic, centre))
    return 0.0;
  std::vector<std::pair<double, int> > order;
  order.reserve(indices.size());
  for (int k : indices) {
    const Eigen::Vector2d d = points[static_cast<size_t>(k)] - centre;
    order.emplace_back(std::atan2(d.y(), d.x()), k);
  }
  std::sort(order.begin(), order.end());
  std::vector<double> distances;
  for (size_t i = 1; i + 1 < order.size(); ++i) {
    const Eigen::Vector2d &p0 = points[static_cast<size_t>(order[i - 1].second)],
                          &p1 = points[static_cast<size_t>(order[i].second)],
                          &p2 = points[static_cast<size_t>(order[i + 1].second)];
    const Eigen::Vector2d chord = p2 - p0;
    const double length = chord.norm();
    if (!(length > 0.0) || (p1 - p0).norm() > spacing || (p2 - p1).norm() > spacing)
      continue;
    const Eigen::Vector2d r = p1 - p0;
    distances.push_back(std::fabs(chord.x() * r.y() - chord.y() * r.x()) / length);
  }
  if (distances.size() < 20)
    return 0.0;
  std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
  return focal * 1.4826 * distances[distances.size() / 2] / std::sqrt(1.5);
}

bool suspectAtLocalNoise(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                         double focal)
{
  // The trace's neighbours are about a pixel apart; four leaves room for a line the detector skipped.
  const double local = localNoise(points, result.inliers, result.conic, focal, 4.0 / focal);
  return local > 0.0 && kInflatedScale * local < noiseScale(result) && misfit(result) > kSuspectFactor * local;
}

namespace
{
//! The intrinsics of an image \e scale times larger (another resolution of the same camera).
vpCameraParameters scaled(const vpCameraParameters &cam, double scale)
{
  vpCameraParameters out = cam;
  if (cam.get_projModel() == vpCameraParameters::perspectiveProjWithDistortion)
    out.initPersProjWithDistortion(scale * cam.get_px(), scale * cam.get_py(), scale * cam.get_u0(),
                                   scale * cam.get_v0(), cam.get_kud(), cam.get_kdu());
  else
    out.initPersProjWithoutDistortion(scale * cam.get_px(), scale * cam.get_py(), scale * cam.get_u0(),
                                      scale * cam.get_v0());
  return out;
}
} // namespace

vpLaserConicPose::vpLaserConicMistake diagnose(double openingAngle, const vpHomogeneousMatrix &cMl,
                                               const vpCameraParameters &cam,
                                               const std::function<double(const Alternative &)> &fits,
                                               double *bestMisfit)
{
  std::vector<Alternative> alternatives;
  if (2.0 * openingAngle < M_PI)
    alternatives.push_back({vpLaserConicPose::MISTAKE_HALF_OPENING_ANGLE, 2.0 * openingAngle, cMl, cam, false});
  alternatives.push_back({vpLaserConicPose::MISTAKE_DOUBLED_OPENING_ANGLE, 0.5 * openingAngle, cMl, cam, false});
  alternatives.push_back({vpLaserConicPose::MISTAKE_INVERSE_LASER_POSE, openingAngle, cMl.inverse(), cam, false});
  alternatives.push_back({vpLaserConicPose::MISTAKE_SWAPPED_UV, openingAngle, cMl, cam, true});
  alternatives.push_back({vpLaserConicPose::MISTAKE_CAMERA_RESOLUTION, openingAngle, cMl, scaled(cam, 2.0), false});
  alternatives.push_back({vpLaserConicPose::MISTAKE_CAMERA_RESOLUTION, openingAngle, cMl, scaled(cam, 0.5), false});
  vpLaserConicPose::vpLaserConicMistake best = vpLaserConicPose::MISTAKE_UNKNOWN;
  double smallest = std::numeric_limits<double>::infinity();
  for (const Alternative &alternative : alternatives) {
    const double m = fits(alternative);
    if (m >= 0.0 && m < smallest) {
      smallest = m;
      best = alternative.mistake;
    }
  }
  if (bestMisfit)
    *bestMisfit = smallest;
  return best;
}
} // namespace vsp::laser_calibration_check

std::string vpLaserConicPose::getMistakeMessage(vpLaserConicMistake mistake)
{
  switch (mistake) {
  case MISTAKE_UNKNOWN:
    return "no standard mistake explains the trace";
  case MISTAKE_HALF_OPENING_ANGLE:
    return "the trace fits twice the opening angle: the half angle was given, setLaser() takes the full one";
  case MISTAKE_DOUBLED_OPENING_ANGLE:
    return "the trace fits half the opening angle: give the full angle, not twice it";
  case MISTAKE_INVERSE_LASER_POSE:
    return "the trace fits the inverse laser pose: lMc was given, setLaser() takes cMl (the laser in the camera frame)";
  case MISTAKE_SWAPPED_UV:
    return "the trace fits with u and v exchanged: vpImagePoint(i, j) takes (v, u), row first";
  case MISTAKE_CAMERA_RESOLUTION:
    return "the trace fits the intrinsics scaled by 2 or 1/2: the camera parameters are those of another resolution";
  }
  return "unknown mistake";
}
