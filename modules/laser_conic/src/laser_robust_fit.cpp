/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Scale-adaptive final fit of the circular-laser estimators (see laser_robust_fit.h). Why it exists:
// with an imperfect calibration no plane explains the whole trace within a RANSAC threshold of a few
// pixels, so a consensus set collected with that threshold around a plane keeps the arc the plane
// explains best, and a fit on a partial arc leaves the tilt weakly constrained. The image of the
// trace, however, remains a conic whatever the calibration error: the trace is collected around the
// free conic at the scale of its own residuals, then the plane is fitted on the whole trace.
#include "laser_robust_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <visp3/robust/vpRobustScale.h>

#include "laser_geometry.h"
#include "laser_kernels.h"

namespace vsp::laser_robust_fit
{
namespace
{
using vpLaserSolvers::LaserCone;
using vpLaserSolvers::detail::signedSampson;

//! Rounds of trace collection and of reweighting at most.
constexpr int kCollectRounds = 5;
constexpr int kIrlsRounds = 2;
//! Levenberg-Marquardt iterations per reweighting round (each one pass over the trace).
constexpr int kIrlsIterations = 5;
/*!
  Iterations of the constrained fit made only for the calibration-health figure (final fit FREE):
  it starts from the plane of the free conic, already close, and its RMS residual converges first.
*/
constexpr int kHealthIterations = 4;
//! Significance of the F-test that rejects the constrained fit against the free one.
constexpr double kSelectSignificance = 0.01;

//! Residuals (pixels, signed Sampson distances) of the listed points to the conic.
std::vector<double> residualsOf(const PointList &points, const std::vector<int> &indices, const Eigen::Matrix3d &c,
                                double focal)
{
  const vpLaserSolvers::detail::ConicCoefficients k(c);
  std::vector<double> r;
  r.reserve(indices.size());
  for (int i : indices) {
    double v0, v1;
    const double a = k.apply(points[i](0), points[i](1), v0, v1);
    r.push_back(focal * a / (2.0 * std::sqrt(v0 * v0 + v1 * v1)));
  }
  return r;
}

//! Residuals (pixels) of every point to the conic.
std::vector<double> allResiduals(const PointList &points, const Eigen::Matrix3d &c, double focal)
{
  const vpLaserSolvers::detail::ConicCoefficients k(c);
  std::vector<double> r(points.size());
  // Two points per SIMD register (the square root and the division dominate), the same operations
  // per point as the scalar tail.
  typedef Eigen::Array2d P;
  size_t i = 0;
  for (; i + 1 < points.size(); i += 2) {
    const P x(points[i](0), points[i + 1](0)), y(points[i](1), points[i + 1](1));
    const P v0 = k.a * x + k.b * y + k.d, v1 = k.b * x + k.e * y + k.f;
    const P a = x * v0 + y * v1 + (k.d * x + k.f * y + k.g);
    P::Map(&r[i]) = focal * a / (2.0 * (v0 * v0 + v1 * v1).sqrt());
  }
  for (; i < points.size(); ++i) {
    double v0, v1;
    const double a = k.apply(points[i](0), points[i](1), v0, v1);
    r[i] = focal * a / (2.0 * std::sqrt(v0 * v0 + v1 * v1));
  }
  return r;
}

double rms(const std::vector<double> &r)
{
  double s = 0.0;
  for (double v : r)
    s += v * v;
  return r.empty() ? 0.0 : std::sqrt(s / double(r.size()));
}

PointList subset(const PointList &points, const std::vector<int> &indices)
{
  PointList out;
  out.reserve(indices.size());
  for (int i : indices)
    out.push_back(points[i]);
  return out;
}

Eigen::Matrix3d normalised(const Eigen::Matrix3d &c)
{
  const double n = c.norm();
  return n > 0.0 ? Eigen::Matrix3d(c / n) : c;
}

/*!
  The points of the trace: the free conic fitted on the consensus, the residual scale sigma of the
  consensus to it (MAD), every point within max(threshold, k sigma) collected, and again on the new
  set while it changes. The free conic extrapolates a partial arc well enough that each round
  gathers the rest of the trace. \return false when no ellipse fits the consensus.
*/
bool collectTrace(const PointList &points, const Settings &s, std::vector<int> &inliers, Eigen::Matrix3d &c,
                  double &sigma, std::vector<double> &traceResiduals)
{
  if (!vsp::laser_estimators::fitEllipseOn(points, inliers, c))
    return false;
  std::vector<int> next;
  bool current = false; // traceResiduals and sigma are those of the final inliers to the final conic
  for (int round = 0; round < kCollectRounds; ++round) {
    const std::vector<double> r = allResiduals(points, c, s.focal);
    traceResiduals.clear();
    traceResiduals.reserve(inliers.size());
    for (int i : inliers)
      traceResiduals.push_back(r[static_cast<size_t>(i)]);
    sigma = vpRobustMadScale(traceResiduals);
    current = true;
    vpRobustCollect(r, std::max(s.threshold, s.scaleFactor * sigma), next);
    Eigen::Matrix3d refit;
    if (next.size() < 5 || next == inliers || !vsp::laser_estimators::fitEllipseOn(points, next, refit))
      break;
    inliers.swap(next);
    c = refit;
    current = false;
  }
  if (!current) {
    traceResiduals = residualsOf(points, inliers, c, s.focal);
    sigma = vpRobustMadScale(traceResiduals);
  }
  return true;
}

/*!
  Constrained fit: the plane refined on the trace by IRLS with the Huber loss at the scale of its own
  residuals. The trace is already free of gross outliers; the loss only tempers the few points left
  near it, and, being quadratic up to 1.345 sigma, does not discard the arc a miscalibrated model
  explains worst (which a redescending loss, or a tight inlier threshold, would do).
*/
bool constrainedFit(const PointList &trace, const LaserCone &cone, double focal, bool robust, int iterations,
                    Eigen::Vector4d &plane, std::vector<double> &residuals)
{
  const int n = static_cast<int>(trace.size());
  if (robust) {
    // The residuals of the final plane come from the refinement's own last pass.
    if (!vpLaserSolvers::detail::refinePlaneHuber(trace.data(), n, cone, plane, kIrlsRounds, kIrlsIterations,
                                                  residuals))
      return false;
    for (double &r : residuals)
      r *= focal;
    return true;
  }
  if (!vpLaserSolvers::refinePlane(trace.data(), n, cone, plane, iterations))
    return false;
  residuals = allResiduals(trace, normalised(vpLaserSolvers::conicFromPlane(plane, cone)), focal);
  return true;
}

/*!
  p-value of the F-test of the constrained model (3 parameters) against the free one (5) on n points:
  F = ((RSS_c - RSS_f) / 2) / (RSS_f / (n - 5)), whose survival function for 2 numerator degrees of
  freedom is (1 + 2 F / (n - 5))^(-(n - 5) / 2).
*/
double constrainedPValue(double rssConstrained, double rssFree, int n)
{
  const double dof = double(n - 5);
  if (!(dof > 0.0) || !(rssConstrained > rssFree) || !(rssFree > 0.0))
    return 1.0;
  const double F = 0.5 * (rssConstrained - rssFree) / (rssFree / dof);
  return std::pow(1.0 + 2.0 * F / dof, -0.5 * dof);
}

//! (altitude, roll, pitch) of a plane.
Eigen::Vector3d attitudeOf(const Eigen::Vector4d &plane)
{
  Eigen::Vector3d a;
  vpLaserSolvers::altitudeRollPitch(plane, a(0), a(1), a(2));
  return a;
}

//! Jacobian (4x3) of the plane with respect to (altitude, roll, pitch).
Eigen::Matrix<double, 4, 3> planeJacobian(const Eigen::Vector3d &a)
{
  Eigen::Matrix<double, 4, 3> P;
  const double h = 1e-7;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d plus = a, minus = a;
    plus(j) += h;
    minus(j) -= h;
    P.col(j) = (vpLaserSolvers::planeFromAltitudeRollPitch(plus(0), plus(1), plus(2)) -
                vpLaserSolvers::planeFromAltitudeRollPitch(minus(0), minus(1), minus(2))) /
               (2.0 * h);
  }
  return P;
}

/*!
  Covariance of (altitude, roll, pitch) of the constrained fit: sigma^2 (J^T J)^-1 with J the
  Jacobian of the residuals (pixels) with respect to those three parameters and sigma^2 = RSS / (n - 3).
*/
Eigen::Matrix3d constrainedCovariance(const PointList &trace, const LaserCone &cone, double focal,
                                      const Eigen::Vector4d &plane, double rss)
{
  const Eigen::Vector3d a = attitudeOf(plane);
  const int n = static_cast<int>(trace.size());
  Eigen::MatrixXd J(n, 3);
  for (int j = 0; j < 3; ++j) {
    const double h = j == 0 ? 1e-7 * std::max(1.0, a(0)) : 1e-7;
    Eigen::Vector3d plus = a, minus = a;
    plus(j) += h;
    minus(j) -= h;
    const Eigen::Matrix3d cp = vpLaserSolvers::conicFromPlane(
                              vpLaserSolvers::planeFromAltitudeRollPitch(plus(0), plus(1), plus(2)), cone),
                          cm = vpLaserSolvers::conicFromPlane(
                              vpLaserSolvers::planeFromAltitudeRollPitch(minus(0), minus(1), minus(2)), cone);
    for (int i = 0; i < n; ++i)
      J(i, j) = focal * (signedSampson(cp, trace[i]) - signedSampson(cm, trace[i])) / (2.0 * h);
  }
  // No residual degree of freedom left (3 points or fewer): no noise to scale by, no covariance.
  if (n <= 3)
    return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const double sigma2 = rss / (n - 3);
  return sigma2 * (J.transpose() * J).inverse();
}

/*!
  The residual sum of squares the constrained fit's covariance is scaled by when that fit is Huber's (IRLS at
  kHuberTuning times the residuals' MAD scale, constrainedFit()): sum psi(r)^2 / (mean psi'(r))^2, the M-estimator's
  sandwich (psi(r) = r clipped at the threshold, psi' = 1 inside it, 0 beyond). With Gaussian noise it is 1.053
  times the sum of squares: the Huber fit is 95 % as efficient as least squares, and the plain sum understated
  its variance by that much.
*/
double huberRss(const std::vector<double> &residuals)
{
  const double c = vpLaserSolvers::detail::kHuberTuning * vpRobustMadScale(residuals);
  double psi2 = 0.0, rss = 0.0;
  size_t inside = 0;
  for (double r : residuals) {
    const double clipped = std::max(-c, std::min(c, r));
    psi2 += clipped * clipped;
    rss += r * r;
    inside += std::fabs(r) <= c ? 1 : 0;
  }
  if (!(c > 0.0)) // no scale to clip at: the plain sum of squares
    return rss;
  const double share = static_cast<double>(inside) / static_cast<double>(residuals.size());
  return share > 0.0 ? psi2 / (share * share) : std::numeric_limits<double>::quiet_NaN();
}

/*!
  Covariance of (altitude, roll, pitch) of the free fit: the conic moves in the 5 directions of the
  symmetric matrices orthogonal to it; their covariance sigma^2 (J^T J)^-1 (sigma^2 = RSS / (n - 5))
  is propagated through the plane pair by its Jacobian (central differences).
*/
bool freeCovariance(const PointList &trace, const LaserCone &cone, double focal, const Eigen::Matrix3d &conic,
                    double rss, Eigen::Matrix3d &cov)
{
  const Eigen::Matrix3d c0 = normalised(conic);
  // Orthonormal basis of the symmetric matrices (Frobenius inner product), then Gram-Schmidt against c0.
  Eigen::Matrix3d basis[6];
  int nb = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
      e(i, j) = e(j, i) = i == j ? 1.0 : std::sqrt(0.5);
      basis[nb++] = e;
    }
  Eigen::Matrix3d dirs[5];
  int nd = 0;
  for (int k = 0; k < 6 && nd < 5; ++k) {
    Eigen::Matrix3d v = basis[k] - (basis[k].cwiseProduct(c0).sum()) * c0;
    for (int m = 0; m < nd; ++m)
      v -= v.cwiseProduct(dirs[m]).sum() * dirs[m];
    const double norm = v.norm();
    if (norm > 0.3)
      dirs[nd++] = v / norm;
  }
  if (nd < 5)
    return false;
  const int n = static_cast<int>(trace.size());
  const double h = 1e-7;
  Eigen::MatrixXd J(n, 5);
  Eigen::Matrix<double, 3, 5> G;
  for (int k = 0; k < 5; ++k) {
    const Eigen::Matrix3d cp = c0 + h * dirs[k], cm = c0 - h * dirs[k];
    for (int i = 0; i < n; ++i)
      J(i, k) = focal * (signedSampson(cp, trace[i]) - signedSampson(cm, trace[i])) / (2.0 * h);
    Eigen::Vector4d pp, pm;
    if (!vpLaserSolvers::planePair(cp, cone, pp) || !vpLaserSolvers::planePair(cm, cone, pm))
      return false;
    Eigen::Vector3d ap = attitudeOf(pp), am = attitudeOf(pm);
    G.col(k) = (ap - am) / (2.0 * h);
  }
  if (n <= 5) // the conic goes through the points: no residual to measure the noise by (the covariance was 0)
    return false;
  const double sigma2 = rss / (n - 5);
  const Eigen::Matrix<double, 5, 5> info = J.transpose() * J;
  cov = G * (sigma2 * info.inverse()) * G.transpose();
  return cov.allFinite();
}
} // namespace

