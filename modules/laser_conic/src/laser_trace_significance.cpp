/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_trace_significance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "laser_geometry.h"

namespace vsp::laser_trace_significance
{
namespace
{
// log C(n, k)
double logChoose(double n, double k) { return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0); }

// Perimeter of the ellipse \e conic, +infinity when it is no ellipse.
double ellipsePerimeter(const Eigen::Matrix3d &conic)
{
  Eigen::Vector2d centre;
  Eigen::Matrix2d axes;
  double a = 0.0, b = 0.0;
  return vpLaserSolvers::detail::ellipseAxes(conic, centre, axes, a, b) ? vpLaserSolvers::detail::ellipsePerimeter(a, b)
                                                                        : std::numeric_limits<double>::infinity();
}
} // namespace

bool allCollinear(const vsp::laser_estimators::PointList &points)
{
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d &p : points)
    mean += p;
  mean /= double(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d &p : points)
    scatter += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const double largest = eig.eigenvalues()(1);
  return !(largest > 0.0) || !(eig.eigenvalues()(0) > 1e-20 * largest);
}

double logBinomialTail(double n, double k, double p)
{
  if (k <= 0.0 || p >= 1.0)
    return 0.0;
  if (k > n || p <= 0.0)
    return -std::numeric_limits<double>::infinity();
  if (k <= n * p)
    return 0.0; // at or below the mean: the tail holds about half of the mass or more, counted as all of it
  // Past the mean the terms fall by (n - j) p / ((j + 1)(1 - p)) < 1 each: summed until they no longer count.
  const double logP = std::log(p), logQ = std::log1p(-p);
  const double first = logChoose(n, k) + k * logP + (n - k) * logQ;
  double sum = 1.0, term = 1.0; // relative to the first term
  for (double j = k; j < n && term > 1e-17 * sum; ++j) {
    term *= (n - j) / (j + 1.0) * p / (1.0 - p);
    sum += term;
  }
  return first + std::log(sum);
}

double log10FalseAlarms(const vsp::laser_estimators::PointList &points, size_t inliers, const Eigen::Matrix3d &conic,
                        double coverage, double halfWidth, int sampleSize)
{
  const double n = static_cast<double>(points.size()), m = static_cast<double>(sampleSize);
  if (points.empty() || n <= m)
    return std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo = points.front(), hi = points.front();
  for (const Eigen::Vector2d &p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d size = (hi - lo).cwiseMax(2.0 * halfWidth); // a flat box still holds the band's width
  // The covered arc; inside the box, no convex arc is longer than the box's perimeter.
  const double arc = std::min(ellipsePerimeter(conic) * coverage / (2.0 * M_PI), 2.0 * (size.x() + size.y()));
  if (!std::isfinite(arc))
    return std::numeric_limits<double>::infinity();
  const double p = std::min(1.0, 2.0 * halfWidth * arc / (size.x() * size.y()));
  const double logNfa = logChoose(n, m) + logBinomialTail(n - m, static_cast<double>(inliers) - m, p);
  return logNfa / std::log(10.0);
}

double log10FalseAlarms(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                        const vsp::laser_robust_fit::Settings &settings, int sampleSize)
{
  const double band = settings.adaptive ? std::max(settings.threshold, settings.scaleFactor * result.sigma)
                                        : settings.threshold;
  return log10FalseAlarms(points, result.inliers.size(), result.conic, result.coverage, band / settings.focal,
                          sampleSize);
}

std::string clutterReason(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                          const vsp::laser_robust_fit::Settings &settings, int sampleSize)
{
  // Every point on the conic: no clutter to tell the trace from (five points of a trace, the fewest taken, fit a
  // conic as five at random do; refusing them would refuse every sparse trace given alone).
  if (result.inliers.size() >= points.size())
    return std::string();
  const double falseAlarms = log10FalseAlarms(points, result, settings, sampleSize);
  if (falseAlarms < kMaxLog10FalseAlarms)
    return std::string();
  std::ostringstream os;
  os.precision(2);
  os << " (" << result.inliers.size() << " of " << points.size()
     << " points on the best conic: as many as points at random would give, 1e" << std::fixed << falseAlarms
     << " false alarms; a trace gives far fewer than 1e" << kMaxLog10FalseAlarms << ")";
  return os.str();
}
} // namespace vsp::laser_trace_significance
