/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicCalibration.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>

#include "laser_calibration_problem.h"
#include "laser_pose_check.h"
#include "laser_value_check.h"

using namespace vsp::laser_calibration;

vpLaserConicCalibration::vpLaserConicCalibration()
  : m_cam(), m_hasCam(false), m_hasGuess(false), m_estimateAngle(false), m_jackknife(false), m_openingAngle(0.0),
    m_guess(), m_loss(LOSS_CAUCHY), m_userLossScale(0.0), m_maxIterations(200), m_maxCondition(1e5),
    m_maxRmsPixels(3.0), m_views(), m_status(STATUS_NOT_COMPUTED), m_statusDetails(), m_rms(0.0), m_rmsPixels(0.0),
    m_initialRms(0.0), m_openingAngleEstimate(0.0), m_lossScale(0.0), m_condition(0.0), m_nbInliers(0),
    m_covariance(kNbConeParams, kNbConeParams, 0.0), m_hasJackknifeStd(false), m_jackknifeStd(kNbConeParams, 0.0),
    m_predicted(), m_initialPredicted(), m_measured(), m_inlier()
{
}

void vpLaserConicCalibration::setCameraParameters(const vpCameraParameters &cam)
{
  vsp::laser_value_check::requireUsableCamera(cam, "vpLaserConicCalibration");
  m_cam = cam;
  m_hasCam = true;
}

void vpLaserConicCalibration::setOpeningAngle(double openingAngle)
{
  vsp::laser_value_check::requireOpeningAngle(openingAngle, "vpLaserConicCalibration");
  const double lowest = vsp::laser_calibration::kMinOpening;
  if (!(openingAngle >= lowest && openingAngle <= M_PI - lowest))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the laser's full opening angle must be in [1e-3, pi - 1e-3] "
                                "rad (the solver's bounds)");
  m_openingAngle = openingAngle;
  m_openingAngleEstimate = openingAngle;
}

void vpLaserConicCalibration::setRobustLoss(vpLaserConicLoss loss, double scale)
{
  vsp::laser_value_check::requireNonNegative(scale, "vpLaserConicCalibration: the robust loss scale must be finite and "
                                                    ">= 0 (0: automatic)");
  vsp::laser_value_check::require(loss == LOSS_NONE || loss == LOSS_HUBER || loss == LOSS_CAUCHY,
                                  "vpLaserConicCalibration: unknown robust loss");
  m_loss = loss;
  m_userLossScale = scale;
}

void vpLaserConicCalibration::setMaxIterations(int maxIterations)
{
  vsp::laser_value_check::require(maxIterations > 0, "vpLaserConicCalibration: the iteration limit must be positive");
  m_maxIterations = maxIterations;
}

void vpLaserConicCalibration::setMaxRmsPixels(double maxRms)
{
  vsp::laser_value_check::requirePositive(maxRms,
                                          "vpLaserConicCalibration: the largest RMS must be positive and finite");
  m_maxRmsPixels = maxRms;
}

void vpLaserConicCalibration::setMaxConditionNumber(double maxCondition)
{
  vsp::laser_value_check::require(maxCondition > 1.0,
                                  "vpLaserConicCalibration: the largest condition number must be greater than 1");
  m_maxCondition = maxCondition;
}

void vpLaserConicCalibration::setInitialGuess(const vpHomogeneousMatrix &cMl)
{
  vsp::laser_value_check::requireLaserPose(cMl, "vpLaserConicCalibration: the initial guess");
  m_guess = cMl;
  m_hasGuess = true;
}

void vpLaserConicCalibration::addView(const vpHomogeneousMatrix &cMg, const std::vector<vpImagePoint> &laserPoints)
{
  if (!vsp::laser_pose_check::isFinitePose(cMg))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the grid pose is not a finite rigid transformation");
  if (laserPoints.size() < 5) {
    std::ostringstream os;
    os << "vpLaserConicCalibration: a view needs at least 5 laser points, got " << laserPoints.size();
    throw vpLaserConicException(vpLaserConicException::notEnoughPointError, os.str());
  }
  for (const vpImagePoint &p : laserPoints)
    if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v()))
      throw vpLaserConicException(vpLaserConicException::badPointError,
                                  "vpLaserConicCalibration: a laser point has non-finite coordinates");
  View view;
  view.cMg = cMg;
  view.points = laserPoints;
  m_views.push_back(view);
  m_status = STATUS_NOT_COMPUTED;
}

