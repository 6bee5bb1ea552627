/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The conic of the guided pass: a robust ellipse through the first pass's points, and its crossings with
// the image rows and columns, the lines along which its profiles are measured.
#include "guided_detail.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include <visp3/robust/vpRansac.h>

#include "../laser_estimators.h"
#include "chain_estimator.h"
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
  // Minor over major axis of the ellipse: the square root of the ratio of the eigenvalues of its quadratic part
  // (0 when they differ in sign: not an ellipse).
  double axisRatio() const
  {
    const double mean = 0.5 * (a + c), half = std::hypot(0.5 * (a - c), b);
    const double small = mean - half, large = mean + half;
    return small * large > 0.0
               ? std::sqrt(std::min(std::fabs(small), std::fabs(large)) / std::max(std::fabs(small), std::fabs(large)))
               : 0.0;
  }
  // The multiples of \e step in [0, n) between which the ellipse's lines lie: rows (v) when !alongU, else
  // columns (u), one step beyond each end (rounding); [0, n) when the extent cannot be computed. A row v
  // crosses the ellipse where (b v + d)^2 - a (c v^2 + 2 e v + f) >= 0, a quadratic in v with a negative
  // leading term (b^2 - a c < 0); for columns a and c, d and e swap roles.
  void extent(bool alongU, int step, int n, int &first, int &last) const
  {
    const double p = alongU ? c : a, q = alongU ? e : d, r = alongU ? d : e, t = alongU ? a : c;
    std::vector<double> ends;
    solveQuadratic(b * b - p * t, 2.0 * (b * q - p * r), q * q - p * f, ends);
    if (ends.size() != 2 || !std::isfinite(ends[0]) || !std::isfinite(ends[1]))
      return;
    const double lo = std::min(ends[0], ends[1]) - step, hi = std::max(ends[0], ends[1]) + step;
    first = std::max(0, static_cast<int>(std::ceil(std::max(lo, 0.0) / step)) * step);
    last = std::min(n - 1, static_cast<int>(std::min(hi, static_cast<double>(n - 1))));
  }
};

// Least-squares conic through the listed points, kept only if it is an ellipse (vpLaserSolvers::isEllipse()).
bool fitImageEllipse(const vsp::laser_estimators::PointList &points, const std::vector<int> &indices,
                     Eigen::Matrix3d &c)
{
  vsp::laser_estimators::PointList subset;
  subset.reserve(indices.size());
  for (int i : indices)
    subset.push_back(points[static_cast<size_t>(i)]);
  return vpLaserSolvers::fitConic(subset.data(), static_cast<int>(subset.size()), c) && vpLaserSolvers::isEllipse(c);
}

