/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>

#include <visp3/laser_conic/vpLaserConicSolvers.h>
#include <visp3/robust/vpRansac.h>

#include "laser_calibration_check.h"
#include "laser_consensus.h"
#include "laser_estimators.h"
#include "laser_robust_fit.h"
#include "laser_trace_significance.h"

namespace
{
using vsp::laser_consensus::Consensus;
using vsp::laser_consensus::findConsensus;
using vsp::laser_estimators::PointList;

/*!
  Why the trace of \e result (fitted with \e settings) is no better than clutter, empty when it is (see
  laser_trace_significance.h); always empty for PLANE_PAIR, which fits every point without a consensus. The
  minimal sample of the method's RANSAC is a conic's five points (PP5) or three for a plane of the known cone.
*/
std::string clutterOf(vpLaserConicPose::vpLaserConicMethod method, const PointList &normalized,
                      const vsp::laser_robust_fit::Result &result, const vsp::laser_robust_fit::Settings &settings)
{
  if (method == vpLaserConicPose::PLANE_PAIR)
    return std::string();
  return vsp::laser_trace_significance::clutterReason(normalized, result, settings,
                                                      method == vpLaserConicPose::PP5 ? 5 : 3);
}

/*!
  Fraction of the points whose ray meets the plane in front of the camera, on the lit (forward)
  nappe of the laser cone: a plane found only through the mirrored nappes of the cone quadrics
  (behind the camera or behind the laser) explains none of them.
*/
double fractionInFront(const PointList &points, const std::vector<int> &indices, const Eigen::Vector4d &plane,
                       const vpLaserSolvers::LaserCone &cone)
{
  if (indices.empty())
    return 0.0;
  int front = 0;
  for (int i : indices) {
    const Eigen::Vector3d ray(points[i](0), points[i](1), 1.0);
    const double nr = plane.head<3>().dot(ray);
    if (!(nr < 0.0))
      continue; // the ray never reaches the plane ahead of the camera
    const Eigen::Vector3d X = (-plane(3) / nr) * ray;
    if ((X - cone.apex).dot(cone.cRl.col(2)) > 0.0)
      ++front;
  }
  return double(front) / double(indices.size());
}
} // namespace

vpLaserConicPose::vpLaserConicPose()
  : m_cam(), m_hasCam(false), m_hasLaser(false), m_openingAngle(0.0), m_cMl(), m_threshold(2.0), m_maxTrials(1000),
    m_probability(0.99), m_seed(0), m_localOptimisation(true), m_altitude(std::numeric_limits<double>::quiet_NaN()),
    m_roll(std::numeric_limits<double>::quiet_NaN()), m_pitch(std::numeric_limits<double>::quiet_NaN()), m_inliers(),
    m_trials(0), m_conic(3, 3, 0.0), m_failure(), m_status(STATUS_NOT_COMPUTED), m_nbInliersToReachConsensus(0),
    m_scaleAdaptive(true), m_minCoverage(0.5 * M_PI), m_maxAltitudeDilution(5.0),
    m_maxAttitudeUncertainty(vpMath::rad(5.0)), m_finalFit(FINAL_FIT_DEFAULT), m_computeCovariance(false),
    m_covariance(), m_planeCovariance(), m_rmsConstrained(0.0), m_rmsFree(0.0), m_sigma(0.0), m_coverage(0.0),
    m_constrainedChosen(false), m_points(), m_calibrationCheck(true), m_mistake(MISTAKE_UNKNOWN)
{
}

unsigned int vpLaserConicPose::getMinimumPointCount(vpLaserConicMethod)
{
  // The free conic of the final fit (laser_robust_fit.h) needs 5 points whatever the method's sample.
  return 5;
}

bool vpLaserConicPose::fail(vpLaserConicStatus status, const std::string &details)
{
  m_status = status;
  m_failure = getStatusMessage(status) + details;
  return false;
}

double vpLaserConicPose::getCalibrationHealth() const
{
  if (!m_fitted) // no fit to judge (not computed, or a failure before the final fit)
    return std::numeric_limits<double>::quiet_NaN();
  if (!(m_rmsFree > 0.0))
    return m_rmsConstrained > 0.0 ? std::numeric_limits<double>::infinity() : 1.0;
  return m_rmsConstrained / m_rmsFree;
}