void vpLaserConicCalibration::clearViews()
{
  m_views.clear();
  m_predicted.clear();
  m_measured.clear();
  m_inlier.clear();
  m_status = STATUS_NOT_COMPUTED;
}

unsigned int vpLaserConicCalibration::getNbPoints() const
{
  size_t n = 0;
  for (const View &view : m_views)
    n += view.points.size();
  return static_cast<unsigned int>(n);
}

vpColVector vpLaserConicCalibration::getStdDeviations() const
{
  return vsp::laser_value_check::stdDeviationsOf(m_covariance, kNbConeParams);
}

std::string vpLaserConicCalibration::getStatusMessage(vpLaserConicCalibrationStatus status)
{
  switch (status) {
  case STATUS_NOT_COMPUTED:
    return "the calibration has not been computed";
  case STATUS_OK:
    return "calibration OK";
  case STATUS_NOT_ENOUGH_VIEWS:
    return "not enough views: give at least 2 grid views (better 6 or more, at several distances and tilts)";
  case STATUS_DEGENERATE_VIEWS:
    return "degenerate views: the grids do not determine the laser cone; show the grid at several distances "
           "and tilts";
  case STATUS_NO_CONVERGENCE:
    return "no convergence: the optimisation stopped at the iteration limit (bad initial guess or bad data)";
  case STATUS_SOLVER_FAILURE:
    return "solver failure: the optimisation failed or gave a non-finite result";
  case STATUS_TOO_MANY_OUTLIERS:
    return "too many outliers: fewer than half the laser points lie on the fitted cone";
  case STATUS_LARGE_RESIDUALS:
    return "large residuals: the fitted cone does not explain the laser points (too many outliers, wrong camera "
           "model or wrong grid poses)";
  }
  return "unknown status";
}

bool vpLaserConicCalibration::fail(vpLaserConicCalibrationStatus status, const std::string &details)
{
  // No covariance of a failed run: a run refused for its residuals had filled it, and read as a result.
  m_covariance = vpMatrix(kNbConeParams, kNbConeParams, std::numeric_limits<double>::quiet_NaN());
  m_status = status;
  m_statusDetails = details;
  return false;
}

void vpLaserConicCalibration::checkReady(const vpHomogeneousMatrix &guess) const
{
  if (!m_hasCam)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicCalibration: call setCameraParameters() before compute()");
  if (!(m_openingAngle > 0.0))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: call setOpeningAngle() before compute()");
  if (m_views.empty())
    throw vpLaserConicException(vpLaserConicException::notEnoughPointError,
                                "vpLaserConicCalibration: no view added, call addView() before compute()");
  if (!vsp::laser_pose_check::isFinitePose(guess))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the initial guess is not a finite rigid transformation");
}

void vpLaserConicCalibration::backProject()
{
  // Measured points: back-projection of each laser pixel (undistorted by vpPixelMeterConversion with the
  // camera's model) on its grid plane, in grid coordinates.
  m_measured.assign(m_views.size(), {});
  for (size_t j = 0; j < m_views.size(); ++j) {
    const vpHomogeneousMatrix &cMg = m_views[j].cMg;
    const vpHomogeneousMatrix gMc = cMg.inverse();
    const double n[3] = {cMg[0][2], cMg[1][2], cMg[2][2]};
    const double nDotOrigin = n[0] * cMg[0][3] + n[1] * cMg[1][3] + n[2] * cMg[2][3];
    for (const vpImagePoint &p : m_views[j].points) {
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(m_cam, p, x, y);
      const double denom = n[0] * x + n[1] * y + n[2];
      const double depth = nDotOrigin / denom; // Z of the ray/plane intersection
      if (!std::isfinite(depth) || !(depth > 0.0) || std::fabs(denom) < 1e-12) {
        std::ostringstream os;
        os << "vpLaserConicCalibration: laser point (" << p.get_u() << ", " << p.get_v() << ") of view " << j
           << " does not back-project in front of the camera on the grid plane";
        throw vpLaserConicException(vpLaserConicException::badPointError, os.str());
      }
      const double Pc[3] = {x * depth, y * depth, depth};
      const double X = gMc[0][0] * Pc[0] + gMc[0][1] * Pc[1] + gMc[0][2] * Pc[2] + gMc[0][3];
      const double Y = gMc[1][0] * Pc[0] + gMc[1][1] * Pc[1] + gMc[1][2] * Pc[2] + gMc[1][3];
      m_measured[j].push_back(std::make_pair(X, Y));
    }
  }
}