bool ellipseCentre(const Eigen::Matrix3d &c, Eigen::Vector2d &centre)
{
  const Eigen::Matrix2d A = 0.5 * (c.topLeftCorner<2, 2>() + c.topLeftCorner<2, 2>().transpose());
  const Eigen::Vector2d b = 0.5 * (c.topRightCorner<2, 1>() + c.bottomLeftCorner<1, 2>().transpose());
  if (!(std::fabs(A.determinant()) > 0.0))
    return false;
  centre = -A.inverse() * b;
  // A determinant that is subnormal (an ellipse fitted to points of 1e78 px has coefficients near 1e-157)
  // gives an infinite or NaN centre, around which no point has an angle.
  return centre.allFinite();
}

double arcCoverage(const PointList &points, const std::vector<int> &indices, const Eigen::Matrix3d &conic)
{
  Eigen::Matrix3d c = conic;
  if (c(0, 0) < 0.0)
    c = -c;
  const Eigen::Matrix2d A = c.topLeftCorner<2, 2>();
  const Eigen::LLT<Eigen::Matrix2d> llt(A);
  if (llt.info() != Eigen::Success || indices.empty())
    return 0.0;
  Eigen::Vector2d centre;
  if (!ellipseCentre(c, centre))
    return 0.0;
  const Eigen::Matrix2d U = llt.matrixU(); // A = U^T U: U (x - centre) lies on a circle
  // Occupied bins of 0.5 deg around the ellipse; the coverage is the circle minus its largest empty run.
  constexpr int kBins = 720;
  std::vector<int> bins(indices.size());
  vpLaserSolvers::detail::ellipseBins(points.data(), indices.data(), static_cast<int>(indices.size()), centre, U, kBins,
                                      bins.data());
  char occupied[kBins] = {};
  for (int bin : bins)
    if (bin >= 0) // -1: a point without an angle (see ellipseBins())
      occupied[std::min(kBins - 1, bin)] = 1;
  int first = -1, last = -1, gap = 0;
  for (int b = 0; b < kBins; ++b) {
    if (!occupied[b])
      continue;
    if (last >= 0)
      gap = std::max(gap, b - last - 1);
    if (first < 0)
      first = b;
    last = b;
  }
  if (first < 0)
    return 0.0;
  gap = std::max(gap, first + kBins - last - 1); // the run across the +-pi cut
  return 2.0 * M_PI * double(kBins - gap) / kBins;
}

