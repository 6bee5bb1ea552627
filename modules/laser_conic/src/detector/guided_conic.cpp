/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The conic of the guided pass: a robust ellipse through the first pass's points, and its crossings with
// the image rows and columns, the lines along which its profiles are measured.
#include "guided_detail.h"

#include <algorithm>
#include <cmath>

#include <visp3/robust/vpRansac.h>

#include "../laser_estimators.h"
#include "search_region.h"

namespace vsp::laser_detector
{
namespace
{
// The symmetric coefficients a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f of C, scaled to a largest of 1.
struct ConicCoefficients
{
  double a, b, c, d, e, f;
  explicit ConicCoefficients(const Eigen::Matrix3d &C)
  {
    const Eigen::Matrix3d S = 0.5 * (C + C.transpose());
    const double scale = S.cwiseAbs().maxCoeff();
    const double k = scale > 0.0 ? 1.0 / scale : 1.0;
    a = k * S(0, 0), b = k * S(0, 1), c = k * S(1, 1), d = k * S(0, 2), e = k * S(1, 2), f = k * S(2, 2);
  }
  // Centre of the ellipse; false for a parabola (no centre).
  bool centre(double &u, double &v) const
  {
    const double det = a * c - b * b;
    if (!(std::fabs(det) > 1e-300))
      return false;
    u = (b * e - c * d) / det;
    v = (b * d - a * e) / det;
    return std::isfinite(u) && std::isfinite(v);
  }
};

// Arc (radians) around (uc, vc) covered by the points: 36 sectors of 10 degrees, the occupied ones.
double sectorCoverage(const vsp::laser_estimators::PointList &points, const std::vector<int> &indices, double uc,
                      double vc)
{
  const double pi = 3.14159265358979323846;
  bool occupied[36] = {false};
  for (int i : indices) {
    const double t = std::atan2(points[i].y() - vc, points[i].x() - uc) + pi;
    occupied[std::min(35, static_cast<int>(t / (2.0 * pi) * 36.0))] = true;
  }
  return static_cast<double>(std::count(occupied, occupied + 36, true)) * (2.0 * pi / 36.0);
}

// A point of the second pass in the frame of the conic: its unit normal, its signed offset along it (first
// order: F / |grad F|) and its angle around the centre (the order along the curve).
struct OnConic
{
  double u, v, nu, nv, offset, angle;
};

// The offset at s = 0 of the straight line fitted to the (s, offset) pairs within RidgeTuning::guidedSmoothOutlier
// of their median; false when fewer than RidgeTuning::guidedSmoothMinPoints remain.
bool fitOffset(std::vector<std::pair<double, double> > &pairs, std::vector<double> &scratch, double &offset)
{
  scratch.clear();
  for (const auto &p : pairs)
    scratch.push_back(p.second);
  std::nth_element(scratch.begin(), scratch.begin() + scratch.size() / 2, scratch.end());
  const double median = scratch[scratch.size() / 2];
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, t0 = 0.0, t1 = 0.0;
  for (const auto &p : pairs)
    if (std::fabs(p.second - median) <= RidgeTuning::guidedSmoothOutlier) {
      s0 += 1.0, s1 += p.first, s2 += p.first * p.first, t0 += p.second, t1 += p.first * p.second;
    }
  if (s0 < RidgeTuning::guidedSmoothMinPoints)
    return false;
  const double det = s0 * s2 - s1 * s1;
  offset = det > 1e-9 * s0 * s2 ? (s2 * t0 - s1 * t1) / det : t0 / s0;
  return true;
}

// The neighbours of point order[p] within RidgeTuning::guidedSmoothRadius pixels along the sorted points (both
// ways, around the ring), as (position along the tangent, offset) pairs, itself included.
void neighbours(const std::vector<OnConic> &points, const std::vector<int> &order, size_t p,
                std::vector<std::pair<double, double> > &pairs)
{
  const OnConic &c = points[static_cast<size_t>(order[p])];
  const size_t n = order.size();
  pairs.assign(1, std::make_pair(0.0, c.offset));
  size_t walked = 0; // points taken forward: backward stops before them (a ring shorter than the window)
  for (int direction : {1, -1})
    for (size_t step = 1; step + walked < n; ++step) {
      const size_t q = direction > 0 ? (p + step) % n : (p + n - step) % n;
      const OnConic &o = points[static_cast<size_t>(order[q])];
      const double du = o.u - c.u, dv = o.v - c.v;
      if (du * du + dv * dv > RidgeTuning::guidedSmoothRadius * RidgeTuning::guidedSmoothRadius)
        break;
      pairs.push_back(std::make_pair(du * -c.nv + dv * c.nu, o.offset));
      if (direction > 0)
        ++walked;
    }
}
} // namespace

bool fitTraceEllipse(const std::vector<vpImagePoint> &points, int W, int H, int minInliers, Eigen::Matrix3d &C,
                     std::vector<int> &inliers)
{
  inliers.clear();
  if (static_cast<int>(points.size()) < std::max(5, minInliers))
    return false;
  // RANSAC on a subsample (a few hundred points locate the trace as well as all of them), the inliers and
  // the refit on every point. The subsample is chosen by position and sorted: the same points in any order
  // give the same ellipse (the first pass's order depends on how it searched).
  const unsigned int stride = static_cast<unsigned int>(std::max<size_t>(1, points.size() / 300));
  vsp::laser_estimators::PointList all, sample;
  all.reserve(points.size());
  for (const vpImagePoint &p : points) {
    all.push_back(Eigen::Vector2d(p.get_u(), p.get_v()));
    const unsigned int iu = static_cast<unsigned int>(std::max(0.0, p.get_u())),
                       iv = static_cast<unsigned int>(std::max(0.0, p.get_v()));
    if (((iu * 73856093u) ^ (iv * 19349663u)) % stride == 0)
      sample.push_back(all.back());
  }
  std::sort(sample.begin(), sample.end(), [](const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
    return a.y() < b.y() || (a.y() == b.y() && a.x() < b.x());
  });
  // Most frames hold the trace alone: the least-squares ellipse of the subsample then fits nearly all of it,
  // and RANSAC (a singular value decomposition per sample) is needed only when it does not.
  const double threshold = 2.0; // pixels: the first pass's centres are within a few tenths of the trace
  std::vector<int> everyone(sample.size());
  for (size_t k = 0; k < sample.size(); ++k)
    everyone[k] = static_cast<int>(k);
  bool fitted = vsp::laser_estimators::fitEllipseOn(sample, everyone, C);
  if (fitted) {
    size_t close = 0;
    for (const Eigen::Vector2d &p : sample)
      close += vpLaserSolvers::sampsonDistance(C, p) <= threshold ? 1 : 0;
    fitted = close >= sample.size() * 9 / 10;
  }
  if (!fitted) {
    const vsp::laser_estimators::Pp5Estimator estimator(sample);
    vpRansacOptions options;
    options.threshold = threshold;
    options.seed = 1;
    // Few samples, no local optimisation: five-point conics cost a singular value decomposition each, and a
    // trace that is most of the points needs few (40 samples find a 60 % majority with 96 % probability);
    // a frame whose points make no ellipse (no trace, or a hyperbola's arc) must not cost more.
    options.maxTrials = 40;
    options.localOptimisation = false;
    vpRansacReport ransac;
    if (!vpRansacLoop(estimator, options, C, ransac))
      return false;
  }
  for (int round = 0; round < 2; ++round) { // inliers of all points, refit, once more
    inliers.clear();
    for (int k = 0; k < static_cast<int>(all.size()); ++k)
      if (vpLaserSolvers::sampsonDistance(C, all[k]) <= threshold)
        inliers.push_back(k);
    if (static_cast<int>(inliers.size()) < minInliers || !vsp::laser_estimators::fitEllipseOn(all, inliers, C))
      return false;
  }
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  const double pi = 3.14159265358979323846, diagonal = std::hypot(W, H);
  if (!k.centre(uc, vc) || std::hypot(uc - 0.5 * W, vc - 0.5 * H) > 4.0 * diagonal)
    return false; // a huge ellipse: a few straight pieces, not a ring
  return sectorCoverage(all, inliers, uc, vc) >= pi / 3.0;
}

void smoothAlongCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings)
{
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  if (crossings.size() < static_cast<size_t>(RidgeTuning::guidedSmoothMinPoints) || !k.centre(uc, vc))
    return;
  std::vector<OnConic> points;
  std::vector<int> order;
  for (const Crossing &x : crossings) {
    const double u = x.point.get_u(), v = x.point.get_v();
    const double fu = k.a * u + k.b * v + k.d, fv = k.b * u + k.c * v + k.e, norm = std::hypot(fu, fv);
    const double F = k.a * u * u + 2.0 * k.b * u * v + k.c * v * v + 2.0 * k.d * u + 2.0 * k.e * v + k.f;
    if (!(norm > 0.0))
      return;
    order.push_back(static_cast<int>(points.size()));
    points.push_back(OnConic{u, v, fu / norm, fv / norm, F / (2.0 * norm), std::atan2(v - vc, u - uc)});
  }
  std::sort(order.begin(), order.end(), [&](int p, int q) { return points[p].angle < points[q].angle; });
  std::vector<std::pair<double, double> > pairs;
  std::vector<double> scratch, shifts(points.size(), 0.0);
  for (size_t p = 0; p < order.size(); ++p) {
    neighbours(points, order, p, pairs);
    double offset = 0.0;
    const OnConic &c = points[static_cast<size_t>(order[p])];
    if (fitOffset(pairs, scratch, offset))
      shifts[static_cast<size_t>(order[p])] = offset - c.offset;
  }
  // Moved once all the fits are done: each fit reads the offsets as measured.
  for (size_t i = 0; i < crossings.size(); ++i)
    crossings[i].point = vpImagePoint(points[i].v + shifts[i] * points[i].nv, points[i].u + shifts[i] * points[i].nu);
}