void vpLaserConicCalibration::resetResults()
{
  m_status = STATUS_NOT_COMPUTED;
  m_statusDetails.clear();
  m_covariance = vpMatrix(kNbConeParams, kNbConeParams, 0.0);
  m_hasJackknifeStd = false;
  m_jackknifeStd = vpColVector(kNbConeParams, 0.0);
  m_condition = 0.0;
  m_nbInliers = 0;
  m_rms = m_rmsPixels = 0.0;
  m_initialRms = 0.0; // an earlier run's stayed readable after a run that failed before its first stage
  m_lossScale = 0.0;
  m_predicted.clear();
  m_initialPredicted.clear();
  m_inlier.clear();
  m_openingAngleEstimate = m_openingAngle;
}

bool vpLaserConicCalibration::checkViewSet(const std::vector<vpHomogeneousMatrix> &cMg)
{
  if (cMg.size() < 2) {
    std::ostringstream os;
    os << cMg.size() << " view given";
    return fail(STATUS_NOT_ENOUGH_VIEWS, os.str());
  }
  if (!hasTwoGridPlanes(cMg)) {
    std::ostringstream os;
    os << "all the " << cMg.size() << " grids lie in one plane (normals within " << kSamePlaneAngleDeg
       << " deg, distances within " << 100.0 * kSamePlaneDistanceRatio << " %)";
    return fail(STATUS_DEGENERATE_VIEWS, os.str());
  }
  return true;
}

bool vpLaserConicCalibration::fitCone(ConeProblem &cone)
{
  std::string error;
  if (!cone.fitGammas(error))
    return fail(STATUS_SOLVER_FAILURE, error);
  m_initialRms = cone.gridRms(false);
  m_initialPredicted = cone.predictedGridPoints(m_measured);
  cone.releaseCone(m_estimateAngle);
  if (m_loss != LOSS_NONE) {
    double scale = 0.0;
    if (!cone.fitRobust(m_loss, m_userLossScale, scale, error))
      return fail(STATUS_SOLVER_FAILURE, error);
    m_lossScale = scale;
  }
  m_nbInliers = cone.nbInliers();
  const unsigned int nbPoints = getNbPoints();
  if (2 * m_nbInliers < nbPoints) {
    std::ostringstream os;
    os << m_nbInliers << " of " << nbPoints << " points within 3 x " << m_lossScale << " px of the cone";
    return fail(STATUS_TOO_MANY_OUTLIERS, os.str());
  }
  ceres::Solver::Summary summary;
  if (!cone.fitInliers(summary))
    return fail(STATUS_SOLVER_FAILURE, "final stage: " + summary.message);
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    std::ostringstream os;
    os << "final stage stopped after " << summary.iterations.size() - 1 << " iterations: " << summary.message;
    return fail(STATUS_NO_CONVERGENCE, os.str());
  }
  if (!cone.isFinite())
    return fail(STATUS_SOLVER_FAILURE, "non-finite result");
  return true;
}