// Arc (radians) around (uc, vc) covered by the points: 36 sectors of 10 degrees, the occupied ones.
double sectorCoverage(const vsp::laser_estimators::PointList &points, double uc, double vc)
{
  const double pi = 3.14159265358979323846;
  bool occupied[36] = {false};
  for (const Eigen::Vector2d &p : points) {
    const double t = std::atan2(p.y() - vc, p.x() - uc) + pi;
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

// Straight-line fits offset = a + b x over windows of a sequence of (x, offset) pairs, x increasing: prefix
// sums, so that each window costs the same whatever its length.
class WindowFits
{
public:
  // The sums over the pairs k with use[k].
  void build(const std::vector<double> &x, const std::vector<double> &offset, const std::vector<unsigned char> &use)
  {
    const size_t m = x.size();
    // Every sum is written below but the first five, zero: the buffer is not cleared first (clearing a few
    // tens of kilobytes twice was 1.7 % of a tracked frame's instructions).
    if (m_size < 5 * (m + 1)) {
      m_size = 5 * (m + 1);
      m_sums.reset(new double[m_size]);
    }
    std::fill(m_sums.get(), m_sums.get() + 5, 0.0);
    for (size_t k = 0; k < m; ++k) {
      const double w = use[k] ? 1.0 : 0.0,
                   terms[5] = {w, w * x[k], w * x[k] * x[k], w * offset[k], w * x[k] * offset[k]};
      for (int j = 0; j < 5; ++j)
        m_sums[5 * (k + 1) + j] = m_sums[5 * k + j] + terms[j];
    }
  }
  // The fit over pairs [first, last] at x0, or their mean when not \e straight; false with fewer than
  // RidgeTuning::guidedSmoothMinPoints pairs.
  bool at(size_t first, size_t last, double x0, bool straight, double &value) const
  {
    double S[5];
    for (int j = 0; j < 5; ++j)
      S[j] = m_sums[5 * (last + 1) + j] - m_sums[5 * first + j];
    if (S[0] < RidgeTuning::guidedSmoothMinPoints)
      return false;
    if (!straight) {
      value = S[3] / S[0];
      return true;
    }
    // Centred on x0: sums of (x - x0), (x - x0)^2, (x - x0) offset.
    const double c1 = S[1] - S[0] * x0, c2 = S[2] - 2.0 * x0 * S[1] + x0 * x0 * S[0], e1 = S[4] - x0 * S[3];
    const double det = S[0] * c2 - c1 * c1;
    value = det > 1e-9 * S[0] * c2 ? (c2 * S[3] - c1 * e1) / det : S[3] / S[0];
    return true;
  }

private:
  std::unique_ptr<double[]> m_sums; //!< the prefix sums, five per pair and five zeros first
  size_t m_size = 0;                //!< doubles m_sums holds
};

// \e order: the indices of \e points by increasing angle, ties by index. A whole frame's second pass gives its
// points as a few long ascending runs (its walks around the ring); an introsort of the indices through the
// points' angles met them as a bad case of its pivots and fell back to heapsort, a scattered read per
// comparison (3 % of a colourful floor's detection). Merging the (angle, index) pairs, contiguous, costs the
// same whatever the runs.
void sortByAngle(const std::vector<OnConic> &points, std::vector<int> &order)
{
  std::vector<std::pair<double, int> > keyed(points.size());
  for (size_t k = 0; k < keyed.size(); ++k)
    keyed[k] = std::make_pair(points[k].angle, static_cast<int>(k));
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const std::pair<double, int> &a, const std::pair<double, int> &b) { return a.first < b.first; });
  for (size_t k = 0; k < keyed.size(); ++k)
    order[k] = keyed[k].second;
}

// The points in their order along the curve, as positions of a sequence (with, on a closed ring, the points
// within RidgeTuning::guidedSmoothRadius of the seam repeated beyond it): \e sequence the point of each
// position, \e arc its arc length (the chords between consecutive points, so a gap is long), \e first the
// position of the first point.
void arcSequence(const std::vector<OnConic> &points, std::vector<int> &sequence, std::vector<double> &arc,
                 size_t &first)
{
  std::vector<int> order(points.size());
  for (size_t k = 0; k < order.size(); ++k)
    order[k] = static_cast<int>(k);
  // The points often come in that order already (one walk along the curve), or as a rotation of it (a walk
  // that started elsewhere on the ring, as in tracking): sorted only when neither. (A sort of a rotated
  // sequence, a bad case of its pivots, was half the regularisation's time per tracked frame.)
  const auto byAngle = [&](int p, int q) { return points[p].angle < points[q].angle; };
  const auto descent = std::is_sorted_until(order.begin(), order.end(), byAngle);
  if (descent != order.end()) {
    if (std::is_sorted(descent, order.end(), byAngle) && !byAngle(order.front(), order.back()))
      std::rotate(order.begin(), descent, order.end());
    else
      sortByAngle(points, order);
  }
  const size_t n = order.size();
  std::vector<double> along(n, 0.0);
  auto chord = [&](int p, int q) {
    return std::sqrt(std::pow(points[p].u - points[q].u, 2) + std::pow(points[p].v - points[q].v, 2));
  };
  for (size_t k = 1; k < n; ++k)
    along[k] = along[k - 1] + chord(order[k - 1], order[k]);
  const double R = RidgeTuning::guidedSmoothRadius, length = along[n - 1] + chord(order[n - 1], order[0]);
  const bool closed = chord(order[n - 1], order[0]) <= R && length > 4.0 * R;
  sequence.clear();
  arc.clear();
  const size_t positions = closed ? 2 * n : n; // at most: the points, on a closed ring those repeated at its seam
  sequence.reserve(positions);
  arc.reserve(positions);
  for (size_t k = 0; closed && k < n; ++k)
    if (along[k] - length >= -R) {
      sequence.push_back(order[k]);
      arc.push_back(along[k] - length);
    }
  first = sequence.size();
  for (size_t k = 0; k < n; ++k) {
    sequence.push_back(order[k]);
    arc.push_back(along[k]);
  }
  for (size_t k = 0; closed && k < n && along[k] + length <= along[n - 1] + R; ++k) {
    sequence.push_back(order[k]);
    arc.push_back(along[k] + length);
  }
}

