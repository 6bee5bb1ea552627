/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicCalibration.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <ceres/ceres.h>

#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "laser_pose_check.h"

namespace
{
// Direction of the cone ray gamma in the camera frame, D' = Rx(alpha) Ry(beta) Rz(gamma) (sin h, 0, cos h)
// with h the half opening angle (paper eq. 58-59).
template <typename T>
void coneRay(const T &alpha, const T &beta, const T &gamma, double sinHalf, double cosHalf, T D[3])
{
  using std::cos;
  using std::sin;
  const T dx = sinHalf * cos(gamma), dy = sinHalf * sin(gamma), dz = T(cosHalf);
  const T cb = cos(beta), sb = sin(beta), ca = cos(alpha), sa = sin(alpha);
  const T x = cb * dx + sb * dz, z = -sb * dx + cb * dz; // Ry(beta) leaves y = dy
  D[0] = x;                                               // Rx(alpha)
  D[1] = ca * dy - sa * z;
  D[2] = sa * dy + ca * z;
}

// Residual of one laser point: predicted minus measured XY on its grid plane (paper eq. 60-65).
struct GridPointResidual
{
  GridPointResidual(const vpHomogeneousMatrix &gMc, double X, double Y, double sinHalf, double cosHalf)
    : m_X(X), m_Y(Y), m_sinHalf(sinHalf), m_cosHalf(cosHalf)
  {
    for (unsigned int i = 0; i < 3; ++i) {
      for (unsigned int j = 0; j < 3; ++j)
        m_S[3 * i + j] = gMc[i][j];
      m_t[i] = gMc[i][3];
    }
  }

  template <typename T> bool operator()(const T *const angles, const T *const apex, const T *const gamma, T *r) const
  {
    T D[3];
    coneRay(angles[0], angles[1], gamma[0], m_sinHalf, m_cosHalf, D);
    T Dg[3], vg[3];
    for (int i = 0; i < 3; ++i) {
      Dg[i] = m_S[3 * i] * D[0] + m_S[3 * i + 1] * D[1] + m_S[3 * i + 2] * D[2];
      vg[i] = m_S[3 * i] * apex[0] + m_S[3 * i + 1] * apex[1] + m_S[3 * i + 2] * apex[2] + m_t[i];
    }
    const T lambda = -vg[2] / Dg[2];
    r[0] = vg[0] + lambda * Dg[0] - m_X;
    r[1] = vg[1] + lambda * Dg[1] - m_Y;
    return true;
  }

  double m_S[9], m_t[3];
  double m_X, m_Y, m_sinHalf, m_cosHalf;
};

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

void solveOrThrow(const ceres::Solver::Options &options, ceres::Problem &problem, const char *stage)
{
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (!summary.IsSolutionUsable() || !std::isfinite(summary.final_cost)) {
    std::ostringstream os;
    os << "vpLaserConicCalibration: the " << stage << " stage failed: " << summary.message;
    throw vpLaserConicException(vpLaserConicException::badValueError, os.str());
  }
}
} // namespace

vpLaserConicCalibration::vpLaserConicCalibration()
  : m_cam(), m_hasCam(false), m_hasGuess(false), m_openingAngle(0.0), m_guess(), m_views(), m_initialRms(0.0),
    m_predicted(), m_measured()
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
}

void vpLaserConicCalibration::setInitialGuess(const vpHomogeneousMatrix &cMl)
{
  if (!vpLaserPoseCheck::isFinitePose(cMl))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the initial guess is not a finite rigid transformation");
  m_guess = cMl;
  m_hasGuess = true;
}

void vpLaserConicCalibration::addView(const vpHomogeneousMatrix &cMg, const std::vector<vpImagePoint> &laserPoints)
{
  if (!vpLaserPoseCheck::isFinitePose(cMg))
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
}

void vpLaserConicCalibration::clearViews()
{
  m_views.clear();
  m_predicted.clear();
  m_measured.clear();
}