bool vpLaserConicCalibration::computeCovariance(ConeProblem &cone)
{
  // Observability: conditioning of the reduced normal equations with the angles in metres at the grids.
  double rss = 0.0;
  const ConeMatrix S = cone.reducedNormalMatrix(rss);
  m_rmsPixels = std::sqrt(rss / static_cast<double>(m_nbInliers));
  m_rms = cone.gridRms(true);
  const int p = m_estimateAngle ? kNbConeParams : kNbConeParams - 1;
  Eigen::VectorXd scaling = Eigen::VectorXd::Ones(p);
  scaling[kAlpha] = scaling[kBeta] = 1.0 / cone.meanDistance();
  if (m_estimateAngle)
    scaling[kOpening] = 1.0 / cone.meanDistance();
  const Eigen::MatrixXd Sp = S.topLeftCorner(p, p);
  const Eigen::MatrixXd scaled = scaling.asDiagonal() * Sp * scaling.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled, Eigen::EigenvaluesOnly);
  const double lambdaMin = eig.eigenvalues()[0], lambdaMax = eig.eigenvalues()[p - 1];
  m_condition = lambdaMin > 0.0 ? lambdaMax / lambdaMin : std::numeric_limits<double>::infinity();
  if (!(m_condition <= m_maxCondition)) {
    std::ostringstream os;
    os << "ill-conditioned normal equations: condition number " << m_condition << " > " << m_maxCondition;
    return fail(STATUS_DEGENERATE_VIEWS, os.str());
  }
  const double dof = static_cast<double>(m_nbInliers) - static_cast<double>(p); // 2N residuals, N + p unknowns
  const Eigen::MatrixXd covariance = (rss / std::max(1.0, dof)) * Sp.inverse();
  for (int r = 0; r < p; ++r)
    for (int c = 0; c < p; ++c)
      m_covariance[r][c] = covariance(r, c);
  return true;
}

bool vpLaserConicCalibration::compute(vpHomogeneousMatrix &cMl)
{
  const vpHomogeneousMatrix guess = m_hasGuess ? m_guess : cMl;
  checkReady(guess);
  resetResults();
  backProject();
  std::vector<vpHomogeneousMatrix> cMg;
  for (const View &view : m_views)
    cMg.push_back(view.cMg);
  if (!checkViewSet(cMg))
    return false;
  ConeProblem cone(cMg, m_measured, m_cam, guess, m_openingAngle, m_maxIterations);
  if (!fitCone(cone))
    return false;
  // A cone's two nappes fit the same points: from a guess whose axis points away from the grids (turned by
  // 150-180 degrees) the fit took the nappe behind the laser, a cone no laser projects (apex 0.1 mm off, axis
  // 180 degrees off), and ended STATUS_OK. The same cone with its axis turned over is fitted again from there:
  // its forward nappe is the same set of rays, so the refit starts at its minimum.
  if (gridsBehind(cone.pose(), cMg)) {
    ConeProblem turned(cMg, m_measured, m_cam, cone.pose() * vpHomogeneousMatrix(0, 0, 0, M_PI, 0, 0), m_openingAngle,
                       m_maxIterations);
    const double initialRms = m_initialRms; // the figures of the caller's guess, not of the turned cone
    const auto initialPredicted = m_initialPredicted;
    const bool fitted = fitCone(turned);
    m_initialRms = initialRms;
    m_initialPredicted = initialPredicted;
    if (!fitted)
      return false;
    if (gridsBehind(turned.pose(), cMg))
      return fail(STATUS_SOLVER_FAILURE, "the fitted cone's axis points away from the grids");
    return checkInlierViews(turned, cMg) && finishCone(turned, cMl);
  }
  return checkInlierViews(cone, cMg) && finishCone(cone, cMl);
}

bool vpLaserConicCalibration::checkInlierViews(const ConeProblem &cone, const std::vector<vpHomogeneousMatrix> &cMg)
{
  // The one-plane refusal again, on the views the fit kept: a view counts when more than half of its points are
  // inliers. Four views of one plane and a fifth of clutter on another, whose points the robust stage set
  // aside but for a few it passed the cone through, ended STATUS_OK with the axis 11.7 degrees off.
  const std::vector<std::vector<bool> > flags = cone.inlierFlags(cMg.size());
  std::vector<vpHomogeneousMatrix> kept;
  for (size_t v = 0; v < cMg.size() && v < flags.size(); ++v) {
    const size_t inliers = static_cast<size_t>(std::count(flags[v].begin(), flags[v].end(), true));
    if (2 * inliers > flags[v].size())
      kept.push_back(cMg[v]);
  }
  if (kept.size() >= 2 && hasTwoGridPlanes(kept))
    return true;
  std::ostringstream os;
  os << "the " << kept.size() << " views that keep more than half of their points as inliers do not show two grid "
     << "planes; the other " << cMg.size() - kept.size() << " view(s) are mostly outliers";
  return fail(STATUS_DEGENERATE_VIEWS, os.str());
}