// The straight-line fit of the offsets within RidgeTuning::guidedSmoothRadius of arc length, at each point
// of the sequence from position \e first on (NaN where too few points); their mean at a point with less than
// RidgeTuning::guidedSmoothEnd of arc on one side (see there).
void fitWindows(const WindowFits &fits, const std::vector<double> &arc, size_t first, size_t count,
                std::vector<double> &values)
{
  values.assign(count, std::numeric_limits<double>::quiet_NaN());
  size_t lo = 0, hi = 0;
  for (size_t i = first; i < first + count; ++i) {
    while (arc[i] - arc[lo] > RidgeTuning::guidedSmoothRadius)
      ++lo;
    while (hi + 1 < arc.size() && arc[hi + 1] - arc[i] <= RidgeTuning::guidedSmoothRadius)
      ++hi;
    const bool inside = arc[i] - arc[lo] >= RidgeTuning::guidedSmoothEnd &&
                        arc[hi] - arc[i] >= RidgeTuning::guidedSmoothEnd;
    double value = 0.0;
    if (fits.at(lo, hi, arc[i], inside, value))
      values[i - first] = value;
  }
}
} // namespace

namespace
{
// The stride of positionSubsample() for about \e target of \e count points.
unsigned int subsampleStride(size_t count, size_t target)
{
  return static_cast<unsigned int>(std::max<size_t>(1, count / target));
}

// Whether positionSubsample() picks \e p at \e stride: a hash of its pixel.
bool pickedByPosition(const vpImagePoint &p, unsigned int stride)
{
  const unsigned int iu = static_cast<unsigned int>(std::max(0.0, p.get_u())),
                     iv = static_cast<unsigned int>(std::max(0.0, p.get_v()));
  // Every point when the stride is 1 (a tracked frame's 700), without the modulo's division.
  return stride == 1 || ((iu * 73856093u) ^ (iv * 19349663u)) % stride == 0;
}
} // namespace

void positionSubsample(const std::vector<vpImagePoint> &points, size_t target, bool byPosition,
                       std::vector<Eigen::Vector2d> &sample)
{
  sample.clear();
  if (byPosition) {
    for (int k : positionSubsampleIndices(points, target))
      sample.push_back(Eigen::Vector2d(points[static_cast<size_t>(k)].get_u(), points[static_cast<size_t>(k)].get_v()));
    return;
  }
  const unsigned int stride = subsampleStride(points.size(), target);
  for (const vpImagePoint &p : points)
    if (pickedByPosition(p, stride))
      sample.push_back(Eigen::Vector2d(p.get_u(), p.get_v()));
}

std::vector<int> positionSubsampleIndices(const std::vector<vpImagePoint> &points, size_t target)
{
  // By row then column, then by index: points at the same place keep their order. Sorted as keys side by side
  // (a comparison that read both points through their indices was a scattered read each).
  struct Key
  {
    double v, u;
    int index;
    bool operator<(const Key &o) const { return std::tie(v, u, index) < std::tie(o.v, o.u, o.index); }
  };
  std::vector<Key> keys;
  const unsigned int stride = subsampleStride(points.size(), target);
  for (size_t k = 0; k < points.size(); ++k)
    if (pickedByPosition(points[k], stride))
      keys.push_back(Key{points[k].get_v(), points[k].get_u(), static_cast<int>(k)});
  std::sort(keys.begin(), keys.end());
  std::vector<int> picked(keys.size());
  for (size_t k = 0; k < keys.size(); ++k)
    picked[k] = keys[k].index;
  return picked;
}

size_t pointsOnTraceEllipse(const Eigen::Matrix3d &C, const std::vector<vpImagePoint> &points)
{
  size_t on = 0;
  for (const vpImagePoint &p : points)
    on += vpLaserSolvers::sampsonDistance(C, Eigen::Vector2d(p.get_u(), p.get_v())) <= RidgeTuning::traceInlierDistance
              ? 1
              : 0;
  return on;
}

