/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_calibration_problem.h"

#include <algorithm>
#include <cmath>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpTranslationVector.h>

namespace vsp::laser_calibration
{
namespace
{
// Direction of the cone ray gamma in the camera frame, D' = Rx(alpha) Ry(beta) Rz(gamma) (sin h, 0, cos h)
// with h the half opening angle (paper eq. 58-59).
template <typename T> void coneRay(const T &alpha, const T &beta, const T &gamma, const T &halfAngle, T D[3])
{
  using std::cos;
  using std::sin;
  const T sinHalf = sin(halfAngle);
  const T dx = sinHalf * cos(gamma), dy = sinHalf * sin(gamma), dz = cos(halfAngle);
  const T cb = cos(beta), sb = sin(beta), ca = cos(alpha), sa = sin(alpha);
  const T x = cb * dx + sb * dz, z = -sb * dx + cb * dz; // Ry(beta) leaves y = dy
  D[0] = x;                                              // Rx(alpha)
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
  bool operator()(const T *const angles, const T *const apex, const T *const gamma, const T *const opening, T *r) const
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
typedef ceres::AutoDiffCostFunction<GridPointResidual, 2, 2, 3, 1, 1> GridPointCost;

// Pixels per metre of grid displacement at grid point (X, Y): diag(px, py) d(x, y)/d(X, Y), row-major.
void gridToPixelJacobian(const vpHomogeneousMatrix &cMg, const vpCameraParameters &cam, double X, double Y, double W[4])
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

ceres::Problem::Options problemOptions()
{
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.enable_fast_removal = true;
  return options;
}

ceres::Solver::Options solverOptions(int maxIterations)
{
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_SCHUR; // the gamma_i are eliminated: a 5x5 (6x6) reduced system
  options.max_num_iterations = maxIterations;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  return options;
}
} // namespace

bool hasTwoGridPlanes(const std::vector<vpHomogeneousMatrix> &cMg)
{
  const vpHomogeneousMatrix &M0 = cMg[0];
  const double d0 = std::fabs(M0[0][2] * M0[0][3] + M0[1][2] * M0[1][3] + M0[2][2] * M0[2][3]);
  for (size_t k = 1; k < cMg.size(); ++k) {
    const vpHomogeneousMatrix &M = cMg[k];
    const double dot = M0[0][2] * M[0][2] + M0[1][2] * M[1][2] + M0[2][2] * M[2][2];
    const double angle = vpMath::deg(std::acos(std::min(1.0, std::fabs(dot))));
    const double d = std::fabs(M[0][2] * M[0][3] + M[1][2] * M[1][3] + M[2][2] * M[2][3]);
    if (angle >= kSamePlaneAngleDeg || std::fabs(d - d0) >= kSamePlaneDistanceRatio * std::max(d, d0))
      return true;
  }
  return false;
}

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

ConeProblem::ConeProblem(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured,
                         const vpCameraParameters &cam, const vpHomogeneousMatrix &guess, double openingAngle,
                         int maxIterations)
  : m_s(), m_meanDistance(0.0), m_problem(problemOptions()),
    m_loss(nullptr, ceres::TAKE_OWNERSHIP), // nullptr: plain least squares
    m_costs(), m_blocks(), m_norms(), m_options(solverOptions(maxIterations)), m_summary()
{
  initialState(cMg, measured, guess, openingAngle);
  addBlocks(cMg, measured, cam);
  m_problem.SetParameterLowerBound(&m_s.opening, 0, kMinOpening);
  m_problem.SetParameterUpperBound(&m_s.opening, 0, M_PI - kMinOpening);
}

void ConeProblem::initialState(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured,
                               const vpHomogeneousMatrix &guess, double openingAngle)
{
  axisAngles(guess, m_s.angles[0], m_s.angles[1]);
  for (unsigned int i = 0; i < 3; ++i)
    m_s.apex[i] = guess[i][3];
  m_s.opening = openingAngle;
  const vpRotationMatrix lRc =
      (vpRotationMatrix(m_s.angles[0], 0, 0) * vpRotationMatrix(0, m_s.angles[1], 0)).inverse();
  m_s.gammas.resize(cMg.size());
  size_t nbPoints = 0;
  for (size_t j = 0; j < cMg.size(); ++j) {
    for (const std::pair<double, double> &XY : measured[j]) {
      double d[3];
      for (unsigned int i = 0; i < 3; ++i)
        d[i] = cMg[j][i][0] * XY.first + cMg[j][i][1] * XY.second + cMg[j][i][3] - m_s.apex[i];
      const double dlx = lRc[0][0] * d[0] + lRc[0][1] * d[1] + lRc[0][2] * d[2];
      const double dly = lRc[1][0] * d[0] + lRc[1][1] * d[1] + lRc[1][2] * d[2];
      m_s.gammas[j].push_back(std::atan2(dly, dlx));
      m_meanDistance += std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      ++nbPoints;
    }
  }
  m_meanDistance /= static_cast<double>(nbPoints);
}

void ConeProblem::addBlocks(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured,
                            const vpCameraParameters &cam)
{
  size_t count = 0;
  for (const std::vector<std::pair<double, double> > &view : measured)
    count += view.size();
  m_blocks.reserve(count);
  m_costs.reserve(count);
  for (size_t j = 0; j < cMg.size(); ++j) {
    const vpHomogeneousMatrix gMc = cMg[j].inverse();
    for (size_t i = 0; i < measured[j].size(); ++i) {
      PointBlock b;
      const double X = measured[j][i].first, Y = measured[j][i].second;
      gridToPixelJacobian(cMg[j], cam, X, Y, b.W);
      m_costs.emplace_back(new GridPointCost(new GridPointResidual(gMc, X, Y, b.W)));
      b.cost = m_costs.back().get();
      b.id = m_problem.AddResidualBlock(m_costs.back().get(), &m_loss, m_s.angles, m_s.apex, &m_s.gammas[j][i],
                                        &m_s.opening);
      b.view = j;
      b.index = i;
      b.inlier = true;
      m_blocks.push_back(b);
    }
  }
}

bool ConeProblem::solve()
{
  ceres::Solve(m_options, &m_problem, &m_summary);
  return m_summary.IsSolutionUsable() && std::isfinite(m_summary.final_cost);
}

bool ConeProblem::fitGammas(std::string &error)
{
  m_problem.SetParameterBlockConstant(m_s.angles);
  m_problem.SetParameterBlockConstant(m_s.apex);
  m_problem.SetParameterBlockConstant(&m_s.opening);
  if (!solve()) {
    error = "first stage (gamma_i only): " + m_summary.message;
    return false;
  }
  evaluateNorms();
  return true;
}

void ConeProblem::releaseCone(bool estimateAngle)
{
  m_problem.SetParameterBlockVariable(m_s.angles);
  m_problem.SetParameterBlockVariable(m_s.apex);
  if (estimateAngle)
    m_problem.SetParameterBlockVariable(&m_s.opening);
  m_freeConeParameters = estimateAngle ? 6 : 5;
}

bool ConeProblem::fitRobust(vpRobustLoss loss, double userScale, double &scale, std::string &error)
{
  // Each gamma_i absorbs the residual along the trace, so a residual norm is the distance across the
  // trace: |N(0, sigma)|, of median 0.6745 sigma, and sigma = vpRobustMadScale() of the norms.
  const double minScale = 1e-6; // pixels: exact data
  // The fitted cone takes p degrees of freedom from the N distances across the trace: they spread by
  // sqrt((N - p) / N) of the noise. Without this, 5 points on each of 3 views (N = 15, p = 6) gave a scale of
  // 0.77 of the noise, genuine points fell beyond 3 scales (0.64 of 15 per run), and the standard deviations of
  // the fit on the rest came out 1.3 times too small.
  const double N = static_cast<double>(m_norms.size()), p = static_cast<double>(m_freeConeParameters);
  const double dofCorrection = N > p ? std::sqrt(N / (N - p)) : 1.0;
  scale = std::max(std::max(userScale, minScale), vpRobustMadScale(m_norms) / 1.4826);
  for (int round = 0; round < 10; ++round) {
    m_loss.Reset(makeLoss(loss, scale), ceres::TAKE_OWNERSHIP);
    if (!solve()) {
      error = "robust stage: " + m_summary.message;
      return false;
    }
    evaluateNorms();
    const double target = userScale > 0.0 ? userScale
                                          : std::max(minScale, 1.5 * vpRobustMadScale(m_norms) * dofCorrection);
    const double next = std::max(target, 0.25 * scale);
    if (next >= 0.8 * scale)
      break;
    scale = next;
  }
  // Stage 3 works on the points within 3 scales of the cone; the others keep their gamma, out of the problem.
  for (size_t k = 0; k < m_blocks.size(); ++k) {
    if (m_norms[k] > 3.0 * scale) {
      m_problem.RemoveResidualBlock(m_blocks[k].id);
      m_problem.SetParameterBlockConstant(&m_s.gammas[m_blocks[k].view][m_blocks[k].index]);
      m_blocks[k].inlier = false;
    }
  }
  m_loss.Reset(nullptr, ceres::TAKE_OWNERSHIP);
  return true;
}

bool ConeProblem::fitInliers(ceres::Solver::Summary &summary)
{
  const bool usable = solve();
  summary = m_summary;
  return usable;
}

unsigned int ConeProblem::nbInliers() const
{
  unsigned int n = 0;
  for (const PointBlock &b : m_blocks)
    n += b.inlier ? 1u : 0u;
  return n;
}

bool ConeProblem::isFinite() const
{
  return std::isfinite(m_s.angles[0]) && std::isfinite(m_s.angles[1]) && std::isfinite(m_s.apex[0]) &&
         std::isfinite(m_s.apex[1]) && std::isfinite(m_s.apex[2]) && std::isfinite(m_s.opening);
}

void ConeProblem::residual(const PointBlock &b, double r[2], double *jacobians[4])
{
  const double *params[4] = {m_s.angles, m_s.apex, &m_s.gammas[b.view][b.index], &m_s.opening};
  b.cost->Evaluate(params, r, jacobians);
}

void ConeProblem::evaluateNorms()
{
  m_norms.resize(m_blocks.size());
  for (size_t k = 0; k < m_blocks.size(); ++k) {
    double r[2];
    residual(m_blocks[k], r);
    m_norms[k] = std::sqrt(r[0] * r[0] + r[1] * r[1]);
  }
}

// Residual of a block on its grid plane (metres): the pixel residual mapped back by W^-1.
void ConeProblem::gridResidual(const PointBlock &b, double d[2])
{
  double r[2];
  residual(b, r);
  const double *W = b.W;
  const double det = W[0] * W[3] - W[1] * W[2];
  d[0] = (W[3] * r[0] - W[1] * r[1]) / det;
  d[1] = (-W[2] * r[0] + W[0] * r[1]) / det;
}

double ConeProblem::gridRms(bool inliersOnly)
{
  double sum2 = 0.0;
  size_t n = 0;
  for (const PointBlock &b : m_blocks) {
    if (inliersOnly && !b.inlier)
      continue;
    double d[2];
    gridResidual(b, d);
    sum2 += d[0] * d[0] + d[1] * d[1];
    ++n;
  }
  return n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
}

GridPoints ConeProblem::predictedGridPoints(const GridPoints &measured)
{
  GridPoints predicted(measured.size());
  for (const PointBlock &b : m_blocks) {
    double d[2];
    gridResidual(b, d);
    const std::pair<double, double> &XY = measured[b.view][b.index];
    predicted[b.view].push_back(std::make_pair(XY.first + d[0], XY.second + d[1]));
  }
  return predicted;
}

ConeMatrix ConeProblem::reducedNormalMatrix(double &rss)
{
  ConeMatrix S = ConeMatrix::Zero();
  rss = 0.0;
  for (const PointBlock &b : m_blocks) {
    if (!b.inlier)
      continue;
    double r[2], jA[4], jV[6], jG[2], jO[2];
    double *jac[4] = {jA, jV, jG, jO};
    residual(b, r, jac);
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

std::vector<std::vector<bool> > ConeProblem::inlierFlags(size_t nbViews) const
{
  std::vector<std::vector<bool> > flags(nbViews);
  for (const PointBlock &b : m_blocks)
    flags[b.view].push_back(b.inlier);
  return flags;
}
} // namespace vsp::laser_calibration
