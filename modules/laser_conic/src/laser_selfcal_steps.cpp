/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_selfcal_steps.cpp
  \brief The steps of the self-calibration from ground frames (see vpLaserConicSelfCalibration).
*/
#include "laser_selfcal_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/robust/vpRobustScale.h>

namespace vpLaserSelfCal
{
namespace
{
//! Index of the apex distance and of the opening angle in the laser vector.
constexpr int kScale = 4, kAngle = 5;
//! Points farther than this many residual scales from their conic are outliers.
constexpr double kOutlierScales = 3.0;
//! Reweighting rounds under the Cauchy loss before the final least-squares fit.
constexpr int kRobustRounds = 3;
//! Points per frame used to rank the frames by information.
constexpr size_t kSelectionPoints = 64;
//! searchInitialAxis(): frames scored, and the grid of axis tilts (kAxisSearchSteps steps of kAxisSearchStep rad
//! on each side of the initial axis, about both axes of the laser frame: +-12 degrees).
constexpr size_t kAxisSearchFrames = 10;
constexpr int kAxisSearchSteps = 3;
constexpr double kAxisSearchStep = 4.0 * M_PI / 180.0;

typedef vpLaserConicSelfCalibration Facade;

Eigen::Vector4d eigenPlane(const vpPlane &p)
{
  Eigen::Vector4d v(p.getA(), p.getB(), p.getC(), p.getD());
  return v / v.head<3>().norm();
}

vpPlane vispPlane(const Eigen::Vector4d &v) { return vpPlane(v(0), v(1), v(2), v(3)); }

//! log det of a symmetric positive matrix (LDLT), -inf when not positive definite.
double logDet(const Eigen::MatrixXd &M)
{
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
  double sum = 0.0;
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    const double d = ldlt.vectorD()(i);
    if (!(d > 0.0))
      return -std::numeric_limits<double>::infinity();
    sum += std::log(d);
  }
  return sum;
}
} // namespace

namespace
{
//! The laser pose of \e cone: rotation cRl, translation the apex.
vpHomogeneousMatrix laserPoseOf(const vpLaserSolvers::LaserCone &cone)
{
  vpHomogeneousMatrix cMl;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      cMl[i][j] = cone.cRl(i, j);
    cMl[i][3] = cone.apex(i);
  }
  return cMl;
}
} // namespace

Steps::Steps(const vpCameraParameters &cam, double openingAngle, const vpHomogeneousMatrix &cMl)
  : m_cam(cam), m_focal(0.5 * (cam.get_px() + cam.get_py()))
{
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      m_cone0.cRl(i, j) = cMl[i][j];
    m_cone0.apex(i) = cMl[i][3];
  }
  m_cone0.halfAngle = 0.5 * openingAngle;
  m_chart = ApexChart::around(m_cone0.apex);
  m_L = laserParameters(m_cone0, m_chart);
  m_solve.focal = m_focal;
}