namespace
{
// The ellipse that locates the trace among \e points (\e all: the same as vectors), before the refit on all of
// them: fitted to a subsample (a few hundred points locate the trace as well as all of them), chosen by
// position and sorted (the same points in any order give the same ellipse: the first pass's order depends on
// how it searched). Most frames hold the trace alone: the least-squares ellipse of the subsample then fits
// nearly all of it, and RANSAC (a singular value decomposition per sample) is needed only when it does not;
// its samples are drawn chain by chain when \e chainOf gives the chain of each point (ChainPp5Estimator).
bool locateEllipse(const std::vector<vpImagePoint> &points, const vsp::laser_estimators::PointList &all,
                   int ransacTrials, const std::vector<int> *chainOf, Eigen::Matrix3d &C)
{
  const std::vector<int> picked = positionSubsampleIndices(points, 300);
  vsp::laser_estimators::PointList sample;
  std::vector<int> chains, everyone(picked.size());
  for (size_t k = 0; k < picked.size(); ++k) {
    sample.push_back(all[static_cast<size_t>(picked[k])]);
    if (chainOf != nullptr)
      chains.push_back((*chainOf)[static_cast<size_t>(picked[k])]);
    everyone[k] = static_cast<int>(k);
  }
  const double threshold = RidgeTuning::traceInlierDistance;
  if (fitImageEllipse(sample, everyone, C)) {
    size_t close = 0;
    for (const Eigen::Vector2d &p : sample)
      close += vpLaserSolvers::sampsonDistance(C, p) <= threshold ? 1 : 0;
    if (close >= sample.size() * 9 / 10)
      return true;
  }
  vpRansacOptions options;
  options.threshold = threshold;
  options.seed = 1;
  // No local optimisation, and as few samples as the caller can afford: five-point conics cost a singular
  // value decomposition each; a frame whose points make no ellipse (no trace, or a hyperbola's arc) must
  // not cost more.
  options.maxTrials = ransacTrials;
  options.localOptimisation = false;
  vpRansacReport ransac;
  if (chainOf != nullptr)
    return vpRansacLoop(ChainPp5Estimator(sample, chains), options, C, ransac);
  return vpRansacLoop(vsp::laser_estimators::Pp5Estimator(sample), options, C, ransac);
}
} // namespace

bool fitTraceEllipse(const std::vector<vpImagePoint> &points, int W, int H, int minInliers, int ransacTrials,
                     Eigen::Matrix3d &C, std::vector<int> &inliers, const std::vector<int> *chainOf)
{
  inliers.clear();
  if (static_cast<int>(points.size()) < std::max(5, minInliers))
    return false;
  vsp::laser_estimators::PointList all;
  all.reserve(points.size());
  for (const vpImagePoint &p : points)
    all.push_back(Eigen::Vector2d(p.get_u(), p.get_v()));
  if (!locateEllipse(points, all, ransacTrials,
                     chainOf != nullptr && chainOf->size() == points.size() ? chainOf : nullptr, C))
    return false;
  const double threshold = RidgeTuning::traceInlierDistance;
  for (int round = 0; round < 2; ++round) { // inliers of all points, refit, once more
    inliers.clear();
    for (int k = 0; k < static_cast<int>(all.size()); ++k)
      if (vpLaserSolvers::sampsonDistance(C, all[k]) <= threshold)
        inliers.push_back(k);
    if (static_cast<int>(inliers.size()) < minInliers || !fitImageEllipse(all, inliers, C))
      return false;
  }
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  const double pi = 3.14159265358979323846, diagonal = std::hypot(W, H);
  if (!k.centre(uc, vc) || std::hypot(uc - 0.5 * W, vc - 0.5 * H) > 4.0 * diagonal)
    return false; // a huge ellipse: a few straight pieces, not a ring
  if (k.axisRatio() < RidgeTuning::traceMinAxisRatio)
    return false; // a short, nearly straight arc: the ellipse hugs it on both of its long sides
  // The arc of about 300 of the inliers, evenly spread along their list (an arc tangent each: all of them cost
  // as much as the rest of the fit).
  vsp::laser_estimators::PointList arc;
  const size_t stride = std::max<size_t>(1, inliers.size() / 300);
  for (size_t j = 0; j < inliers.size(); j += stride)
    arc.push_back(all[static_cast<size_t>(inliers[j])]);
  return sectorCoverage(arc, uc, vc) >= pi / 3.0;
}

