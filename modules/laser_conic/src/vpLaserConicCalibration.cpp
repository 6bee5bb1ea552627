/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicCalibration.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>

#include "laser_pose_check.h"

namespace
{
// Parameter vector of the cone, in the order of the covariance matrix.
enum { kAlpha = 0, kBeta, kVx, kVy, kVz, kOpening, kNbConeParams };

// Direction of the cone ray gamma in the camera frame, D' = Rx(alpha) Ry(beta) Rz(gamma) (sin h, 0, cos h)
// with h the half opening angle (paper eq. 58-59).
template <typename T>
void coneRay(const T &alpha, const T &beta, const T &gamma, const T &halfAngle, T D[3])
{
  using std::cos;
  using std::sin;
  const T sinHalf = sin(halfAngle);
  const T dx = sinHalf * cos(gamma), dy = sinHalf * sin(gamma), dz = cos(halfAngle);
  const T cb = cos(beta), sb = sin(beta), ca = cos(alpha), sa = sin(alpha);
  const T x = cb * dx + sb * dz, z = -sb * dx + cb * dz; // Ry(beta) leaves y = dy
  D[0] = x;                                               // Rx(alpha)
  D[1] = ca * dy - sa * z;
  D[2] = sa * dy + ca * z;
}

// Residual of one laser point: predicted minus measured XY on its grid plane (paper eq. 60-65), mapped to
// pixels by W, the Jacobian of the grid-to-image projection at the measured point. The noise of the
// points is isotropic in the image, not on the grids (a far or oblique grid stretches it): the mapping
// makes the residuals equally weighted, as the covariance assumes, and the loss scale a pixel distance.
// Parameter blocks: (alpha, beta), apex, gamma_i, full opening angle.
struct GridPointResidual
{
  GridPointResidual(const vpHomogeneousMatrix &gMc, double X, double Y, const double W[4]) : m_X(X), m_Y(Y)
  {
    for (unsigned int k = 0; k < 4; ++k)
      m_W[k] = W[k];
    for (unsigned int i = 0; i < 3; ++i) {
      for (unsigned int j = 0; j < 3; ++j)
        m_S[3 * i + j] = gMc[i][j];
      m_t[i] = gMc[i][3];
    }
  }

  template <typename T>
  bool operator()(const T *const angles, const T *const apex, const T *const gamma, const T *const opening,
                  T *r) const
  {
    T D[3];
    coneRay(angles[0], angles[1], gamma[0], T(0.5) * opening[0], D);
    T Dg[3], vg[3];
    for (int i = 0; i < 3; ++i) {
      Dg[i] = m_S[3 * i] * D[0] + m_S[3 * i + 1] * D[1] + m_S[3 * i + 2] * D[2];
      vg[i] = m_S[3 * i] * apex[0] + m_S[3 * i + 1] * apex[1] + m_S[3 * i + 2] * apex[2] + m_t[i];
    }
    const T lambda = -vg[2] / Dg[2];
    const T dX = vg[0] + lambda * Dg[0] - m_X, dY = vg[1] + lambda * Dg[1] - m_Y;
    r[0] = m_W[0] * dX + m_W[1] * dY;
    r[1] = m_W[2] * dX + m_W[3] * dY;
    return true;
  }

