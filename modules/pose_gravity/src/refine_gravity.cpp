/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Maximum-likelihood refinement of a gravity-aided pose with Ceres.

  Image noise is taken Gaussian, isotropic, of standard deviation imageSigma in normalized
  coordinates, so the reprojection errors divided by imageSigma are whitened residuals.
  - Exact gravity (gravitySigma == 0): cRo = wRc^T Rz(alpha) wRo, 4 unknowns (alpha, t).
  - Noisy gravity (a gravity sigma > 0): 6 unknowns, cRo = exp([delta]x) cRo_0 with a 3-vector delta
    (a local chart around the initial rotation, no singularity) and t, plus the prior tying the two
    gravity measurements.
  An optional robust loss (Huber, Cauchy) acts on each point's whitened squared reprojection error.
  The covariance is the inverse of J^T J of the same whitened, robustified residuals, evaluated at
  the estimate in a chart centred on it (so that the rotation part is a left perturbation there).
*/
#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "gravity_geometry.h"

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

// Prior tying the two gravity measurements: r = (cRo g_obj - g_cam) / sqrt(sigma_c^2 + sigma_o^2).
// Each measured unit vector carries noise of standard deviation sigma_c (camera) or sigma_o (object)
// per component, so the difference of the two (one rotated, which does not change an isotropic
// covariance) has standard deviation sqrt(sigma_c^2 + sigma_o^2) per component; dividing by it
// whitens the residual. Only the two components orthogonal to gravity matter to first order: the
// third is second order in the noise.
struct GravityPrior
{
  GravityPrior(const Eigen::Vector3d &R0gObj, const Eigen::Vector3d &gCam, double sigma)
    : m_R0gObj(R0gObj), m_gCam(gCam), m_invSigma(1.0 / sigma)
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

// The robust loss of the options, on whitened residuals (null: squared error). Owned by the problem.
ceres::LossFunction *makeLoss(const RefineOptions &o)
{
  const double a = o.lossScale / o.imageSigma;
  switch (o.loss) {
  case vpRobustLoss::HUBER:
    return new ceres::HuberLoss(a);
  case vpRobustLoss::CAUCHY:
    return new ceres::CauchyLoss(a);
  case vpRobustLoss::NONE:
    break;
  }
  return nullptr;
}

double priorSigma(const RefineOptions &o)
{
  return std::sqrt(o.cameraGravitySigma * o.cameraGravitySigma + o.objectGravitySigma * o.objectGravitySigma);
}

// Yaw of the rotation about e_z closest to wRc cRo wRo^T (exact when cRo honours both gravities).
double yawOf(const Eigen::Matrix3d &wRc, const Eigen::Matrix3d &R, const Eigen::Matrix3d &wRo)
{
  const Eigen::Matrix3d W = wRc * R * wRo.transpose();
  return std::atan2(W(1, 0) - W(0, 1), W(0, 0) + W(1, 1));
}

// The 4-DOF problem on (alpha, t).
void buildYawProblem(const Eigen::Matrix3d &wRc, const Eigen::Matrix3d &wRo, const Eigen::Vector3d *x,
                     const Eigen::Vector3d *X, int n, const RefineOptions &o, double *alpha, double *t,
                     ceres::Problem &problem)
{
  const Eigen::Matrix3d A = wRc.transpose();
  for (int i = 0; i < n; ++i)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<YawReprojection, 2, 1, 3>(
                                 new YawReprojection(A, wRo * X[i], x[i], o.imageSigma)),
                             makeLoss(o), alpha, t);
}

// The 6-DOF problem on (delta, t) around the rotation R0.
void buildFullProblem(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                      const Eigen::Vector3d *X, int n, const RefineOptions &o, const Eigen::Matrix3d &R0, double *delta,
                      double *t, ceres::Problem &problem)
{
  for (int i = 0; i < n; ++i)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FullReprojection, 2, 3, 3>(
                                 new FullReprojection(R0 * X[i], x[i], o.imageSigma)),
                             makeLoss(o), delta, t);
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GravityPrior, 3, 3>(
                               new GravityPrior(R0 * gObj, gCam, priorSigma(o))),
                           nullptr, delta);
}