std::vector<int> smoothAlongCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings)
{
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  if (crossings.size() < static_cast<size_t>(RidgeTuning::guidedSmoothMinPoints) || !k.centre(uc, vc))
    return std::vector<int>();
  std::vector<OnConic> points;
  points.reserve(crossings.size());
  for (const Crossing &x : crossings) {
    const double u = x.point.get_u(), v = x.point.get_v();
    const double fu = k.a * u + k.b * v + k.d, fv = k.b * u + k.c * v + k.e, norm = std::sqrt(fu * fu + fv * fv);
    const double F = k.a * u * u + 2.0 * k.b * u * v + k.c * v * v + 2.0 * k.d * u + 2.0 * k.e * v + k.f;
    if (!(norm > 0.0))
      return std::vector<int>();
    points.push_back(OnConic{u, v, fu / norm, fv / norm, F / (2.0 * norm), curveOrder(u - uc, v - vc)});
  }
  std::vector<int> sequence;
  std::vector<double> arc, offset, fitted;
  size_t first = 0;
  arcSequence(points, sequence, arc, first);
  offset.reserve(sequence.size());
  for (int p : sequence)
    offset.push_back(points[static_cast<size_t>(p)].offset);
  // A fit on every point, then again without those farther than RidgeTuning::guidedSmoothOutlier from it.
  std::vector<unsigned char> use(sequence.size(), 1);
  WindowFits fits;
  fits.build(arc, offset, use);
  fitWindows(fits, arc, 0, sequence.size(), fitted);
  size_t dropped = 0;
  for (size_t i = 0; i < sequence.size(); ++i) {
    use[i] = std::fabs(offset[i] - fitted[i]) <= RidgeTuning::guidedSmoothOutlier ? 1 : 0; // NaN: left out
    dropped += 1 - use[i];
  }
  if (dropped > 0) { // else the same fits again
    fits.build(arc, offset, use);
    fitWindows(fits, arc, first, points.size(), fitted);
  } else
    fitted.erase(fitted.begin(), fitted.begin() + static_cast<std::ptrdiff_t>(first));
  for (size_t i = 0; i < points.size(); ++i) {
    const OnConic &c = points[static_cast<size_t>(sequence[first + i])];
    const double shift = std::isfinite(fitted[i]) ? fitted[i] - c.offset : 0.0;
    crossings[static_cast<size_t>(sequence[first + i])].point = vpImagePoint(c.v + shift * c.nv, c.u + shift * c.nu);
  }
  return std::vector<int>(sequence.begin() + static_cast<std::ptrdiff_t>(first),
                          sequence.begin() + static_cast<std::ptrdiff_t>(first + points.size()));
}

namespace
{
bool byAngle(const GuidedSample &p, const GuidedSample &q) { return p.angle < q.angle; }

// The roots of the lines t = first, first + step, ... <= last of a family, p x^2 + 2 (b t + q1) x + r t^2 +
// 2 q2 t + f = 0 (quadraticRoots()): the smaller in low[i], the larger in high[i], count[i] of them. All
// lines are solved before their crossings are looked at: one line's square root and divisions, a long chain,
// waited behind the previous line's crossings when each line was solved and crossed in turn (the sampling
// took half as long again: 18 against 12 us for a ring of 630 samples).
struct LineRoots
{
  std::vector<double> low, high;
  std::vector<int> count;
  void solve(double p, double q1, double r, double q2, double b, double f, int first, int last, int step)
  {
    const size_t lines = last < first ? 0 : static_cast<size_t>((last - first) / step + 1);
    low.resize(lines);
    high.resize(lines);
    count.resize(lines);
    for (size_t i = 0; i < lines; ++i) {
      const double t = first + static_cast<int>(i) * step;
      double x[2];
      count[i] = quadraticRoots(p, 2.0 * (b * t + q1), r * t * t + 2.0 * q2 * t + f, x);
      const bool swapped = count[i] == 2 && x[1] < x[0];
      low[i] = swapped ? x[1] : x[0];
      high[i] = swapped ? x[0] : x[1];
    }
  }
};

// The crossings of a family of lines (rows when AlongRow, roots in u; else columns, roots in v) kept as
// samples, appended to arcs[0] (smaller roots) and arcs[1] (larger), each in the order of its lines: those
// within the margin of the image, where the gradient is more along the line than across it (the line
// crosses the curve at 45 degrees or more).
template <bool AlongRow>
void appendCrossings(const ConicCoefficients &k, const LineRoots &roots, int first, int step, int n, double margin,
                     double uc, double vc, std::vector<GuidedSample> arcs[2])
{
  for (int root = 0; root < 2; ++root) {
    arcs[root].reserve(arcs[root].size() + roots.count.size()); // one crossing a line at most
    for (size_t i = 0; i < roots.count.size(); ++i) {
      const int t = first + static_cast<int>(i) * step;
      const double x = root == 0 ? roots.low[i] : roots.high[i];
      const double u = AlongRow ? x : t, v = AlongRow ? t : x;
      const double fu = k.a * u + k.b * v + k.d, fv = k.b * u + k.c * v + k.e;
      const double along = std::fabs(AlongRow ? fu : fv), across = std::fabs(AlongRow ? fv : fu);
      // About half the crossings are the other family's: the sample's divisions and square root only for a kept one.
      if (!(roots.count[i] > root && x >= -margin && x <= n - 1 + margin && along > 0.0 && along >= across &&
            (AlongRow || along != across)))
        continue;
      const double norm = std::sqrt(fu * fu + fv * fv);
      const double toNormal = along / norm;
      const double slope = -(AlongRow ? fv : fu) / (AlongRow ? fu : fv);
      const signed char side = (AlongRow ? fu : fv) > 0.0 ? 1 : -1;
      arcs[root].push_back(
          GuidedSample{AlongRow, side, t, x, margin / toNormal, toNormal, curveOrder(u - uc, v - vc), slope});
    }
  }
}

// Puts the samples of \e run, one arc of the curve in the order of its lines, in increasing angle: reversed
// when the angle decreases along it, rotated when it crosses the -pi / pi cut. False when the run is no such
// arc (then the caller sorts).
bool alongTheCurve(std::vector<GuidedSample> &run)
{
  size_t descents = 0;
  for (size_t i = 1; i < run.size(); ++i)
    descents += run[i].angle < run[i - 1].angle ? 1 : 0;
  if (2 * descents > run.size())
    std::reverse(run.begin(), run.end());
  const auto cut = std::is_sorted_until(run.begin(), run.end(), byAngle);
  if (cut == run.end())
    return true;
  std::rotate(run.begin(), cut, run.end());
  return std::is_sorted(run.begin(), run.end(), byAngle);
}
} // namespace