double vpLaserConicCalibration::calibrate(vpHomogeneousMatrix &cMl)
{
  if (!m_hasCam)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicCalibration: call setCameraParameters() before calibrate()");
  if (!(m_openingAngle > 0.0))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: call setOpeningAngle() before calibrate()");
  if (m_views.empty())
    throw vpLaserConicException(vpLaserConicException::notEnoughPointError,
                                "vpLaserConicCalibration: no view added, call addView() before calibrate()");
  const vpHomogeneousMatrix guess = m_hasGuess ? m_guess : cMl;
  if (!vpLaserPoseCheck::isFinitePose(guess))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicCalibration: the initial guess is not a finite rigid transformation");

  // Measured points: back-projection of each laser pixel on its grid plane, in grid coordinates.
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

  // Initial cone parameters and, for each point, the gamma of the cone ray closest to it as seen from the apex.
  double angles[2];
  axisAngles(guess, angles[0], angles[1]);
  double apex[3] = {guess[0][3], guess[1][3], guess[2][3]};
  const vpRotationMatrix lRc = (vpRotationMatrix(angles[0], 0, 0) * vpRotationMatrix(0, angles[1], 0)).inverse();
  std::vector<std::vector<double> > gammas(m_views.size());
  for (size_t j = 0; j < m_views.size(); ++j) {
    const vpHomogeneousMatrix &cMg = m_views[j].cMg;
    for (const std::pair<double, double> &XY : m_measured[j]) {
      double d[3];
      for (unsigned int i = 0; i < 3; ++i)
        d[i] = cMg[i][0] * XY.first + cMg[i][1] * XY.second + cMg[i][3] - apex[i];
      const double dlx = lRc[0][0] * d[0] + lRc[0][1] * d[1] + lRc[0][2] * d[2];
      const double dly = lRc[1][0] * d[0] + lRc[1][1] * d[1] + lRc[1][2] * d[2];
      gammas[j].push_back(std::atan2(dly, dlx));
    }
  }

  const double sinHalf = std::sin(0.5 * m_openingAngle), cosHalf = std::cos(0.5 * m_openingAngle);
  ceres::Problem problem;
  size_t nbPoints = 0;
  for (size_t j = 0; j < m_views.size(); ++j) {
    const vpHomogeneousMatrix gMc = m_views[j].cMg.inverse();
    for (size_t i = 0; i < m_measured[j].size(); ++i) {
      ceres::CostFunction *cost = new ceres::AutoDiffCostFunction<GridPointResidual, 2, 2, 3, 1>(
          new GridPointResidual(gMc, m_measured[j][i].first, m_measured[j][i].second, sinHalf, cosHalf));
      problem.AddResidualBlock(cost, nullptr, angles, apex, &gammas[j][i]);
      ++nbPoints;
    }
  }

  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_SCHUR; // the gamma_i are eliminated: a 5x5 reduced system
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;

  // Stage 1: only the gamma_i, so that every point starts on its closest ray of the guessed cone.
  problem.SetParameterBlockConstant(angles);
  problem.SetParameterBlockConstant(apex);
  solveOrThrow(options, problem, "first (gamma_i only)");

  auto rmsAndPredictions = [&](bool keepPredictions) {
    double sum2 = 0.0;
    if (keepPredictions)
      m_predicted.assign(m_views.size(), {});
    for (size_t j = 0; j < m_views.size(); ++j) {
      const vpHomogeneousMatrix gMc = m_views[j].cMg.inverse();
      for (size_t i = 0; i < m_measured[j].size(); ++i) {
        const GridPointResidual residual(gMc, m_measured[j][i].first, m_measured[j][i].second, sinHalf, cosHalf);
        double r[2];
        residual(angles, apex, &gammas[j][i], r);
        sum2 += r[0] * r[0] + r[1] * r[1];
        if (keepPredictions)
          m_predicted[j].push_back(std::make_pair(m_measured[j][i].first + r[0], m_measured[j][i].second + r[1]));
      }
    }
    return std::sqrt(sum2 / static_cast<double>(nbPoints));
  };
  m_initialRms = rmsAndPredictions(false);

  // Stage 2: everything.
  problem.SetParameterBlockVariable(angles);
  problem.SetParameterBlockVariable(apex);
  solveOrThrow(options, problem, "second (all parameters)");

  const double rms = rmsAndPredictions(true);
  if (!std::isfinite(rms) || !std::isfinite(angles[0]) || !std::isfinite(angles[1]) || !std::isfinite(apex[0]) ||
      !std::isfinite(apex[1]) || !std::isfinite(apex[2]))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicCalibration: the optimisation diverged (non-finite result)");
  cMl = laserPose(angles[0], angles[1], apex);
  return rms;
}