bool Steps::initialPlanes(const std::vector<InputFrame> &inputs, StepsOutcome &out)
{
  vpLaserConicPose estimator;
  estimator.setCameraParameters(m_cam);
  // The initial laser is the calibration to be repaired (a knocked mount) or a drawing: the check that the
  // calibration explains each trace refused every frame of a mount knocked by 2 degrees or more, and the
  // self-calibration ran out of frames. Here a plane near the trace is all that is asked.
  estimator.setCalibrationCheck(false);
  estimator.setLaser(2.0 * m_cone0.halfAngle, laserPoseOf(m_cone0));
  m_all.assign(inputs.size(), Frame());
  out.planes.assign(inputs.size(), vpPlane(0, 0, 0, 0));
  unsigned int usable = 0;
  for (size_t k = 0; k < inputs.size(); ++k) {
    const std::vector<vpImagePoint> &pixels = *inputs[k].points;
    Frame &f = m_all[k];
    vpPlane plane;
    std::vector<double> weights(pixels.size(), 1.0);
    // GP-3's inliers with the initial laser start as the frame's points, its outliers at weight 0: the first
    // solve is plain least squares. A frame given a rough plane keeps it, and its inliers when GP-3 finds a plane
    // (with all its points at weight 1, 10 % of outliers per frame stopped the solve at the iteration limit).
    const bool found = estimator.computePlane(pixels, vpLaserConicPose::GP3, plane);
    if (!found && !inputs[k].hasPlane)
      continue; // no plane with the initial laser: the frame is left out
    if (found) {
      weights.assign(pixels.size(), 0.0);
      for (unsigned int i : estimator.getRansacInlierIndex())
        weights[i] = 1.0;
    }
    if (inputs[k].hasPlane)
      plane = inputs[k].plane;
    f.points.resize(pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
      vpPixelMeterConversion::convertPoint(m_cam, pixels[i], f.points[i].x(), f.points[i].y());
    f.weights = weights;
    f.plane = planeParameters(eigenPlane(plane));
    out.planes[k] = plane;
    ++usable;
  }
  return usable >= 3;
}

void Steps::applyScale(const std::vector<InputFrame> &inputs, const StepsSettings &settings)
{
  // The planes were found with the guess's apex distance: one factor brings the whole scene to the given length.
  double ratio = 1.0;
  if (settings.holdApex) {
    ratio = 1.0;
  } else if (settings.apexDistance > 0.0) {
    ratio = settings.apexDistance / m_L(kScale);
  } else {
    std::vector<double> ratios;
    for (size_t k = 0; k < inputs.size(); ++k)
      if (inputs[k].knownAltitude > 0.0 && !m_all[k].points.empty())
        ratios.push_back(inputs[k].knownAltitude / m_all[k].plane(2));
    if (!ratios.empty()) {
      std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
      ratio = ratios[ratios.size() / 2];
    }
  }
  m_L(kScale) *= ratio;
  for (size_t k = 0; k < m_all.size(); ++k) {
    m_all[k].plane(2) *= ratio;
    if (inputs[k].knownAltitude > 0.0) {
      m_all[k].plane(2) = inputs[k].knownAltitude;
      m_all[k].fixedAltitude = true;
    }
  }
  m_solve.free[kScale] = !(settings.apexDistance > 0.0) && !settings.holdApex;
  m_solve.free[2] = m_solve.free[3] = !settings.holdApex;
  m_solve.free[kAngle] = settings.estimateAngle;
}

std::vector<size_t> Steps::selectFrames(const std::vector<InputFrame> &inputs, unsigned int maxFrames) const
{
  std::vector<size_t> usable, chosen;
  for (size_t k = 0; k < m_all.size(); ++k)
    if (!m_all[k].points.empty()) {
      if (inputs[k].knownAltitude > 0.0)
        chosen.push_back(k); // the scale: always kept
      else
        usable.push_back(k);
    }
  if (usable.size() + chosen.size() <= maxFrames) {
    chosen.insert(chosen.end(), usable.begin(), usable.end());
    std::sort(chosen.begin(), chosen.end());
    return chosen;
  }
  // Greedy D-optimal choice on the free laser parameters (the apex distance scaled to a relative change).
  std::vector<int> free;
  for (int k = 0; k < kLaserSize; ++k)
    if (m_solve.free[k])
      free.push_back(k);
  LaserVector scale = LaserVector::Ones();
  scale(kScale) = m_L(kScale);
  std::vector<Eigen::MatrixXd> info(m_all.size());
  double largest = 0.0;
  for (size_t k = 0; k < m_all.size(); ++k) {
    if (m_all[k].points.empty())
      continue;
    const LaserMatrix I = scale.asDiagonal() *
                          frameLaserInformation(m_all[k], m_L, m_chart, m_focal, kSelectionPoints) * scale.asDiagonal();
    info[k].resize(free.size(), free.size());
    for (size_t a = 0; a < free.size(); ++a)
      for (size_t b = 0; b < free.size(); ++b)
        info[k](a, b) = I(free[a], free[b]);
    largest = std::max(largest, info[k].trace());
  }
  Eigen::MatrixXd sum = 1e-9 * largest * Eigen::MatrixXd::Identity(free.size(), free.size());
  for (size_t k : chosen)
    sum += info[k];
  std::vector<bool> taken(m_all.size(), false);
  while (chosen.size() < maxFrames) {
    double best = -std::numeric_limits<double>::infinity();
    size_t pick = m_all.size();
    for (size_t k : usable)
      if (!taken[k]) {
        const double value = logDet(sum + info[k]);
        if (value > best) {
          best = value;
          pick = k;
        }
      }
    if (pick == m_all.size())
      break;
    taken[pick] = true;
    sum += info[pick];
    chosen.push_back(pick);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

void Steps::planesOfFramesLeftOut(const std::vector<InputFrame> &inputs, StepsOutcome &out) const
{
  // Their initial planes were found with the initial laser, at its scale and attitude: beside the planes of the
  // frames used, an altitude 13 % off where those were within 2 % (a guess 10 % off on the apex distance).
  vpLaserConicPose estimator;
  estimator.setCameraParameters(m_cam);
  estimator.setLaser(out.openingAngle, out.cMl);
  for (size_t k = 0; k < inputs.size(); ++k) {
    if (out.used[k])
      continue;
    vpPlane plane(0, 0, 0, 0);
    if (!estimator.computePlane(*inputs[k].points, vpLaserConicPose::GP3, plane))
      plane = vpPlane(0, 0, 0, 0);
    out.planes[k] = plane;
  }
}

std::vector<double> Steps::residuals(const Frame &f) const
{
  std::vector<double> r(f.points.size());
  frameResiduals(f, f.plane, m_L, m_chart, m_focal, r.data(), nullptr, nullptr);
  return r;
}

bool Steps::robustRounds(StepsOutcome &out)
{
  for (int round = 0; round <= kRobustRounds; ++round) {
    const SolveResult result = solveJoint(m_frames, m_L, m_chart, m_solve);
    // A failure of Ceres (its residuals could not be evaluated: lengths of 1e200 m) was reported as the
    // iteration limit, after "0 iterations".
    if (!result.finite || result.failed) {
      out.status = Facade::STATUS_SOLVER_FAILURE;
      out.details = (result.finite ? "Ceres failed (" : "non-finite parameters (") + result.message + ")";
      return false;
    }
    std::vector<std::vector<double> > r(m_frames.size());
    std::vector<double> all;
    for (size_t k = 0; k < m_frames.size(); ++k) {
      r[k] = residuals(m_frames[k]);
      all.insert(all.end(), r[k].begin(), r[k].end());
    }
    const double sigma = std::max(1e-6, vpRobustMadScale(all));
    out.sigma = sigma;
    if (round == kRobustRounds) {
      if (!result.converged) {
        out.status = Facade::STATUS_NO_CONVERGENCE;
        out.details = std::to_string(result.iterations) + " iterations: " + result.message;
        return false;
      }
      double rss = 0.0;
      out.nbPoints = out.nbInliers = 0;
      for (size_t k = 0; k < m_frames.size(); ++k)
        for (size_t i = 0; i < r[k].size(); ++i) {
          ++out.nbPoints;
          if (m_frames[k].weights[i] > 0.0) {
            ++out.nbInliers;
            rss += r[k][i] * r[k][i];
          }
        }
      out.rms = out.nbInliers ? std::sqrt(rss / out.nbInliers) : 0.0;
      return true;
    }
    // Cauchy weights at the current scale, outliers dropped; the last solve is plain least squares on the inliers.
    const bool last = round + 1 == kRobustRounds;
    for (size_t k = 0; k < m_frames.size(); ++k)
      for (size_t i = 0; i < r[k].size(); ++i) {
        const double a = std::abs(r[k][i]);
        m_frames[k].weights[i] =
            a < kOutlierScales * sigma ? (last ? 1.0 : vpRobustWeight(vpRobustLoss::CAUCHY, a, sigma)) : 0.0;
      }
  }
  return true;
}

void Steps::attitudeSpread(StepsOutcome &out) const
{
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Frame &f : m_frames)
    mean += f.plane.head<2>();
  mean /= static_cast<double>(m_frames.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Frame &f : m_frames)
    scatter += (f.plane.head<2>() - mean) * (f.plane.head<2>() - mean).transpose();
  scatter /= static_cast<double>(m_frames.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  out.spreadWeak = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  out.spreadStrong = std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
}

void Steps::analyse(StepsOutcome &out) const
{
  std::vector<int> free;
  for (int k = 0; k < kLaserSize; ++k)
    if (m_solve.free[k])
      free.push_back(k);
  const int p = static_cast<int>(free.size());
  LaserMatrix S = LaserMatrix::Zero();
  double rss = 0.0;
  unsigned int fixedAltitudes = 0;
  for (const Frame &f : m_frames) {
    S += frameLaserInformation(f, m_L, m_chart, m_focal, f.points.size());
    const std::vector<double> r = residuals(f);
    for (size_t i = 0; i < r.size(); ++i)
      rss += f.weights[i] * r[i] * r[i];
    fixedAltitudes += f.fixedAltitude ? 1 : 0;
  }
  const double dof = static_cast<double>(out.nbInliers) - 3.0 * m_frames.size() + fixedAltitudes - p;
  const double variance = dof > 0.0 ? rss / dof : out.sigma * out.sigma;
  // Normal matrix of the free parameters, the apex distance as a relative change (all in radians).
  LaserVector scale = LaserVector::Ones();
  scale(kScale) = m_L(kScale);
  Eigen::MatrixXd Sf(p, p);
  for (int a = 0; a < p; ++a)
    for (int b = 0; b < p; ++b)
      Sf(a, b) = scale(free[a]) * S(free[a], free[b]) * scale(free[b]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Sf);
  const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(p - 1);
  out.condition = lo > 0.0 ? hi / lo : std::numeric_limits<double>::infinity();
  LaserVector weakest = LaserVector::Zero();
  for (int a = 0; a < p; ++a)
    weakest(free[a]) = eig.eigenvectors()(a, 0);
  // Covariance of the free parameters, then of (alpha, beta, apex, A) through the chart (finite differences).
  LaserMatrix C = LaserMatrix::Zero();
  const bool singular = !(lo > 1e-14 * hi);
  if (!singular) {
    const Eigen::MatrixXd inv =
        eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
    for (int a = 0; a < p; ++a)
      for (int b = 0; b < p; ++b)
        C(free[a], free[b]) = variance * scale(free[a]) * inv(a, b) * scale(free[b]);
  }
  LaserMatrix J = LaserMatrix::Zero(); // rows (alpha, beta, apex x, y, z, A), columns the laser vector
  J(0, 0) = J(1, 1) = J(5, 5) = 1.0;
  const Eigen::Vector3d apex = laserCone(m_L, m_chart).apex;
  for (int k = 2; k <= 4; ++k) {
    LaserVector L = m_L;
    const double h = 1e-7 * (k == kScale ? m_L(kScale) : 1.0);
    L(k) += h;
    J.block<3, 1>(2, k) = (laserCone(L, m_chart).apex - apex) / h;
  }
  const LaserMatrix cov = J * C * J.transpose();
  out.covariance.resize(6, 6);
  // Frames that do not determine every parameter: no covariance (NaN), not the zeros of C, which read as known.
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      out.covariance[a][b] = singular ? std::numeric_limits<double>::quiet_NaN() : cov(a, b);
  const double inf = std::numeric_limits<double>::infinity();
  const double uv = 1.0 + m_L(2) * m_L(2) + m_L(3) * m_L(3);
  out.axisStd = singular ? inf : std::sqrt(vpMath::sqr(std::cos(m_L(1))) * C(0, 0) + C(1, 1));
  out.apexDirStd = singular ? inf : std::sqrt(C(2, 2) + C(3, 3)) / uv;
  attitudeSpread(out);
  out.details = degeneracyDetails(out, weakest);
}

std::string Steps::degeneracyDetails(const StepsOutcome &out, const LaserVector &weakest) const
{
  std::ostringstream os;
  os.precision(3);
  os << "attitude spread of the " << m_frames.size() << " frames used " << vpMath::deg(out.spreadWeak)
     << " deg (RMS about their mean, weakest direction; strongest " << vpMath::deg(out.spreadStrong)
     << " deg); standard deviations: axis " << vpMath::deg(out.axisStd) << " deg, apex direction "
     << vpMath::deg(out.apexDirStd) << " deg; condition number " << out.condition;
  // The images leave a one-parameter family of cones (the angle traded against the axis) and the scale: two lengths
  // fix both (known altitudes, and the apex distance when it is given or held).
  unsigned int lengths = m_solve.free[kScale] ? 0 : 1;
  for (const Frame &f : m_frames)
    lengths += f.fixedAltitude ? 1 : 0;
  if (m_solve.free[kAngle] && (lengths < 2 || std::abs(weakest(kAngle)) > 0.3))
    os << "; the opening angle is not determined by the images (any cone with the same epipolar tangents fits): "
          "hold it (no estimation) or give a second length: known altitudes of two frames at different altitudes, "
          "or one with the apex distance";
  return os.str();
}

bool Steps::solveFromTheInitialLaser(const std::vector<InputFrame> &inputs, const StepsSettings &settings,
                                     StepsOutcome &out)
{
  out.used.assign(inputs.size(), false);
  if (!initialPlanes(inputs, out)) {
    out.status = Facade::STATUS_NOT_ENOUGH_FRAMES;
    out.details = "fewer than 3 frames with a ground plane under the initial laser";
    return false;
  }
  applyScale(inputs, settings);
  m_index = selectFrames(inputs, settings.maxFrames);
  m_frames.clear();
  for (size_t k : m_index) {
    m_frames.push_back(m_all[k]);
    out.used[k] = true;
  }
  return robustRounds(out);
}

bool Steps::searchInitialAxis(const std::vector<InputFrame> &inputs)
{
  // GP-3's points within its RANSAC threshold (no scale-adaptive stage, which widens the band to fit a wrong
  // laser) over a few frames spread along the list, under the initial laser's axis tilted on a grid.
  vpLaserConicPose estimator;
  estimator.setCameraParameters(m_cam);
  estimator.setCalibrationCheck(false);
  estimator.setScaleAdaptive(false);
  const size_t stride = std::max<size_t>(1, inputs.size() / kAxisSearchFrames);
  const auto explained = [&](const vpLaserSolvers::LaserCone &cone) {
    estimator.setLaser(2.0 * cone.halfAngle, laserPoseOf(cone));
    unsigned int inliers = 0;
    vpPlane plane;
    for (size_t k = 0; k < inputs.size(); k += stride)
      inliers +=
          estimator.computePlane(*inputs[k].points, vpLaserConicPose::GP3, plane) ? estimator.getRansacNbInliers() : 0u;
    return inliers;
  };
  vpLaserSolvers::LaserCone best = m_cone0;
  unsigned int bestInliers = explained(m_cone0);
  for (int i = -kAxisSearchSteps; i <= kAxisSearchSteps; ++i)
    for (int j = -kAxisSearchSteps; j <= kAxisSearchSteps; ++j) {
      vpLaserSolvers::LaserCone cone = m_cone0;
      cone.cRl = m_cone0.cRl * Eigen::AngleAxisd(i * kAxisSearchStep, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                 Eigen::AngleAxisd(j * kAxisSearchStep, Eigen::Vector3d::UnitY()).toRotationMatrix();
      const unsigned int inliers = explained(cone);
      if (inliers > bestInliers) {
        bestInliers = inliers;
        best = cone;
      }
    }
  if (best.cRl == m_cone0.cRl)
    return false; // the initial axis explains the traces best: nothing better to start from
  m_cone0 = best;
  m_L = laserParameters(m_cone0, m_chart);
  return true;
}

StepsOutcome Steps::run(const std::vector<InputFrame> &inputs, const StepsSettings &settings)
{
  // From a mount knocked by several degrees, the planes GP-3 finds with the initial laser start the joint solve
  // in another valley (8 degrees: a residual scale of 30 px after 1000 iterations, the axis 5 degrees off; 12
  // degrees: planes tilted by thousands of degrees, refused as degenerate): once more from the axis of a grid
  // around the initial one under which GP-3 explains most of the traces, kept when it succeeds.
  StepsOutcome first = attempt(inputs, settings);
  const bool badStart = first.status == Facade::STATUS_NO_CONVERGENCE ||
                        first.status == Facade::STATUS_DEGENERATE_FRAMES ||
                        first.status == Facade::STATUS_TOO_MANY_OUTLIERS;
  if (!badStart || !searchInitialAxis(inputs))
    return first;
  StepsOutcome second = attempt(inputs, settings);
  return second.status == Facade::STATUS_OK ? second : first;
}

StepsOutcome Steps::attempt(const std::vector<InputFrame> &inputs, const StepsSettings &settings)
{
  StepsOutcome out;
  if (!solveFromTheInitialLaser(inputs, settings, out))
    return out;
  if (out.nbInliers < out.nbPoints / 2) {
    out.status = Facade::STATUS_TOO_MANY_OUTLIERS;
    out.details = std::to_string(out.nbInliers) + " inliers of " + std::to_string(out.nbPoints) + " points";
    return out;
  }
  for (size_t j = 0; j < m_index.size(); ++j)
    out.planes[m_index[j]] = vispPlane(planeOf(m_frames[j].plane));
  analyse(out);
  if (!(out.axisStd <= settings.maxStd) || !(out.apexDirStd <= 2.0 * settings.maxStd)) {
    std::ostringstream os;
    os.precision(3);
    os << out.details << "; limit " << vpMath::deg(settings.maxStd) << " deg (axis), "
       << vpMath::deg(2.0 * settings.maxStd) << " deg (apex direction)";
    const double factor = std::max(out.axisStd / settings.maxStd, out.apexDirStd / (2.0 * settings.maxStd));
    if (std::isfinite(factor) && out.spreadWeak > vpMath::rad(0.1))
      os << "; about " << vpMath::deg(out.spreadWeak * factor)
         << " deg of spread needed in the weakest direction (standard deviations scale as 1 / spread)";
    else
      os << "; the frames need attitudes differing by several degrees in roll and in pitch (e.g. +-10 deg)";
    out.status = Facade::STATUS_DEGENERATE_FRAMES;
    out.details = os.str();
    return out;
  }
  const vpLaserSolvers::LaserCone cone = laserCone(m_L, m_chart);
  out.cMl = laserPoseOf(cone);
  out.openingAngle = 2.0 * cone.halfAngle;
  planesOfFramesLeftOut(inputs, out);
  out.status = Facade::STATUS_OK;
  out.details.clear();
  return out;
}
} // namespace vpLaserSelfCal