  double m_S[9], m_t[3];
  double m_X, m_Y;
  double m_W[4];
};

// Pixels per metre of grid displacement at grid point (X, Y): diag(px, py) d(x, y)/d(X, Y), row-major.
void gridToPixelJacobian(const vpHomogeneousMatrix &cMg, const vpCameraParameters &cam, double X, double Y,
                         double W[4])
{
  double P[3];
  for (unsigned int i = 0; i < 3; ++i)
    P[i] = cMg[i][0] * X + cMg[i][1] * Y + cMg[i][3];
  const double iz2 = 1.0 / (P[2] * P[2]);
  for (unsigned int c = 0; c < 2; ++c) {
    W[c] = cam.get_px() * (cMg[0][c] * P[2] - P[0] * cMg[2][c]) * iz2;
    W[2 + c] = cam.get_py() * (cMg[1][c] * P[2] - P[1] * cMg[2][c]) * iz2;
  }
}
typedef ceres::AutoDiffCostFunction<GridPointResidual, 2, 2, 3, 1, 1> GridPointCost;

// Alpha, beta such that Rx(alpha) Ry(beta) (0, 0, 1) is the Z axis of cMl: (sin b, -sin a cos b, cos a cos b).
void axisAngles(const vpHomogeneousMatrix &cMl, double &alpha, double &beta)
{
  const double ax = cMl[0][2], ay = cMl[1][2], az = cMl[2][2];
  beta = std::asin(std::max(-1.0, std::min(1.0, ax)));
  alpha = std::atan2(-ay, az);
}

vpHomogeneousMatrix laserPose(double alpha, double beta, const double apex[3])
{
  const vpRotationMatrix R = vpRotationMatrix(alpha, 0, 0) * vpRotationMatrix(0, beta, 0);
  return vpHomogeneousMatrix(vpTranslationVector(apex[0], apex[1], apex[2]), R);
}

ceres::LossFunction *makeLoss(vpRobustLoss loss, double scale)
{
  switch (loss) {
  case vpRobustLoss::HUBER:
    return new ceres::HuberLoss(scale);
  case vpRobustLoss::CAUCHY:
    return new ceres::CauchyLoss(scale);
  default:
    return nullptr;
  }
}

} // namespace

vpLaserConicCalibration::vpLaserConicCalibration()
  : m_cam(), m_hasCam(false), m_hasGuess(false), m_estimateAngle(false), m_jackknife(false), m_openingAngle(0.0), m_guess(),
    m_loss(LOSS_CAUCHY), m_userLossScale(0.0), m_maxIterations(200), m_maxCondition(1e5), m_maxRmsPixels(3.0), m_views(),
    m_status(STATUS_NOT_COMPUTED), m_statusDetails(), m_rms(0.0), m_rmsPixels(0.0), m_initialRms(0.0), m_openingAngleEstimate(0.0),
    m_lossScale(0.0), m_condition(0.0), m_nbInliers(0), m_covariance(kNbConeParams, kNbConeParams, 0.0), m_hasJackknifeStd(false),
    m_jackknifeStd(kNbConeParams, 0.0),
    m_predicted(), m_initialPredicted(), m_measured(), m_inlier()
{
}

void vpLaserConicCalibration::setCameraParameters(const vpCameraParameters &cam)
{
  if (!(cam.get_px() > 0) || !(cam.get_py() > 0) || !std::isfinite(cam.get_px()) || !std::isfinite(cam.get_py()) ||
      !std::isfinite(cam.get_u0()) || !std::isfinite(cam.get_v0()))
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicCalibration: focal lengths must be positive and finite");
  m_cam = cam;
  m_hasCam = true;
}

void vpLaserConicCalibration::setOpeningAngle(double openingAngle)
{
  if (!std::isfinite(openingAngle) || openingAngle <= 0.0 || openingAngle >= M_PI)
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the opening angle must be in (0, pi) radians");
  m_openingAngle = openingAngle;
  m_openingAngleEstimate = openingAngle;
}