std::vector<vpImagePoint> vpLaserConicPose::getRansacInliers() const
{
  std::vector<vpImagePoint> out;
  out.reserve(m_inliers.size());
  for (unsigned int i : m_inliers)
    out.push_back(m_points[i]);
  return out;
}

void vpLaserConicPose::computeAltitudeRollPitch(const vpPlane &cPlane, double &altitude, double &roll, double &pitch)
{
  const Eigen::Vector4d plane(cPlane.getA(), cPlane.getB(), cPlane.getC(), cPlane.getD());
  if (!plane.allFinite() || !(plane.head<3>().norm() > 0.0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicPose: the plane normal is zero or not finite");
  vpLaserSolvers::altitudeRollPitch(plane, altitude, roll, pitch);
}

namespace
{
/*!
  Normalized (undistorted) image coordinates of \e points, with ViSP's pixel-to-metre model (kdu when
  the camera has distortion), as vpLaserConicCalibration converts its points.
  \exception vpLaserConicException::badPointError on a point that is not finite or out of range.
*/
PointList normalizedPoints(const std::vector<vpImagePoint> &points, const vpCameraParameters &cam)
{
  PointList normalized;
  normalized.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const double u = points[i].get_u(), v = points[i].get_v();
    if (!std::isfinite(u) || !std::isfinite(v)) {
      std::ostringstream msg;
      msg << "vpLaserConicPose: point " << i << " is not finite";
      throw vpLaserConicException(vpLaserConicException::badPointError, msg.str());
    }
    double x = 0.0, y = 0.0;
    vpPixelMeterConversion::convertPoint(cam, u, v, x, y);
    normalized.emplace_back(x, y);
    // Squares of the coordinates must stay finite for the conic fits.
    if (!(normalized.back().cwiseAbs().maxCoeff() < 1e100)) {
      std::ostringstream msg;
      msg << "vpLaserConicPose: point " << i << " is out of range (" << u << ", " << v << ")";
      throw vpLaserConicException(vpLaserConicException::badPointError, msg.str());
    }
  }
  return normalized;
}

//! The laser cone of a laser of full opening angle \e openingAngle at pose \e cMl in the camera frame.
vpLaserSolvers::LaserCone laserCone(const vpHomogeneousMatrix &cMl, double openingAngle)
{
  vpLaserSolvers::LaserCone cone;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      cone.cRl(i, j) = cMl[i][j];
    cone.apex(i) = cMl[i][3];
  }
  cone.halfAngle = 0.5 * openingAngle;
  return cone;
}

// A ground plane closer to the camera centre than a tenth of the baseline leaves the camera and the
// laser apex on the ground: no ring could be imaged there. A wrong calibration (e.g. the half opening
// angle) can make the fit collapse onto such a plane, which must not be returned as an altitude.
bool passesThroughTheRig(const Eigen::Vector4d &plane, const vpLaserSolvers::LaserCone &cone)
{
  const double normal = plane.head<3>().norm();
  return std::fabs(plane(3)) < 0.1 * cone.apex.norm() * normal;
}

/*!
  Fits \e consensus (of \e method on \e normalized, with \e settings) into \e fit and tells whether it is a trace
  of the calibration of \e cone: at least \e needed points, a finite plane whose constrained fit the calibration
  explains (laser_calibration_check::explained()), more points than clutter would give (clutterOf()).
*/
bool explainedTrace(const PointList &normalized, vpLaserConicPose::vpLaserConicMethod method,
                    const Consensus &consensus, size_t needed, const vpLaserSolvers::LaserCone &cone,
                    const vsp::laser_robust_fit::Settings &settings, vsp::laser_robust_fit::Result &fit)
{
  return consensus.found && consensus.inliers.size() >= needed &&
         vsp::laser_robust_fit::fit(normalized, consensus.inliers, cone, consensus.startPlane, settings, fit) ==
             vsp::laser_robust_fit::Outcome::OK &&
         fit.plane.allFinite() && vsp::laser_calibration_check::explained(fit) &&
         clutterOf(method, normalized, fit, settings).empty();
}

//! PP-5's conic runs along a trace when 90 % of its points lie within this many times their distance to their
//! own conic, plus kConicAlongTraceFloor times the RANSAC threshold.
constexpr double kConicAlongTrace = 2.0;
/*!
  See kConicAlongTrace. On exact traces the clutter inside PP-5's band pulls its free conic by a few tenths of a
  pixel while the trace's own conic stays on it: a floor of 0.05 px refused such estimates, within 1 cm, and
  moved PP-5's break-down in laser-synthetic-eval from 77 to 73 % of outliers (0.5 px: 77 %).
*/
constexpr double kConicAlongTraceFloor = 0.25;

//! The \e share quantile of the distances (pixels) of the points \e indices of \e points to the conic \e C.
double distancePercentile(const Eigen::Matrix3d &C, const PointList &points, const std::vector<int> &indices,
                          double focal, double share)
{
  std::vector<double> distances;
  distances.reserve(indices.size());
  for (int i : indices)
    distances.push_back(focal * vpLaserSolvers::sampsonDistance(C, points[static_cast<size_t>(i)]));
  if (distances.empty())
    return 0.0;
  const auto at = distances.begin() + static_cast<std::ptrdiff_t>(share * static_cast<double>(distances.size() - 1));
  std::nth_element(distances.begin(), at, distances.end());
  return *at;
}

/*!
  Why PP-5's consensus, fitted into \e result, is no trace (empty when it may be one). Among many outliers each
  five-point sample is likely to hold clutter, and the best conic of a thousand may run through part of the
  trace and clutter besides: its plane pair then lies metres off (AFivePointConsensusInHeavyClutterIsCheckedAgainstTheCone).
  When the RANSAC (\e report) drew fewer samples than the consensus's own inlier ratio needs at its confidence,
  the calibrated cone's three-point consensus (GP-3, fitted with \e gp3Settings) is sought: a trace that the
  calibration explains, stands out from clutter and lies off PP-5's conic (kConicAlongTrace) shows PP-5's
  consensus to be no trace.
*/
std::string unconfirmedFivePointConsensus(const PointList &normalized, const vpLaserSolvers::LaserCone &cone,
                                          const vpRansacOptions &options, const vpRansacReport &report,
                                          const vsp::laser_robust_fit::Settings &gp3Settings,
                                          const vsp::laser_robust_fit::Result &result)
{
  namespace check = vsp::laser_calibration_check;
  const double outlierRatio = 1.0 - static_cast<double>(result.inliers.size()) / static_cast<double>(normalized.size());
  const int needed = vpRansacTrialCount(options.probability, outlierRatio, 5, std::numeric_limits<int>::max());
  if (needed <= report.trials)
    return std::string(); // searched for long enough
  const Consensus byCone = findConsensus(normalized, vpLaserConicPose::GP3, cone, options, false);
  // Any trace of the calibrated cone, however short its arc or its parallax: PP-5's conic must follow it.
  vsp::laser_robust_fit::Settings settings = gp3Settings;
  settings.maxAltitudeDilution = settings.maxAttitudeDeviation = 0.0;
  vsp::laser_robust_fit::Result trace;
  if (!explainedTrace(normalized, vpLaserConicPose::GP3, byCone,
                      vpLaserConicPose::getMinimumPointCount(vpLaserConicPose::GP3), cone, settings, trace) ||
      check::suspect(trace))
    return std::string(); // no trace of the calibrated cone to compare with
  // PP-5's conic must run along that trace as closely as the trace's own conic: its points' 90th percentile
  // distance to it was 0.8-1.0 times theirs where PP-5 had found the ring, 4-1500 times where it had not.
  const double own = distancePercentile(trace.conic, normalized, trace.inliers, gp3Settings.focal, 0.9),
               pp5 = distancePercentile(result.conic, normalized, trace.inliers, gp3Settings.focal, 0.9);
  if (!(pp5 > kConicAlongTrace * own + kConicAlongTraceFloor * gp3Settings.threshold))
    return std::string(); // PP-5's conic runs along that trace
  std::ostringstream msg;
  msg.precision(3);
  msg << " (PP5: a consensus of " << result.inliers.size() << " of " << normalized.size() << " points after "
      << report.trials << " samples, where " << needed << " are needed at that ratio; the calibrated cone's "
      << "three-point consensus (GP3) finds a trace of " << trace.inliers.size() << " points, 90 % of them within "
      << pp5 << " px of PP5's conic against " << own << " px of their own: the five-point conic mixes part of "
      << "the trace with clutter; GP3 and PP3 hold among more outliers)";
  return msg.str();
}

//! \e points with u and v exchanged.
std::vector<vpImagePoint> swappedUV(const std::vector<vpImagePoint> &points)
{
  std::vector<vpImagePoint> out(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    out[i].set_uv(points[i].get_v(), points[i].get_u());
  return out;
}
} // namespace

void vpLaserConicPose::checkInput(const std::vector<vpImagePoint> &points, vpLaserConicMethod method) const
{
  if (!m_hasCam)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicPose: call setCameraParameters() before computePlane()");
  if (!m_hasLaser)
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicPose: call setLaser() before computePlane()");
  if (method != PLANE_PAIR && method != PP5 && method != PP3 && method != GP3)
    throw vpLaserConicException(vpLaserConicException::badValueError, "vpLaserConicPose: unknown method");
  const unsigned int needed = getMinimumPointCount(method);
  if (points.size() < needed) {
    std::ostringstream msg;
    msg << "vpLaserConicPose: method " << getMethodName(method) << " needs at least " << needed << " points, got "
        << points.size();
    throw vpLaserConicException(vpLaserConicException::notEnoughPointError, msg.str());
  }
}

void vpLaserConicPose::resetEstimate(const std::vector<vpImagePoint> &points)
{
  m_failure.clear();
  m_inliers.clear();
  m_trials = 0;
  m_status = STATUS_NOT_COMPUTED;
  // Emptied by moving an empty matrix in: ViSP 3.5's resize(0, 0) frees the data, then memsets the null
  // pointer it got back (undefined behaviour, reported by UBSan).
  m_covariance = vpMatrix();
  m_planeCovariance = vpMatrix();
  m_rmsConstrained = m_rmsFree = m_sigma = m_coverage = 0.0;
  // No plane yet: a failure leaves none (the getters gave the last success's, as if it were this one's).
  m_altitude = m_roll = m_pitch = std::numeric_limits<double>::quiet_NaN();
  // The zero matrix, no conic (in place; not an empty one: ViSP 3.5 copies an empty vpMatrix by a memset of its
  // null data, which UBSan reports, and getImageConic() returns a copy).
  m_conic = 0.0;
  m_fitted = false;
  m_constrainedChosen = false;
  m_points = points;
  m_mistake = MISTAKE_UNKNOWN;
}

vpRansacOptions vpLaserConicPose::ransacOptions(double focal) const
{
  vpRansacOptions options;
  options.threshold = m_threshold / focal;
  options.probability = m_probability;
  options.maxTrials = m_maxTrials;
  options.seed = m_seed;
  options.localOptimisation = m_localOptimisation;
  return options;
}

vsp::laser_robust_fit::Settings vpLaserConicPose::finalFitSettings(vpLaserConicMethod method, double focal) const
{
  vsp::laser_robust_fit::Settings settings;
  settings.focal = focal;
  settings.threshold = m_threshold;
  settings.adaptive = m_scaleAdaptive && method != PLANE_PAIR;
  settings.minCoverage = method == PLANE_PAIR ? 0.0 : m_minCoverage;
  settings.covariance = m_computeCovariance;
  settings.maxAltitudeDilution = m_maxAltitudeDilution;
  settings.maxAttitudeDeviation = m_maxAttitudeUncertainty;
  vpLaserConicFinalFit fit = m_finalFit;
  if (fit == FINAL_FIT_DEFAULT)
    fit = (method == PP3 || method == GP3) ? FINAL_FIT_SELECT : FINAL_FIT_FREE;
  settings.finalFit = fit == FINAL_FIT_CONSTRAINED ? vsp::laser_robust_fit::FinalFit::CONSTRAINED
                      : fit == FINAL_FIT_SELECT    ? vsp::laser_robust_fit::FinalFit::SELECT
                                                   : vsp::laser_robust_fit::FinalFit::FREE;
  return settings;
}

vpLaserConicPose::vpLaserConicMistake vpLaserConicPose::suspectedMistake(const std::vector<vpImagePoint> &points,
                                                                         vpLaserConicMethod method, double *misfit,
                                                                         bool strict, size_t minTrace) const
{
  const size_t needed = std::max<size_t>(getMinimumPointCount(method), m_nbInliersToReachConsensus);
  // The estimate again under each alternative calibration: its misfit when it explains the trace, else -1.
  const auto fits = [&](const vsp::laser_calibration_check::Alternative &alternative) {
    const PointList normalized = normalizedPoints(alternative.swapUV ? swappedUV(points) : points, alternative.cam);
    const vpLaserSolvers::LaserCone cone = laserCone(alternative.cMl, alternative.openingAngle);
    const double focal = 0.5 * (alternative.cam.get_px() + alternative.cam.get_py());
    const Consensus consensus = findConsensus(normalized, method, cone, ransacOptions(focal), !m_scaleAdaptive);
    const vsp::laser_robust_fit::Settings settings = finalFitSettings(method, focal);
    vsp::laser_robust_fit::Result fit;
    if (!explainedTrace(normalized, method, consensus, needed, cone, settings, fit) ||
        fractionInFront(normalized, fit.inliers, fit.plane, cone) < 0.5 || passesThroughTheRig(fit.plane, cone) ||
        (strict && (fit.inliers.size() < minTrace || vsp::laser_calibration_check::suspect(fit))))
      return -1.0;
    return vsp::laser_calibration_check::misfit(fit);
  };
  return vsp::laser_calibration_check::diagnose(m_openingAngle, m_cMl, m_cam, fits, misfit);
}

bool vpLaserConicPose::failCalibration(vpLaserConicMistake mistake, const vsp::laser_robust_fit::Result &result,
                                       double alternativeMisfit)
{
  // The refused estimate's trace with its figures: the drift monitor's statistic needs their number.
  m_inliers.assign(result.inliers.begin(), result.inliers.end());
  m_rmsConstrained = result.rmsConstrained;
  m_rmsFree = result.rmsFree;
  m_sigma = result.sigma;
  m_coverage = result.coverage;
  m_fitted = true;
  m_mistake = mistake;
  std::ostringstream msg;
  msg << " (the constrained fit misses the trace by " << vsp::laser_calibration_check::misfit(result)
      << " px beyond the free fit, ";
  if (vsp::laser_calibration_check::explained(result))
    msg << "within the " << vsp::laser_calibration_check::tolerance(result)
        << " px allowed for an imperfect calibration, but " << alternativeMisfit << " px with the alternative; ";
  else
    msg << vsp::laser_calibration_check::tolerance(result) << " px allowed; ";
  msg << getMistakeMessage(m_mistake) << ")";
  return fail(STATUS_CALIBRATION_MISMATCH, msg.str());
}

bool vpLaserConicPose::checkCalibration(const std::vector<vpImagePoint> &points, vpLaserConicMethod method,
                                        const vsp::laser_robust_fit::Result &result)
{
  namespace check = vsp::laser_calibration_check;
  if (!m_calibrationCheck)
    return true;
  // The fit's own noise scale, or the trace's measured along it when the fit's is inflated by a model error
  // (a wrong calibration's fit on crossings of the trace and clutter).
  const double focal = 0.5 * (m_cam.get_px() + m_cam.get_py());
  if (!check::suspect(result) && !(check::misfit(result) > check::kSuspectFloorPixels &&
                                   check::suspectAtLocalNoise(normalizedPoints(points, m_cam), result, focal)))
    return true;
  // A misfit beyond the imperfect calibrations the estimators tolerate is refused whatever the
  // alternatives say; between the noise and that tolerance, only when a standard mistake explains the
  // trace markedly better (with the inverse laser pose, a fading or cluttered trace can leave a
  // misfit within the tolerance: 14 px at 0.6 px noise, or a partial trace of inflated noise scale).
  double alternative = std::numeric_limits<double>::infinity();
  if (!check::explained(result))
    return failCalibration(suspectedMistake(points, method), result, alternative);
  // The alternative must explain the whole trace (on a part of it, a shorter arc, any calibration
  // fits) within the noise, as a right calibration does.
  const vpLaserConicMistake mistake = suspectedMistake(points, method, &alternative, true, result.inliers.size());
  if (mistake != MISTAKE_UNKNOWN && alternative < check::kBetterFraction * check::misfit(result))
    return failCalibration(mistake, result, alternative);
  return true;
}

bool vpLaserConicPose::failOrMismatch(vpLaserConicStatus status, const std::string &details,
                                      const std::vector<vpImagePoint> &points, vpLaserConicMethod method)
{
  if (m_calibrationCheck)
    m_mistake = suspectedMistake(points, method);
  if (m_mistake == MISTAKE_UNKNOWN)
    return fail(status, details);
  return fail(STATUS_CALIBRATION_MISMATCH, " (" + getMistakeMessage(m_mistake) + "; with the calibration given: " +
                                               getStatusMessage(status) + details + ")");
}

void vpLaserConicPose::storeEstimate(const vsp::laser_robust_fit::Result &result, vpPlane &cPlane)
{
  const Eigen::Vector4d &plane = result.plane;
  cPlane.setABCD(plane(0), plane(1), plane(2), plane(3));
  vpLaserSolvers::altitudeRollPitch(plane, m_altitude, m_roll, m_pitch);
  m_inliers.assign(result.inliers.begin(), result.inliers.end());
  m_rmsConstrained = result.rmsConstrained;
  m_rmsFree = result.rmsFree;
  m_sigma = result.sigma;
  m_coverage = result.coverage;
  m_fitted = true;
  m_constrainedChosen = result.constrainedChosen;
  if (m_computeCovariance) {
    m_covariance.resize(3, 3);
    m_planeCovariance.resize(4, 4);
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j) {
        if (i < 3 && j < 3)
          m_covariance[i][j] = result.covariance(i, j);
        m_planeCovariance[i][j] = result.planeCovariance(i, j);
      }
  }
  // Image conic in pixels (undistorted image): x_n = K^-1 x_p, so C_p = K^-T C_n K^-1.
  Eigen::Matrix3d Kinv;
  Kinv << 1.0 / m_cam.get_px(), 0.0, -m_cam.get_u0() / m_cam.get_px(), 0.0, 1.0 / m_cam.get_py(),
      -m_cam.get_v0() / m_cam.get_py(), 0.0, 0.0, 1.0;
  const Eigen::Matrix3d pixelConic = Kinv.transpose() * result.conic * Kinv;
  for (unsigned int i = 0; i < 3; ++i) // m_conic is 3 x 3 from construction on
    for (unsigned int j = 0; j < 3; ++j)
      m_conic[i][j] = pixelConic(i, j);
}

