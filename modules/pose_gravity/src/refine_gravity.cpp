/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Maximum-likelihood refinement of a gravity-aided pose with Ceres.

  Image noise is taken Gaussian, isotropic, of standard deviation imageSigma in normalized
  coordinates, so the reprojection errors divided by imageSigma are whitened residuals.
  - Exact gravity (gravitySigma == 0): cRo = wRc^T Rz(alpha) wRo, 4 unknowns (alpha, t).
  - Noisy gravity (gravitySigma > 0): 6 unknowns, cRo = exp([delta]x) cRo_0 with a 3-vector delta
    (a local chart around the initial rotation, no singularity) and t, plus a prior per gravity pair.
*/
#include <cmath>

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <Eigen/Geometry>

#include "gravityGeometry.h"

namespace vpGravitySolvers
{
namespace detail
{
namespace
{
// Reprojection of one point for the 4-DOF model: P = A Rz(alpha) Y + t with A = wRc^T, Y = wRo X.
struct YawReprojection
{
  YawReprojection(const Eigen::Matrix3d &A, const Eigen::Vector3d &Y, const Eigen::Vector3d &x, double sigma)
    : m_A(A), m_Y(Y), m_x(x.x() / x.z()), m_y(x.y() / x.z()), m_invSigma(1.0 / sigma)
  {
  }
  template <typename T> bool operator()(const T *alpha, const T *t, T *residual) const
  {
    const T c = ceres::cos(alpha[0]), s = ceres::sin(alpha[0]);
    const T RzY[3] = {c * m_Y.x() - s * m_Y.y(), s * m_Y.x() + c * m_Y.y(), T(m_Y.z())};
    T P[3];
    for (int r = 0; r < 3; ++r)
      P[r] = m_A(r, 0) * RzY[0] + m_A(r, 1) * RzY[1] + m_A(r, 2) * RzY[2] + t[r];
    residual[0] = (P[0] / P[2] - m_x) * m_invSigma;
    residual[1] = (P[1] / P[2] - m_y) * m_invSigma;
    return true;
  }
  Eigen::Matrix3d m_A;
  Eigen::Vector3d m_Y;
  double m_x, m_y, m_invSigma;
};

// Reprojection of one point for the 6-DOF model: P = exp([delta]x) (R0 X) + t.
struct FullReprojection
{
  FullReprojection(const Eigen::Vector3d &R0X, const Eigen::Vector3d &x, double sigma)
    : m_R0X(R0X), m_x(x.x() / x.z()), m_y(x.y() / x.z()), m_invSigma(1.0 / sigma)
  {
  }
  template <typename T> bool operator()(const T *delta, const T *t, T *residual) const
  {
    const T R0X[3] = {T(m_R0X.x()), T(m_R0X.y()), T(m_R0X.z())};
    T P[3];
    ceres::AngleAxisRotatePoint(delta, R0X, P);
    for (int r = 0; r < 3; ++r)
      P[r] += t[r];
    residual[0] = (P[0] / P[2] - m_x) * m_invSigma;
    residual[1] = (P[1] / P[2] - m_y) * m_invSigma;
    return true;
  }
  Eigen::Vector3d m_R0X;
  double m_x, m_y, m_invSigma;
};

// Prior tying the two gravity measurements: r = (cRo g_obj - g_cam) / (sqrt(2) sigma).
// Each measured unit vector carries noise of standard deviation sigma per component, so the
// difference of the two (one rotated, which does not change an isotropic covariance) has standard
// deviation sqrt(2) sigma per component; dividing by it whitens the residual. Only the two
// components orthogonal to gravity matter to first order: the third is second order in the noise.
struct GravityPrior
{
  GravityPrior(const Eigen::Vector3d &R0gObj, const Eigen::Vector3d &gCam, double sigma)
    : m_R0gObj(R0gObj), m_gCam(gCam), m_invSigma(1.0 / (std::sqrt(2.0) * sigma))
  {
  }
  template <typename T> bool operator()(const T *delta, T *residual) const
  {
    const T g[3] = {T(m_R0gObj.x()), T(m_R0gObj.y()), T(m_R0gObj.z())};
    T Rg[3];
    ceres::AngleAxisRotatePoint(delta, g, Rg);
    for (int r = 0; r < 3; ++r)
      residual[r] = (Rg[r] - m_gCam[r]) * m_invSigma;
    return true;
  }
  Eigen::Vector3d m_R0gObj, m_gCam;
  double m_invSigma;
};

ceres::Solver::Options solverOptions()
{
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.minimizer_progress_to_stdout = false;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  return options;
}

bool usable(const ceres::Solver::Summary &summary)
{
  return summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
}

bool refineYaw(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
               const Eigen::Vector3d *X, int n, double imageSigma, Pose &pose)
{
  const Eigen::Matrix3d wRc = uprightRotation(gCam);
  const Eigen::Matrix3d wRo = uprightRotation(gObj);
  // Yaw of the rotation about e_z closest to wRc cRo wRo^T (exact when cRo honours both gravities).
  const Eigen::Matrix3d W = wRc * pose.R * wRo.transpose();
  double alpha = std::atan2(W(1, 0) - W(0, 1), W(0, 0) + W(1, 1));
  double t[3] = {pose.t.x(), pose.t.y(), pose.t.z()};

  ceres::Problem problem;
  const Eigen::Matrix3d A = wRc.transpose();
  for (int i = 0; i < n; ++i)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<YawReprojection, 2, 1, 3>(
                               new YawReprojection(A, wRo * X[i], x[i], imageSigma)),
                             nullptr, &alpha, t);
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(), &problem, &summary);
  const Eigen::Vector3d tNew(t[0], t[1], t[2]);
  if (!usable(summary) || !std::isfinite(alpha) || !tNew.allFinite())
    return false;
  pose.R = composeRotation(wRc, alpha, wRo);
  pose.t = tNew;
  return true;
}

bool refineFull(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                const Eigen::Vector3d *X, int n, double imageSigma, double gravitySigma, Pose &pose)
{
  double delta[3] = {0.0, 0.0, 0.0};
  double t[3] = {pose.t.x(), pose.t.y(), pose.t.z()};
  ceres::Problem problem;
  for (int i = 0; i < n; ++i)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FullReprojection, 2, 3, 3>(
                               new FullReprojection(pose.R * X[i], x[i], imageSigma)),
                             nullptr, delta, t);
  problem.AddResidualBlock(
    new ceres::AutoDiffCostFunction<GravityPrior, 3, 3>(new GravityPrior(pose.R * gObj, gCam, gravitySigma)), nullptr,
    delta);
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(), &problem, &summary);
  const Eigen::Vector3d d(delta[0], delta[1], delta[2]);
  const Eigen::Vector3d tNew(t[0], t[1], t[2]);
  if (!usable(summary) || !d.allFinite() || !tNew.allFinite())
    return false;
  const double angle = d.norm();
  const Eigen::Matrix3d dR =
    (angle > 0.0) ? Eigen::AngleAxisd(angle, d / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
  pose.R = dR * pose.R;
  pose.t = tNew;
  return true;
}
} // namespace

bool refinePose(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                const Eigen::Vector3d *X, int n, double imageSigma, double gravitySigma, Pose &pose)
{
  if (n < 2 || !(imageSigma > 0.0) || !(gravitySigma >= 0.0) || !pose.R.allFinite() || !pose.t.allFinite())
    return false;
  Pose refined = pose;
  const bool ok = (gravitySigma > 0.0) ? refineFull(gCam, gObj, x, X, n, imageSigma, gravitySigma, refined)
                                       : refineYaw(gCam, gObj, x, X, n, imageSigma, refined);
  if (ok)
    pose = refined;
  return ok;
}
} // namespace detail
} // namespace vpGravitySolvers