void vpLaserConicCalibration::setRobustLoss(vpLaserConicLoss loss, double scale)
{
  if (!std::isfinite(scale) || scale < 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the robust loss scale must be finite and >= 0 (0: automatic)");
  if (loss != LOSS_NONE && loss != LOSS_HUBER && loss != LOSS_CAUCHY)
    throw vpLaserConicException(vpLaserConicException::badValueError, "vpLaserConicCalibration: unknown robust loss");
  m_loss = loss;
  m_userLossScale = scale;
}

void vpLaserConicCalibration::setMaxIterations(int maxIterations)
{
  if (maxIterations <= 0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the iteration limit must be positive");
  m_maxIterations = maxIterations;
}

void vpLaserConicCalibration::setMaxRmsPixels(double maxRms)
{
  if (!std::isfinite(maxRms) || !(maxRms > 0.0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the largest RMS must be positive and finite");
  m_maxRmsPixels = maxRms;
}

void vpLaserConicCalibration::setMaxConditionNumber(double maxCondition)
{
  if (!(maxCondition > 1.0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the largest condition number must be greater than 1");
  m_maxCondition = maxCondition;
}

void vpLaserConicCalibration::setInitialGuess(const vpHomogeneousMatrix &cMl)
{
  if (!vsp::laser_pose_check::isFinitePose(cMl))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the initial guess is not a finite rigid transformation");
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
  vpColVector sigma(kNbConeParams, 0.0);
  for (unsigned int k = 0; k < kNbConeParams; ++k)
    sigma[k] = std::sqrt(std::max(0.0, m_covariance[k][k]));
  return sigma;
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

namespace
{
// Two grid planes closer than this (angle of the normals, relative difference of the distances to the camera
// centre) count as one: the cone cut by one plane is a conic that several cones fit exactly (views of one
// plane, measured: 11-12 degrees and 18 cm from the truth with a normal RMS, even for planes 1 degree or
// 1 % apart), while planes 3 degrees or 3 % apart gave 0.1 degree and 1.6 mm at 0.5 px of noise.
const double kSamePlaneAngleDeg = 2.0, kSamePlaneDistanceRatio = 0.02;

template <typename Views> bool hasTwoGridPlanes(const Views &views)
{
  const vpHomogeneousMatrix &M0 = views[0].cMg;
  const double d0 = std::fabs(M0[0][2] * M0[0][3] + M0[1][2] * M0[1][3] + M0[2][2] * M0[2][3]);
  for (size_t k = 1; k < views.size(); ++k) {
    const vpHomogeneousMatrix &M = views[k].cMg;
    const double dot = M0[0][2] * M[0][2] + M0[1][2] * M[1][2] + M0[2][2] * M[2][2];
    const double angle = vpMath::deg(std::acos(std::min(1.0, std::fabs(dot))));
    const double d = std::fabs(M[0][2] * M[0][3] + M[1][2] * M[1][3] + M[2][2] * M[2][3]);
    if (angle >= kSamePlaneAngleDeg || std::fabs(d - d0) >= kSamePlaneDistanceRatio * std::max(d, d0))
      return true;
  }
  return false;
}

//! The cone parameters Ceres works on, and one gamma per point.
struct ConeState
{
  double angles[2];
  double apex[3];
  double opening;
  std::vector<std::vector<double> > gammas;
};

//! One residual block of the problem.
struct PointBlock
{
  ceres::ResidualBlockId id;
  const ceres::CostFunction *cost;
  size_t view, index;
  bool inlier;
};

void residual(const PointBlock &b, ConeState &s, double r[2], double *jacobians[4] = nullptr)
{
  const double *params[4] = {s.angles, s.apex, &s.gammas[b.view][b.index], &s.opening};
  b.cost->Evaluate(params, r, jacobians);
}

// Residual of a block on its grid plane (metres): the pixel residual mapped back by W^-1.
void gridResidual(const PointBlock &b, ConeState &s, double d[2])
{
  double r[2];
  residual(b, s, r);
  const double *W = static_cast<const GridPointCost *>(b.cost)->functor().m_W;
  const double det = W[0] * W[3] - W[1] * W[2];
  d[0] = (W[3] * r[0] - W[1] * r[1]) / det;
  d[1] = (-W[2] * r[0] + W[0] * r[1]) / det;
}

// RMS distance (metres) on the grid planes over all the blocks, or over the inliers only.
double gridRms(const std::vector<PointBlock> &blocks, ConeState &s, bool inliersOnly)
{
  double sum2 = 0.0;
  size_t n = 0;
  for (const PointBlock &b : blocks) {
    if (inliersOnly && !b.inlier)
      continue;
    double d[2];
    gridResidual(b, s, d);
    sum2 += d[0] * d[0] + d[1] * d[1];
    ++n;
  }
  return n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
}

// Predicted grid XY of every point (blocks in view order), for figures.
std::vector<std::vector<std::pair<double, double> > >
predictedGridPoints(const std::vector<PointBlock> &blocks, ConeState &s,
                    const std::vector<std::vector<std::pair<double, double> > > &measured)
{
  std::vector<std::vector<std::pair<double, double> > > predicted(measured.size());
  for (const PointBlock &b : blocks) {
    double d[2];
    gridResidual(b, s, d);
    const std::pair<double, double> &XY = measured[b.view][b.index];
    predicted[b.view].push_back(std::make_pair(XY.first + d[0], XY.second + d[1]));
  }
  return predicted;
}

/*!
  Normal matrix of the 6 cone parameters with the gamma_i eliminated (Schur complement; each gamma_i
  touches only its own two residuals), summed over the inlier blocks, and the residual sum of squares.
*/
Eigen::Matrix<double, kNbConeParams, kNbConeParams> reducedNormalMatrix(const std::vector<PointBlock> &blocks,
                                                                        ConeState &s, double &rss)
{
  Eigen::Matrix<double, kNbConeParams, kNbConeParams> S = Eigen::Matrix<double, kNbConeParams, kNbConeParams>::Zero();
  rss = 0.0;
  for (const PointBlock &b : blocks) {
    if (!b.inlier)
      continue;
    double r[2], jA[4], jV[6], jG[2], jO[2];
    double *jac[4] = {jA, jV, jG, jO};
    residual(b, s, r, jac);
    rss += r[0] * r[0] + r[1] * r[1];
    Eigen::Matrix<double, 2, kNbConeParams> Jc;
    Jc << jA[0], jA[1], jV[0], jV[1], jV[2], jO[0], jA[2], jA[3], jV[3], jV[4], jV[5], jO[1];
    const Eigen::Vector2d jg(jG[0], jG[1]);
    const Eigen::Matrix<double, kNbConeParams, 1> cross = Jc.transpose() * jg;
    S += Jc.transpose() * Jc;
    const double gg = jg.squaredNorm();
    if (gg > 0.0)
      S -= cross * cross.transpose() / gg;
  }
  return S;
}

bool runSolver(const ceres::Solver::Options &options, ceres::Problem &problem, ceres::Solver::Summary &summary)
{
  ceres::Solve(options, &problem, &summary);
  return summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
}
} // namespace

bool vpLaserConicCalibration::compute(vpHomogeneousMatrix &cMl)
{
  const vpHomogeneousMatrix guess = m_hasGuess ? m_guess : cMl;
  checkReady(guess);
  m_status = STATUS_NOT_COMPUTED;
  m_statusDetails.clear();
  m_covariance = vpMatrix(kNbConeParams, kNbConeParams, 0.0);
  m_hasJackknifeStd = false;
  m_jackknifeStd = vpColVector(kNbConeParams, 0.0);
  m_condition = 0.0;
  m_nbInliers = 0;
  m_rms = m_rmsPixels = 0.0;
  m_lossScale = 0.0;
  m_predicted.clear();
  m_initialPredicted.clear();
  m_inlier.clear();
  m_openingAngleEstimate = m_openingAngle;
  backProject();
  if (m_views.size() < 2) {
    std::ostringstream os;
    os << m_views.size() << " view given";
    return fail(STATUS_NOT_ENOUGH_VIEWS, os.str());
  }
  if (!hasTwoGridPlanes(m_views)) {
    std::ostringstream os;
    os << "all the " << m_views.size() << " grids lie in one plane (normals within " << kSamePlaneAngleDeg
       << " deg, distances within " << 100.0 * kSamePlaneDistanceRatio << " %)";
    return fail(STATUS_DEGENERATE_VIEWS, os.str());
  }

  // Initial cone parameters and, for each point, the gamma of the cone ray closest to it as seen from the apex.
  ConeState s;
  axisAngles(guess, s.angles[0], s.angles[1]);
  for (unsigned int i = 0; i < 3; ++i)
    s.apex[i] = guess[i][3];
  s.opening = m_openingAngle;
  const vpRotationMatrix lRc = (vpRotationMatrix(s.angles[0], 0, 0) * vpRotationMatrix(0, s.angles[1], 0)).inverse();
  s.gammas.resize(m_views.size());
  double meanDistance = 0.0; // apex to grid points, the length that turns angles into metres
  for (size_t j = 0; j < m_views.size(); ++j) {
    const vpHomogeneousMatrix &cMg = m_views[j].cMg;
    for (const std::pair<double, double> &XY : m_measured[j]) {
      double d[3];
      for (unsigned int i = 0; i < 3; ++i)
        d[i] = cMg[i][0] * XY.first + cMg[i][1] * XY.second + cMg[i][3] - s.apex[i];
      const double dlx = lRc[0][0] * d[0] + lRc[0][1] * d[1] + lRc[0][2] * d[2];
      const double dly = lRc[1][0] * d[0] + lRc[1][1] * d[1] + lRc[1][2] * d[2];
      s.gammas[j].push_back(std::atan2(dly, dlx));
      meanDistance += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
  }
  const size_t nbPoints = getNbPoints();
  meanDistance /= static_cast<double>(nbPoints);

  // The blocks' cost functions outlive their removal from the problem (outliers are still evaluated for
  // the figures), and one loss is shared by all the blocks: both are owned here.
  ceres::Problem::Options problemOptions;
  problemOptions.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problemOptions.enable_fast_removal = true;
  ceres::Problem problem(problemOptions);
  ceres::LossFunctionWrapper loss(nullptr, ceres::TAKE_OWNERSHIP); // nullptr: plain least squares
  std::vector<PointBlock> blocks;
  std::vector<std::unique_ptr<GridPointCost> > costs;
  blocks.reserve(nbPoints);
  costs.reserve(nbPoints);
  for (size_t j = 0; j < m_views.size(); ++j) {
    const vpHomogeneousMatrix gMc = m_views[j].cMg.inverse();
    for (size_t i = 0; i < m_measured[j].size(); ++i) {
      PointBlock b;
      const double X = m_measured[j][i].first, Y = m_measured[j][i].second;
      double W[4];
      gridToPixelJacobian(m_views[j].cMg, m_cam, X, Y, W);
      costs.emplace_back(new GridPointCost(new GridPointResidual(gMc, X, Y, W)));
      b.cost = costs.back().get();
      b.id = problem.AddResidualBlock(costs.back().get(), &loss, s.angles, s.apex, &s.gammas[j][i], &s.opening);
      b.view = j;
      b.index = i;
      b.inlier = true;
      blocks.push_back(b);
    }
  }
  problem.SetParameterLowerBound(&s.opening, 0, 1e-3);
  problem.SetParameterUpperBound(&s.opening, 0, M_PI - 1e-3);

  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_SCHUR; // the gamma_i are eliminated: a 5x5 (6x6) reduced system
  options.max_num_iterations = m_maxIterations;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;

  // Stage 1: only the gamma_i, so that every point starts on its closest ray of the guessed cone.
  problem.SetParameterBlockConstant(s.angles);
  problem.SetParameterBlockConstant(s.apex);
  problem.SetParameterBlockConstant(&s.opening);
  if (!runSolver(options, problem, summary))
    return fail(STATUS_SOLVER_FAILURE, "first stage (gamma_i only): " + summary.message);

  // Residual norms (pixels) of all the points. Each gamma_i absorbs the residual along the trace, so a norm
  // is the distance across the trace: |N(0, sigma)|, of median 0.6745 sigma.
  std::vector<double> norms(blocks.size());
  auto evaluateResiduals = [&]() {
    for (size_t k = 0; k < blocks.size(); ++k) {
      double r[2];
      residual(blocks[k], s, r);
      norms[k] = std::sqrt(r[0] * r[0] + r[1] * r[1]);
    }
  };
  evaluateResiduals();
  m_initialRms = gridRms(blocks, s, false);
  m_initialPredicted = predictedGridPoints(blocks, s, m_measured);

  // Stage 2: everything under a robust loss whose scale shrinks from the initial residuals to the noise
  // level (1.5 sigma, sigma = vpRobustMadScale(): 1.4826 x the median residual norm), by at most a factor
  // of 4 per run.
  problem.SetParameterBlockVariable(s.angles);
  problem.SetParameterBlockVariable(s.apex);
  if (m_estimateAngle)
    problem.SetParameterBlockVariable(&s.opening);
  if (m_loss != LOSS_NONE) {
    const double minScale = 1e-6; // pixels: exact data
    double scale = std::max(std::max(m_userLossScale, minScale), vpRobustMadScale(norms) / 1.4826);
    for (int round = 0; round < 10; ++round) {
      loss.Reset(makeLoss(m_loss, scale), ceres::TAKE_OWNERSHIP);
      if (!runSolver(options, problem, summary))
        return fail(STATUS_SOLVER_FAILURE, "robust stage: " + summary.message);
      evaluateResiduals();
      const double target = m_userLossScale > 0.0 ? m_userLossScale
                                                  : std::max(minScale, 1.5 * vpRobustMadScale(norms));
      const double next = std::max(target, 0.25 * scale);
      if (next >= 0.8 * scale)
        break;
      scale = next;
    }
    m_lossScale = scale;
    // Stage 3 works on the points within 3 scales of the cone; the others keep their gamma, out of the problem.
    for (size_t k = 0; k < blocks.size(); ++k) {
      if (norms[k] > 3.0 * scale) {
        problem.RemoveResidualBlock(blocks[k].id);
        problem.SetParameterBlockConstant(&s.gammas[blocks[k].view][blocks[k].index]);
        blocks[k].inlier = false;
      }
    }
    loss.Reset(nullptr, ceres::TAKE_OWNERSHIP);
  }
  for (const PointBlock &b : blocks)
    m_nbInliers += b.inlier ? 1u : 0u;
  if (2 * m_nbInliers < nbPoints) {
    std::ostringstream os;
    os << m_nbInliers << " of " << nbPoints << " points within 3 x " << m_lossScale << " px of the cone";
    return fail(STATUS_TOO_MANY_OUTLIERS, os.str());
  }

  // Stage 3: plain least squares on the inliers; its convergence is the calibration's.
  if (!runSolver(options, problem, summary))
    return fail(STATUS_SOLVER_FAILURE, "final stage: " + summary.message);
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    std::ostringstream os;
    os << "final stage stopped after " << summary.iterations.size() - 1 << " iterations: " << summary.message;
    return fail(STATUS_NO_CONVERGENCE, os.str());
  }
  const bool finite = std::isfinite(s.angles[0]) && std::isfinite(s.angles[1]) && std::isfinite(s.apex[0]) &&
                      std::isfinite(s.apex[1]) && std::isfinite(s.apex[2]) && std::isfinite(s.opening);
  if (!finite)
    return fail(STATUS_SOLVER_FAILURE, "non-finite result");

  // Observability: conditioning of the reduced normal equations with the angles in metres at the grids.
  double rss = 0.0;
  Eigen::Matrix<double, kNbConeParams, kNbConeParams> S = reducedNormalMatrix(blocks, s, rss);
  m_rmsPixels = std::sqrt(rss / static_cast<double>(m_nbInliers));
  m_rms = gridRms(blocks, s, true);
  const int p = m_estimateAngle ? kNbConeParams : kNbConeParams - 1;
  Eigen::VectorXd scaling = Eigen::VectorXd::Ones(p);
  scaling[kAlpha] = scaling[kBeta] = 1.0 / meanDistance;
  if (m_estimateAngle)
    scaling[kOpening] = 1.0 / meanDistance;
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

  // The inliers' residuals must look like detection noise: a cone fitted to mostly outliers (whose
  // median then sets the loss scale), to a wrong camera model or to wrong grid poses does not.
  if (!(m_rmsPixels <= m_maxRmsPixels)) {
    std::ostringstream os;
    os << "RMS " << m_rmsPixels << " px > " << m_maxRmsPixels << " px over " << m_nbInliers << " points";
    return fail(STATUS_LARGE_RESIDUALS, os.str());
  }

  // Results, predicted points and inlier flags for figures.
  m_predicted = predictedGridPoints(blocks, s, m_measured);
  m_inlier.assign(m_views.size(), {});
  for (const PointBlock &b : blocks)
    m_inlier[b.view].push_back(b.inlier);
  m_openingAngleEstimate = s.opening;
  m_status = STATUS_OK;
  cMl = laserPose(s.angles[0], s.angles[1], s.apex);
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