bool vpLaserConicPose::computePlane(const std::vector<vpImagePoint> &points, vpLaserConicMethod method, vpPlane &cPlane)
{
  resetEstimate(std::vector<vpImagePoint>()); // a refused input leaves no earlier estimate to read
  checkInput(points, method);
  const PointList normalized = normalizedPoints(points, m_cam);
  m_points = points;
  if (vsp::laser_trace_significance::allCollinear(normalized))
    return fail(STATUS_COLLINEAR_POINTS);

  const vpLaserSolvers::LaserCone cone = laserCone(m_cMl, m_openingAngle);
  const double focal = 0.5 * (m_cam.get_px() + m_cam.get_py());
  const Consensus consensus = findConsensus(normalized, method, cone, ransacOptions(focal), !m_scaleAdaptive);
  if (consensus.cameraInsideCone)
    return failOrMismatch(STATUS_CAMERA_INSIDE_CONE, "", points, method);
  m_trials = consensus.report.trials;
  const size_t needed = std::max<size_t>(getMinimumPointCount(method), m_nbInliersToReachConsensus);
  if (!consensus.found || consensus.inliers.size() < needed) {
    std::ostringstream msg;
    msg << " (" << getMethodName(method) << ", " << consensus.inliers.size() << " inliers at best, " << needed
        << " needed, after " << consensus.report.trials << " samples)";
    return failOrMismatch(STATUS_NO_CONSENSUS, msg.str(), points, method);
  }

  // Final stage: the trace at its own residual scale, the arc test and the final fit (laser_robust_fit.h).
  vsp::laser_robust_fit::Result result;
  const vsp::laser_robust_fit::Settings settings = finalFitSettings(method, focal);
  switch (vsp::laser_robust_fit::fit(normalized, consensus.inliers, cone, consensus.startPlane, settings, result)) {
  case vsp::laser_robust_fit::Outcome::OK:
    break;
  case vsp::laser_robust_fit::Outcome::SHORT_ARC: {
    // The arc is the trace's, whatever the calibration (the free conic's inliers), and any calibration fits a
    // short arc: no mistake is looked for.
    std::ostringstream msg;
    msg << " (" << vpMath::deg(result.coverage) << " deg, " << vpMath::deg(m_minCoverage) << " deg needed)";
    return fail(STATUS_SHORT_ARC, msg.str());
  }
  case vsp::laser_robust_fit::Outcome::WEAK_TRACE: {
    // A mistake only as for a plane that is returned (checkCalibration()): the calibration given must miss the
    // trace it fitted first.
    if (!checkCalibration(points, method, result))
      return false;
    return fail(STATUS_WEAK_TRACE, weakTraceDetails(result));
  }
  case vsp::laser_robust_fit::Outcome::NO_PARALLAX:
    // As for a weak trace: a calibration that misses the trace it fitted is named first.
    if (!checkCalibration(points, method, result))
      return false;
    return fail(STATUS_NO_PARALLAX, parallaxDetails(result));
  case vsp::laser_robust_fit::Outcome::NOT_AN_ELLIPSE:
    return fail(STATUS_NOT_AN_ELLIPSE);
  case vsp::laser_robust_fit::Outcome::NO_PLANE:
    return failOrMismatch(STATUS_NO_PLANE_PAIR, "", points, method);
  }
  const std::string clutter = clutterOf(method, normalized, result, settings); // no trace: no more than clutter
  if (!clutter.empty())
    return fail(STATUS_NO_CONSENSUS, clutter);
  if (!result.plane.allFinite())
    return fail(STATUS_PLANE_NOT_FINITE);
  if (fractionInFront(normalized, result.inliers, result.plane, cone) < 0.5)
    return failOrMismatch(STATUS_PLANE_BEHIND, "", points, method);
  if (passesThroughTheRig(result.plane, cone)) // a ground at the rig: no calibration mistake to look for
    return fail(STATUS_PLANE_BEHIND, " (the plane passes through the camera and laser)");
  if (!checkCalibration(points, method, result))
    return false;
  if (method == PP5) {
    const std::string unconfirmed = unconfirmedFivePointConsensus(normalized, cone, ransacOptions(focal),
                                                                  consensus.report, finalFitSettings(GP3, focal),
                                                                  result);
    if (!unconfirmed.empty())
      return fail(STATUS_NO_CONSENSUS, unconfirmed);
  }

  storeEstimate(result, cPlane);
  m_status = STATUS_OK;
  return true;
}

namespace
{
//! \e covariance, or notComputedError naming \e getter when the last estimate computed none.
const vpMatrix &computedCovariance(const vpMatrix &covariance, const char *getter)
{
  if (covariance.size() == 0)
    throw vpLaserConicException(vpLaserConicException::notComputedError,
                                std::string("vpLaserConicPose::") + getter +
                                    ": no covariance computed; call setCovarianceComputation(true) before a "
                                    "successful computePlane()");
  return covariance;
}
} // namespace

vpMatrix vpLaserConicPose::getCovarianceMatrix() const
{
  return m_covarianceInflation * computedCovariance(m_covariance, "getCovarianceMatrix");
}

vpMatrix vpLaserConicPose::getPlaneCovarianceMatrix() const
{
  return m_covarianceInflation * computedCovariance(m_planeCovariance, "getPlaneCovarianceMatrix");
}