bool sampleConic(const Eigen::Matrix3d &C, int W, int H, double margin, int step, std::vector<GuidedSample> &samples)
{
  samples.clear();
  if (!vpLaserSolvers::isEllipse(C))
    return false;
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  if (!k.centre(uc, vc))
    return false;
  std::vector<double> roots;
  // Crossings of row v = t (alongRow) or column u = t: where the gradient is more along the line than
  // across it, the line crosses the curve at 45 degrees or more.
  auto add = [&](bool alongRow, int t, double x) {
    const double u = alongRow ? x : t, v = alongRow ? t : x;
    const double fu = k.a * u + k.b * v + k.d, fv = k.b * u + k.c * v + k.e, norm = std::hypot(fu, fv);
    const double along = std::fabs(alongRow ? fu : fv), across = std::fabs(alongRow ? fv : fu);
    if (!(norm > 0.0) || along < across || (!alongRow && along == across))
      return;
    const int n = alongRow ? W : H;
    if (x < -margin || x > n - 1 + margin)
      return;
    const double toNormal = along / norm;
    const double slope = -(alongRow ? fv : fu) / (alongRow ? fu : fv);
    samples.push_back(GuidedSample{alongRow, t, x, margin / toNormal, toNormal, std::atan2(v - vc, u - uc), slope});
  };
  for (int v = 0; v < H; v += step) {
    roots.clear();
    solveQuadratic(k.a, 2.0 * (k.b * v + k.d), k.c * v * v + 2.0 * k.e * v + k.f, roots);
    for (double u : roots)
      add(true, v, u);
  }
  for (int u = 0; u < W; u += step) {
    roots.clear();
    solveQuadratic(k.c, 2.0 * (k.b * u + k.e), k.a * u * u + 2.0 * k.d * u + k.f, roots);
    for (double v : roots)
      add(false, u, v);
  }
  std::sort(samples.begin(), samples.end(),
            [](const GuidedSample &p, const GuidedSample &q) { return p.angle < q.angle; });
  return true;
}
} // namespace vsp::laser_detector