bool refineYaw(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
               const Eigen::Vector3d *X, int n, const RefineOptions &o, Pose &pose)
{
  const Eigen::Matrix3d wRc = uprightRotation(gCam);
  const Eigen::Matrix3d wRo = uprightRotation(gObj);
  double alpha = yawOf(wRc, pose.R, wRo);
  double t[3] = {pose.t.x(), pose.t.y(), pose.t.z()};
  ceres::Problem problem;
  buildYawProblem(wRc, wRo, x, X, n, o, &alpha, t, problem);
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
                const Eigen::Vector3d *X, int n, const RefineOptions &o, Pose &pose)
{
  double delta[3] = {0.0, 0.0, 0.0};
  double t[3] = {pose.t.x(), pose.t.y(), pose.t.z()};
  ceres::Problem problem;
  buildFullProblem(gCam, gObj, x, X, n, o, pose.R, delta, t, problem);
  ceres::Solver::Summary summary;
  ceres::Solve(solverOptions(), &problem, &summary);
  const Eigen::Vector3d d(delta[0], delta[1], delta[2]);
  const Eigen::Vector3d tNew(t[0], t[1], t[2]);
  if (!usable(summary) || !d.allFinite() || !tNew.allFinite())
    return false;
  const double angle = d.norm();
  const Eigen::Matrix3d dR = (angle > 0.0) ? Eigen::AngleAxisd(angle, d / angle).toRotationMatrix()
                                           : Eigen::Matrix3d::Identity();
  pose.R = dR * pose.R;
  pose.t = tNew;
  return true;
}

// Inverse of J^T J of a problem evaluated at its current parameters (k columns), false if singular.
template <int K> bool inverseNormalMatrix(ceres::Problem &problem, Eigen::Matrix<double, K, K> &inverse)
{
  ceres::CRSMatrix J;
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &J) || J.num_cols != K)
    return false;
  Eigen::Matrix<double, K, K> JtJ = Eigen::Matrix<double, K, K>::Zero();
  for (int r = 0; r < J.num_rows; ++r)
    for (int a = J.rows[r]; a < J.rows[r + 1]; ++a)
      for (int b = J.rows[r]; b < J.rows[r + 1]; ++b)
        JtJ(J.cols[a], J.cols[b]) += J.values[a] * J.values[b];
  const Eigen::FullPivLU<Eigen::Matrix<double, K, K> > lu(JtJ);
  if (!lu.isInvertible() || !JtJ.allFinite())
    return false;
  inverse = lu.inverse();
  return inverse.allFinite();
}
} // namespace

bool poseCovariance(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                    const Eigen::Vector3d *X, int n, const RefineOptions &options, const Pose &pose,
                    Eigen::Matrix<double, 6, 6> &covariance)
{
  if (n < 2 || !(options.imageSigma > 0.0) || !pose.R.allFinite() || !pose.t.allFinite())
    return false;
  double t[3] = {pose.t.x(), pose.t.y(), pose.t.z()};
  covariance.setZero();
  if (priorSigma(options) > 0.0) {
    // Parameters (delta, t); returned in the order (t, theta).
    double delta[3] = {0.0, 0.0, 0.0};
    ceres::Problem problem;
    buildFullProblem(gCam, gObj, x, X, n, options, pose.R, delta, t, problem);
    Eigen::Matrix<double, 6, 6> inv;
    if (!inverseNormalMatrix<6>(problem, inv))
      return false;
    covariance.topLeftCorner<3, 3>() = inv.bottomRightCorner<3, 3>();
    covariance.bottomRightCorner<3, 3>() = inv.topLeftCorner<3, 3>();
    covariance.topRightCorner<3, 3>() = inv.bottomLeftCorner<3, 3>();
    covariance.bottomLeftCorner<3, 3>() = inv.topRightCorner<3, 3>();
    return true;
  }
  // Parameters (alpha, t): cRo = wRc^T Rz(alpha) wRo, so d cRo = [gc]_x cRo d alpha, theta = gc alpha.
  const Eigen::Matrix3d wRc = uprightRotation(gCam);
  const Eigen::Matrix3d wRo = uprightRotation(gObj);
  double alpha = yawOf(wRc, pose.R, wRo);
  ceres::Problem problem;
  buildYawProblem(wRc, wRo, x, X, n, options, &alpha, t, problem);
  Eigen::Matrix<double, 4, 4> inv;
  if (!inverseNormalMatrix<4>(problem, inv))
    return false;
  Eigen::Matrix<double, 6, 4> J = Eigen::Matrix<double, 6, 4>::Zero();
  J.block<3, 3>(0, 1).setIdentity();
  J.block<3, 1>(3, 0) = gCam;
  covariance = J * inv * J.transpose();
  return true;
}

bool refinePose(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                const Eigen::Vector3d *X, int n, const RefineOptions &options, Pose &pose)
{
  if (n < 2 || !(options.imageSigma > 0.0) || !(options.cameraGravitySigma >= 0.0) ||
      !(options.objectGravitySigma >= 0.0) || !(options.lossScale > 0.0) || !pose.R.allFinite() || !pose.t.allFinite())
    return false;
  Pose refined = pose;
  const bool ok = (priorSigma(options) > 0.0) ? refineFull(gCam, gObj, x, X, n, options, refined)
                                              : refineYaw(gCam, gObj, x, X, n, options, refined);
  if (!ok)
    return false;
  // Cheirality: a refinement that moved a point behind the camera is no pose.
  for (int i = 0; i < n; ++i)
    if (!((refined.R * X[i] + refined.t).z() > 0.0))
      return false;
  pose = refined;
  return true;
}
} // namespace detail
} // namespace vpGravitySolvers
