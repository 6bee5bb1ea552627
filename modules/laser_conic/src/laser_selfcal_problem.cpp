/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_selfcal_problem.cpp
  \brief The joint problem of the self-calibration from ground frames: conic of a (plane, laser) pair
  with its derivatives, per-frame residuals, the laser information of a frame, the Ceres solve.
*/
#include "laser_selfcal_problem.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <ceres/ceres.h>
#include <ceres/jet.h>
#include <ceres/manifold.h>

namespace vpLaserSelfCal
{
namespace
{
constexpr int kAll = kPlaneSize + kLaserSize;
typedef ceres::Jet<double, kAll> Jet;

/*!
  The six coefficients (a, b, d, e, f, g) of the image conic of the trace, C = [a b d; b e f; d f g].
  With the plane (n, h), the apex p, the unit axis a and c2 = cos^2(A/2), the trace seen through a ray r
  satisfies r^T G^T M G r = 0 with G = h I + p n^T and M = c2 I - a a^T (the cone (X-p)^T M (X-p) = 0),
  i.e. C = c2 G^T G - q q^T with G^T G = h^2 I + h (n p^T + p n^T) + |p|^2 n n^T and q = G^T a = h a + (p.a) n.
*/
template <typename T> void conicCoefficients(const T *P, const T *L, const ApexChart &chart, T c[6])
{
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T sr = sin(P[0]), cr = cos(P[0]), sp = sin(P[1]), cp = cos(P[1]), h = P[2];
  const T n[3] = {-sp, sr * cp, -cr * cp};
  const T sa = sin(L[0]), ca = cos(L[0]), sb = sin(L[1]), cb = cos(L[1]);
  const T a[3] = {sb, -sa * cb, ca * cb};
  T w[3];
  for (int i = 0; i < 3; ++i)
    w[i] = chart.a0(i) + L[2] * chart.e1(i) + L[3] * chart.e2(i);
  const T scale = L[4] / sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const T p[3] = {scale * w[0], scale * w[1], scale * w[2]};
  const T half = T(0.5) * L[5];
  const T c2 = cos(half) * cos(half);
  const T pa = p[0] * a[0] + p[1] * a[1] + p[2] * a[2];
  const T pp = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  T q[3];
  for (int i = 0; i < 3; ++i)
    q[i] = h * a[i] + pa * n[i];
  const int rows[6] = {0, 0, 0, 1, 1, 2}, cols[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 6; ++k) {
    const int i = rows[k], j = cols[k];
    const T gtg = (i == j ? h * h : T(0.0)) + h * (n[i] * p[j] + p[i] * n[j]) + pp * n[i] * n[j];
    c[k] = c2 * gtg - q[i] * q[j];
  }
}

//! Signed Sampson distance of (x, y) to the conic c and its gradient with respect to the six coefficients.
inline bool sampson(const double c[6], double x, double y, double &s, double ds[6])
{
  const double v0 = c[0] * x + c[1] * y + c[2], v1 = c[1] * x + c[3] * y + c[4];
  const double A = x * v0 + y * v1 + c[2] * x + c[4] * y + c[5];
  const double L2 = v0 * v0 + v1 * v1;
  if (!(L2 > 0.0) || !std::isfinite(L2)) {
    s = 0.0;
    std::fill(ds, ds + 6, 0.0);
    return false;
  }
  const double L = std::sqrt(L2), inv = 0.5 / L;
  s = A * inv;
  const double dA[6] = {x * x, 2.0 * x * y, 2.0 * x, y * y, 2.0 * y, 1.0};
  const double dv0[6] = {x, y, 1.0, 0.0, 0.0, 0.0}, dv1[6] = {0.0, x, 0.0, y, 1.0, 0.0};
  // s = A / (2 L): ds = dA / (2 L) - s dL / L with dL = (v0 dv0 + v1 dv1) / L.
  const double k = s / L2;
  for (int i = 0; i < 6; ++i)
    ds[i] = dA[i] * inv - k * (v0 * dv0[i] + v1 * dv1[i]);
  return true;
}

//! Ceres view of one frame: residuals of its points, blocks (plane, laser).
class FrameCost : public ceres::CostFunction
{
public:
  FrameCost(const Frame &frame, const ApexChart &chart, double focal) : m_frame(frame), m_chart(chart), m_focal(focal)
  {
    set_num_residuals(static_cast<int>(frame.points.size()));
    mutable_parameter_block_sizes()->push_back(kPlaneSize);
    mutable_parameter_block_sizes()->push_back(kLaserSize);
  }
  bool Evaluate(double const *const *parameters, double *residuals, double **jacobians) const override
  {
    const Frame &frame = m_frame;
    const Eigen::Vector3d plane = Eigen::Map<const Eigen::Vector3d>(parameters[0]); // Ceres may probe other planes
    const LaserVector L = Eigen::Map<const LaserVector>(parameters[1]);
    double *jp = jacobians ? jacobians[0] : nullptr, *jl = jacobians ? jacobians[1] : nullptr;
    m_jp.resize(jacobians ? 3 * frame.points.size() : 0);
    m_jl.resize(jacobians ? 6 * frame.points.size() : 0);
    frameResiduals(frame, plane, L, m_chart, m_focal, residuals, jacobians ? m_jp.data() : nullptr,
                   jacobians ? m_jl.data() : nullptr);
    for (size_t i = 0; i < frame.points.size(); ++i) {
      const double w = std::sqrt(frame.weights[i]);
      residuals[i] *= w;
      if (jp)
        for (int k = 0; k < kPlaneSize; ++k)
          jp[kPlaneSize * i + k] = w * m_jp[kPlaneSize * i + k];
      if (jl)
        for (int k = 0; k < kLaserSize; ++k)
          jl[kLaserSize * i + k] = w * m_jl[kLaserSize * i + k];
    }
    for (size_t i = 0; i < frame.points.size(); ++i)
      if (!std::isfinite(residuals[i]))
        return false;
    return true;
  }

private:
  const Frame &m_frame;
  const ApexChart &m_chart;
  double m_focal;
  mutable std::vector<double> m_jp, m_jl;
};
} // namespace

ApexChart ApexChart::around(const Eigen::Vector3d &apex)
{
  ApexChart chart;
  chart.a0 = apex.normalized();
  const Eigen::Vector3d helper = std::abs(chart.a0.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  chart.e1 = chart.a0.cross(helper).normalized();
  chart.e2 = chart.a0.cross(chart.e1);
  return chart;
}

LaserVector laserParameters(const vpLaserSolvers::LaserCone &cone, const ApexChart &chart)
{
  const Eigen::Vector3d a = cone.cRl.col(2);
  LaserVector L;
  L(0) = std::atan2(-a.y(), a.z());
  L(1) = std::asin(std::max(-1.0, std::min(1.0, a.x())));
  const Eigen::Vector3d d = cone.apex.normalized();
  const double along = d.dot(chart.a0);
  L(2) = d.dot(chart.e1) / along;
  L(3) = d.dot(chart.e2) / along;
  L(4) = cone.apex.norm();
  L(5) = 2.0 * cone.halfAngle;
  return L;
}

vpLaserSolvers::LaserCone laserCone(const LaserVector &L, const ApexChart &chart)
{
  vpLaserSolvers::LaserCone cone;
  cone.cRl = (Eigen::AngleAxisd(L(0), Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(L(1), Eigen::Vector3d::UnitY()))
                 .toRotationMatrix();
  cone.apex = L(4) * (chart.a0 + L(2) * chart.e1 + L(3) * chart.e2).normalized();
  cone.halfAngle = 0.5 * L(5);
  return cone;
}

Eigen::Vector3d planeParameters(const Eigen::Vector4d &plane)
{
  double h = 0.0, roll = 0.0, pitch = 0.0;
  vpLaserSolvers::altitudeRollPitch(plane, h, roll, pitch);
  return Eigen::Vector3d(roll, pitch, h);
}

Eigen::Vector4d planeOf(const Eigen::Vector3d &P)
{
  return vpLaserSolvers::planeFromAltitudeRollPitch(P(2), P(0), P(1));
}

bool frameResiduals(const Frame &frame, const Eigen::Vector3d &plane, const LaserVector &L, const ApexChart &chart,
                    double focal, double *residuals, double *jacobianPlane, double *jacobianLaser)
{
  const bool derivatives = jacobianPlane != nullptr && jacobianLaser != nullptr;
  double c[6];
  Eigen::Matrix<double, 6, kAll> dc;
  if (derivatives) {
    Jet P[kPlaneSize], Lj[kLaserSize], cj[6];
    for (int k = 0; k < kPlaneSize; ++k)
      P[k] = Jet(plane(k), k);
    for (int k = 0; k < kLaserSize; ++k)
      Lj[k] = Jet(L(k), kPlaneSize + k);
    conicCoefficients(P, Lj, chart, cj);
    for (int k = 0; k < 6; ++k) {
      c[k] = cj[k].a;
      dc.row(k) = cj[k].v.transpose();
    }
  } else {
    conicCoefficients(plane.data(), L.data(), chart, c);
  }
  // The conic's scale is arbitrary (the Sampson distance ignores it): normalise for the rounding.
  double norm = 0.0;
  for (double ck : c)
    norm = std::max(norm, std::abs(ck));
  if (!(norm > 0.0) || !std::isfinite(norm))
    return false;
  for (double &ck : c)
    ck /= norm;
  dc /= norm; // the Sampson distance is invariant under scale: dropping d(norm) only moves ds along c, where it is 0
  bool ok = true;
  for (size_t i = 0; i < frame.points.size(); ++i) {
    double s = 0.0, ds[6];
    ok = sampson(c, frame.points[i].x(), frame.points[i].y(), s, ds) && ok;
    residuals[i] = focal * s;
    if (!derivatives)
      continue;
    const Eigen::Matrix<double, 1, kAll> g = focal * (Eigen::Map<const Eigen::Matrix<double, 1, 6> >(ds) * dc);
    for (int k = 0; k < kPlaneSize; ++k)
      jacobianPlane[kPlaneSize * i + k] = g(k);
    for (int k = 0; k < kLaserSize; ++k)
      jacobianLaser[kLaserSize * i + k] = g(kPlaneSize + k);
  }
  return ok;
}

LaserMatrix frameLaserInformation(const Frame &frame, const LaserVector &L, const ApexChart &chart, double focal,
                                  size_t maxPoints)
{
  Frame sample;
  sample.plane = frame.plane;
  sample.fixedAltitude = frame.fixedAltitude;
  const size_t n = frame.points.size(),
               step = std::max<size_t>(1, (n + maxPoints - 1) / std::max<size_t>(1, maxPoints));
  double total = 0.0, kept = 0.0;
  for (size_t i = 0; i < n; ++i) {
    total += frame.weights[i];
    if (i % step == 0 && frame.weights[i] > 0.0) {
      sample.points.push_back(frame.points[i]);
      sample.weights.push_back(frame.weights[i]);
      kept += frame.weights[i];
    }
  }
  LaserMatrix info = LaserMatrix::Zero();
  const size_t m = sample.points.size();
  if (m < 4)
    return info;
  std::vector<double> r(m), jp(3 * m), jl(6 * m);
  frameResiduals(sample, sample.plane, L, chart, focal, r.data(), jp.data(), jl.data());
  Eigen::Matrix3d Hpp = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, kLaserSize> Hpl = Eigen::Matrix<double, 3, kLaserSize>::Zero();
  for (size_t i = 0; i < m; ++i) {
    const Eigen::Map<const Eigen::Vector3d> a(&jp[3 * i]);
    const Eigen::Map<const LaserVector> b(&jl[6 * i]);
    const double w = sample.weights[i];
    Hpp += w * a * a.transpose();
    Hpl += w * a * b.transpose();
    info += w * b * b.transpose();
  }
  // The plane is eliminated, but for a known altitude, which is held: only roll and pitch then.
  const int eliminated = frame.fixedAltitude ? 2 : 3;
  const Eigen::MatrixXd H = Hpp.topLeftCorner(eliminated, eliminated);
  const Eigen::MatrixXd B = Hpl.topRows(eliminated);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
  if (ldlt.info() != Eigen::Success)
    return LaserMatrix::Zero();
  info -= B.transpose() * ldlt.solve(B);
  return (kept > 0.0 ? total / kept : 1.0) * 0.5 * (info + info.transpose());
}

SolveResult solveJoint(std::vector<Frame> &frames, LaserVector &L, const ApexChart &chart,
                       const SolveSettings &settings)
{
  ceres::Problem::Options problemOptions;
  problemOptions.manifold_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problemOptions);
  std::vector<int> held;
  for (int k = 0; k < kLaserSize; ++k)
    if (!settings.free[k])
      held.push_back(k);
  problem.AddParameterBlock(L.data(), kLaserSize);
  if (!held.empty())
    problem.SetManifold(L.data(), new ceres::SubsetManifold(kLaserSize, held));
  ceres::ParameterBlockOrdering *ordering = new ceres::ParameterBlockOrdering;
  for (Frame &f : frames) {
    problem.AddResidualBlock(new FrameCost(f, chart, settings.focal), nullptr, f.plane.data(), L.data());
    if (f.fixedAltitude)
      problem.SetManifold(f.plane.data(), new ceres::SubsetManifold(kPlaneSize, {2}));
    ordering->AddElementToGroup(f.plane.data(), 0);
  }
  ordering->AddElementToGroup(L.data(), 1);
  ceres::Solver::Options options;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.linear_solver_ordering.reset(ordering);
  options.max_num_iterations = settings.maxIterations;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  SolveResult result;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.failed = summary.termination_type == ceres::FAILURE;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.message = summary.message;
  result.finite = L.allFinite();
  for (const Frame &f : frames)
    result.finite = result.finite && f.plane.allFinite();
  return result;
}
} // namespace vpLaserSelfCal