bool sampleConic(const Eigen::Matrix3d &C, int W, int H, double margin, int step, std::vector<GuidedSample> &samples)
{
  samples.clear();
  if (!vpLaserSolvers::isEllipse(C))
    return false;
  const ConicCoefficients k(C);
  double uc = 0.0, vc = 0.0;
  if (!k.centre(uc, vc))
    return false;
  // The crossings come as four arcs, each in the order of its lines (rows or columns, first or second root),
  // then merged along the curve: sorting them all was a twentieth of a tracked frame.
  std::vector<GuidedSample> arcs[4];
  // Only the lines that cross the ellipse: its extent along v (rows) and u (columns).
  int firstRow = 0, lastRow = H - 1, firstColumn = 0, lastColumn = W - 1;
  k.extent(false, step, H, firstRow, lastRow);
  k.extent(true, step, W, firstColumn, lastColumn);
  LineRoots roots;
  roots.solve(k.a, k.d, k.c, k.e, k.b, k.f, firstRow, lastRow, step); // row v: roots in u
  appendCrossings<true>(k, roots, firstRow, step, W, margin, uc, vc, arcs);
  roots.solve(k.c, k.e, k.a, k.d, k.b, k.f, firstColumn, lastColumn, step); // column u: roots in v
  appendCrossings<false>(k, roots, firstColumn, step, H, margin, uc, vc, arcs + 2);
  bool arcsInOrder = true;
  for (std::vector<GuidedSample> &arc : arcs)
    arcsInOrder = alongTheCurve(arc) && arcsInOrder;
  std::vector<GuidedSample> rows, columns;
  rows.reserve(arcs[0].size() + arcs[1].size());
  columns.reserve(arcs[2].size() + arcs[3].size());
  std::merge(arcs[0].begin(), arcs[0].end(), arcs[1].begin(), arcs[1].end(), std::back_inserter(rows), byAngle);
  std::merge(arcs[2].begin(), arcs[2].end(), arcs[3].begin(), arcs[3].end(), std::back_inserter(columns), byAngle);
  samples.reserve(rows.size() + columns.size());
  std::merge(rows.begin(), rows.end(), columns.begin(), columns.end(), std::back_inserter(samples), byAngle);
  if (!arcsInOrder)
    std::sort(samples.begin(), samples.end(), byAngle);
  return true;
}
} // namespace vsp::laser_detector