bool vpLaserConicCalibration::gridsBehind(const vpHomogeneousMatrix &cMl, const std::vector<vpHomogeneousMatrix> &cMg)
{
  // The laser points of the grids along the laser's axis, from its apex: most ahead for the cone that lights them.
  const vpHomogeneousMatrix lMc = cMl.inverse();
  size_t behind = 0, all = 0;
  for (size_t v = 0; v < cMg.size() && v < m_measured.size(); ++v) {
    const vpHomogeneousMatrix lMg = lMc * cMg[v];
    for (const std::pair<double, double> &p : m_measured[v]) {
      const double z = lMg[2][0] * p.first + lMg[2][1] * p.second + lMg[2][3];
      behind += z < 0.0 ? 1 : 0;
      ++all;
    }
  }
  return 2 * behind > all;
}

bool vpLaserConicCalibration::finishCone(ConeProblem &cone, vpHomogeneousMatrix &cMl)
{
  if (!computeCovariance(cone))
    return false;
  // The inliers' residuals must look like detection noise: a cone fitted to mostly outliers (whose
  // median then sets the loss scale), to a wrong camera model or to wrong grid poses does not.
  if (!(m_rmsPixels <= m_maxRmsPixels)) {
    std::ostringstream os;
    os << "RMS " << m_rmsPixels << " px > " << m_maxRmsPixels << " px over " << m_nbInliers << " points";
    return fail(STATUS_LARGE_RESIDUALS, os.str());
  }
  // Results, predicted points and inlier flags for figures.
  m_predicted = cone.predictedGridPoints(m_measured);
  m_inlier = cone.inlierFlags(m_views.size());
  m_openingAngleEstimate = cone.openingAngle();
  m_status = STATUS_OK;
  cMl = cone.pose();
  if (m_jackknife)
    computeJackknife(cMl);
  return true;
}

void vpLaserConicCalibration::computeJackknife(const vpHomogeneousMatrix &cMl)
{
  const size_t n = m_views.size();
  std::vector<vpColVector> estimates;
  for (size_t k = 0; k < n; ++k) {
    vpLaserConicCalibration without(*this);
    without.m_jackknife = false;
    without.m_views.erase(without.m_views.begin() + static_cast<std::ptrdiff_t>(k));
    without.setInitialGuess(cMl);
    without.setOpeningAngle(m_openingAngleEstimate);
    vpHomogeneousMatrix M;
    if (!without.compute(M))
      return; // a view set that needs every view: no jackknife
    double alpha = 0.0, beta = 0.0;
    axisAngles(M, alpha, beta);
    vpColVector theta(kNbConeParams);
    theta[kAlpha] = alpha;
    theta[kBeta] = beta;
    for (unsigned int i = 0; i < 3; ++i)
      theta[kVx + i] = M[i][3];
    theta[kOpening] = without.getOpeningAngle();
    estimates.push_back(theta);
  }
  vpColVector mean(kNbConeParams, 0.0);
  for (const vpColVector &theta : estimates)
    mean += theta / static_cast<double>(n);
  for (const vpColVector &theta : estimates)
    for (unsigned int i = 0; i < kNbConeParams; ++i)
      m_jackknifeStd[i] += (theta[i] - mean[i]) * (theta[i] - mean[i]);
  for (unsigned int i = 0; i < kNbConeParams; ++i)
    m_jackknifeStd[i] = std::sqrt(m_jackknifeStd[i] * static_cast<double>(n - 1) / static_cast<double>(n));
  if (!m_estimateAngle)
    m_jackknifeStd[kOpening] = 0.0;
  m_hasJackknifeStd = true;
}

double vpLaserConicCalibration::calibrate(vpHomogeneousMatrix &cMl)
{
  if (!compute(cMl)) {
    std::string msg = "vpLaserConicCalibration: " + getStatusMessage(m_status);
    if (!m_statusDetails.empty())
      msg += " (" + m_statusDetails + ")";
    throw vpLaserConicException(vpLaserConicException::badValueError, msg);
  }
  return m_rms;
}