namespace
{
/*!
  Points evenly spread in azimuth around the whole trace of \e plane (normalized image coordinates): the lines
  of the cone cut by the plane in front of the camera.
*/
PointList wholeTrace(const Eigen::Vector4d &plane, const LaserCone &cone, size_t count)
{
  PointList trace;
  trace.reserve(count);
  const double s = std::sin(cone.halfAngle), c = std::cos(cone.halfAngle);
  for (size_t k = 0; k < count; ++k) {
    const double phi = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(count);
    const Eigen::Vector3d ray = cone.cRl * Eigen::Vector3d(s * std::cos(phi), s * std::sin(phi), c);
    const double along = plane.head<3>().dot(ray);
    if (along == 0.0)
      continue;
    const Eigen::Vector3d X = cone.apex - ((plane.head<3>().dot(cone.apex) + plane(3)) / along) * ray;
    if (X.z() > 0.0) // one line of the cone a step in azimuth: either nappe, as the image conic holds both
      trace.emplace_back(X.x() / X.z(), X.y() / X.z());
  }
  return trace;
}

//! The largest eigenvalue of the attitude's 2 x 2 block of a covariance of (altitude, roll, pitch).
double worstTiltVariance(const Eigen::Matrix3d &covariance)
{
  const Eigen::Matrix2d tilt = covariance.bottomRightCorner<2, 2>();
  return 0.5 * tilt.trace() + std::hypot(0.5 * (tilt(0, 0) - tilt(1, 1)), tilt(0, 1));
}

/*!
  The trace's geometry, into res.altitudeDilution, res.attitudeDeviation and res.wholeAttitudeDeviation (from
  at most kGeometryPoints of its points: the ratios and the scaled deviations do not depend on their number),
  from the constrained fit's covariance at unit residual scale:
  - the altitude's dilution: how many times its standard deviation from \e trace exceeds that from as many
    points spread over the whole trace of the same plane, at the same noise: the trace's geometry alone (a
    short arc, a piece of curve), whatever the noise and the number of points;
  - the attitude's standard deviation (radians, the worst direction of tilt) from all the points of \e trace
    at its residual scale: with the laser's apex too close to the camera for the distance of the ground,
    the trace hardly moves with the plane and any tilt fits it.
*/
void measureTraceGeometry(const PointList &trace, const LaserCone &cone, double focal, Result &res)
{
  constexpr size_t kGeometryPoints = 48;
  const size_t n = trace.size(), step = (n + kGeometryPoints - 1) / kGeometryPoints;
  PointList sample;
  sample.reserve(n / step + 1);
  for (size_t i = 0; i < n; i += step)
    sample.push_back(trace[i]);
  const double unitRss = static_cast<double>(sample.size());
  const Eigen::Matrix3d actual = constrainedCovariance(sample, cone, focal, res.plane, unitRss);
  // For all the points, each as uncertain as their scatter says but no less than kMinTraceError.
  const double error = std::max(res.sigma, kMinTraceError);
  res.attitudeDeviation =
      error * std::sqrt(worstTiltVariance(actual) * static_cast<double>(sample.size()) / static_cast<double>(n));
  const PointList whole = wholeTrace(res.plane, cone, sample.size());
  // Most of the plane's trace behind the camera: no ring to compare with (the plane's own checks refuse it).
  if (whole.size() < sample.size() / 2)
    return;
  const Eigen::Matrix3d wholeCovariance =
      constrainedCovariance(whole, cone, focal, res.plane, static_cast<double>(whole.size()));
  res.wholeAttitudeDeviation = error * std::sqrt(worstTiltVariance(wholeCovariance) *
                                                 static_cast<double>(whole.size()) / static_cast<double>(n));
  const double ideal = wholeCovariance(0, 0);
  if (ideal > 0.0 && std::isfinite(ideal)) // else no reference
    res.altitudeDilution =
        std::sqrt(actual(0, 0) / ideal * static_cast<double>(sample.size()) / static_cast<double>(whole.size()));
}

//! The tests of the trace's geometry (measureTraceGeometry()) that \e s enables, on the final plane of \e res.
Outcome checkTraceGeometry(const PointList &trace, const LaserCone &cone, const Settings &s, Result &res)
{
  if (!(s.maxAltitudeDilution > 0.0 || s.maxAttitudeDeviation > 0.0))
    return Outcome::OK;
  measureTraceGeometry(trace, cone, s.focal, res);
  if (s.maxAltitudeDilution > 0.0 && !(res.altitudeDilution <= s.maxAltitudeDilution))
    return Outcome::WEAK_TRACE;
  if (s.maxAttitudeDeviation > 0.0 && !(res.attitudeDeviation <= s.maxAttitudeDeviation))
    // The whole ring would fix the attitude: the trace's geometry is at fault (a short arc), not the parallax.
    return res.wholeAttitudeDeviation <= s.maxAttitudeDeviation ? Outcome::WEAK_TRACE : Outcome::NO_PARALLAX;
  return Outcome::OK;
}

//! The covariance of (altitude, roll, pitch) symmetrised into \e res, and that of the plane through its Jacobian.
void storeCovariances(const Eigen::Matrix3d &cov, Result &res)
{
  res.covariance = 0.5 * (cov + cov.transpose());
  const Eigen::Matrix<double, 4, 3> P = planeJacobian(attitudeOf(res.plane));
  const Eigen::Matrix4d pc = P * res.covariance * P.transpose();
  res.planeCovariance = 0.5 * (pc + pc.transpose());
}
} // namespace

Outcome fit(const PointList &points, const std::vector<int> &inliers, const LaserCone &cone,
            const Eigen::Vector4d &startPlane, const Settings &s, Result &res)
{
  res.inliers = inliers;
  Eigen::Matrix3d freeConic;
  std::vector<double> rf; // residuals (pixels) of the trace to the free conic
  if (s.adaptive) {
    if (!collectTrace(points, s, res.inliers, freeConic, res.sigma, rf))
      return Outcome::NOT_AN_ELLIPSE;
  } else {
    if (!vsp::laser_estimators::fitEllipseOn(points, res.inliers, freeConic))
      return Outcome::NOT_AN_ELLIPSE;
    rf = residualsOf(points, res.inliers, freeConic, s.focal);
    res.sigma = vpRobustMadScale(rf);
  }
  res.coverage = arcCoverage(points, res.inliers, freeConic);
  if (s.minCoverage > 0.0 && res.coverage < s.minCoverage)
    return Outcome::SHORT_ARC;

  const PointList trace = subset(points, res.inliers);
  const int n = static_cast<int>(trace.size());
  res.rmsFree = rms(rf);

  Eigen::Vector4d freePlane = Eigen::Vector4d::Zero();
  const bool hasFreePlane = vpLaserSolvers::planePair(freeConic, cone, freePlane);
  // The constrained fit starts from the RANSAC plane (GP-3) or from the plane of the free conic.
  Eigen::Vector4d constrainedPlane = startPlane.head<3>().norm() > 0.0 ? startPlane : freePlane;
  std::vector<double> rc;
  const bool hasConstrained = constrainedPlane.head<3>().norm() > 0.0 &&
                              constrainedFit(trace, cone, s.focal, s.adaptive && s.finalFit != FinalFit::FREE,
                                             s.finalFit == FinalFit::FREE ? kHealthIterations : 20, constrainedPlane,
                                             rc) &&
                              constrainedPlane.allFinite();
  const Eigen::Matrix3d constrainedConic =
      hasConstrained ? normalised(vpLaserSolvers::conicFromPlane(constrainedPlane, cone)) : Eigen::Matrix3d::Zero();
  if (!hasConstrained)
    rc.clear();
  res.rmsConstrained = hasConstrained ? rms(rc) : std::numeric_limits<double>::quiet_NaN();

  bool useConstrained = false;
  switch (s.finalFit) {
  case FinalFit::FREE:
    useConstrained = false;
    break;
  case FinalFit::CONSTRAINED:
    useConstrained = hasConstrained;
    break;
  case FinalFit::SELECT: {
    const double rssC = res.rmsConstrained * res.rmsConstrained * n, rssF = res.rmsFree * res.rmsFree * n;
    useConstrained = hasConstrained && (!hasFreePlane || constrainedPValue(rssC, rssF, n) >= kSelectSignificance);
    break;
  }
  }
  if (!useConstrained && !hasFreePlane)
    return Outcome::NO_PLANE;
  res.constrainedChosen = useConstrained;
  res.plane = useConstrained ? constrainedPlane : freePlane;
  res.conic = useConstrained ? constrainedConic : freeConic;

  const Outcome geometry = checkTraceGeometry(trace, cone, s, res);
  if (geometry != Outcome::OK)
    return geometry;
  if (s.covariance) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    if (useConstrained) {
      const bool huber = s.adaptive && s.finalFit != FinalFit::FREE; // as constrainedFit() was called
      cov = constrainedCovariance(trace, cone, s.focal, res.plane,
                                  huber ? huberRss(rc) : res.rmsConstrained * res.rmsConstrained * n);
    } else if (!freeCovariance(trace, cone, s.focal, freeConic, res.rmsFree * res.rmsFree * n, cov)) {
      cov.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    storeCovariances(cov, res);
  }
  return Outcome::OK;
}
} // namespace vsp::laser_robust_fit
