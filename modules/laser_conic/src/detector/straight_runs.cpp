/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Long straight runs among the ridge points. A ring of radius R pixels stays within a band 2t wide of a line
// over a chord of 2 sqrt(4 R t) pixels at most: with t = 1.5 px, 64 px for R = 170 px (the rings of the hard
// sequence), 155 px for R = 1000 px, a ring larger than the images the detector is built for. A run of
// kMinRunLength pixels is then a red cable, a strip of tape or a straight edge of a red object's stripe-like
// rim, which outnumbers a ring's first-pass points on frames where the ring is broken into arcs (the hard
// sequence rendered with other seeds: an ellipse along a cable and two arcs of the ring held 726-792 points,
// more than the ring's own, and its guided pass covered 0.53-0.64 of it).
#include "straight_runs.h"

#include <algorithm>
#include <cmath>

#include <visp3/robust/vpRansac.h>

namespace vsp::laser_detector
{
namespace
{
// Half width (pixels) of the band around a line whose points belong to it: the first pass's centres are within
// a few tenths of a pixel of a straight stripe, and a cable imaged through a distorting lens bends by about a
// pixel over a few hundred.
const double kTolerance = 1.5;
// Shortest run (pixels along the line) taken as a straight structure rather than an arc of the ring.
const double kMinRunLength = 150.0;
// Longest gap (pixels along the line) within a run: a cable crossing the ring, or hidden for a few pixels,
// stays one run, while points of clutter that happen to line up far apart make none.
const double kMaxGap = 10.0;
// Points of a run per pixel of its length, at least (the first pass finds about one a pixel along a stripe):
// a line through scattered clutter is no run.
const double kMinDensity = 0.5;
// Runs searched for, at most: a cable curved by the lens's distortion is taken in a few straight pieces.
const int kMaxRuns = 6;
// Pairs of points tried for each line, at most (a cable of a quarter of the points is drawn with probability
// 0.9999), and the confidence at which the trials stop earlier (vpRansacLoop()'s adaptive count: a cable of
// half the points needs about 30 pairs).
const int kLineTrials = 150;
const double kLineConfidence = 0.9999;
// Points the lines are scored on (a subsample: a few hundred locate a line as well as all of them).
const size_t kScoredPoints = 400;

struct Line
{
  double nu = 0.0, nv = 0.0, c = 0.0; // nu u + nv v + c = 0, (nu, nv) a unit normal
  double distance(const vpImagePoint &p) const { return std::fabs(nu * p.get_u() + nv * p.get_v() + c); }
  double along(const vpImagePoint &p) const { return nu * p.get_v() - nv * p.get_u(); }
};

bool lineThrough(const vpImagePoint &a, const vpImagePoint &b, Line &line)
{
  const double du = b.get_u() - a.get_u(), dv = b.get_v() - a.get_v(), length = std::hypot(du, dv);
  if (!(length > 2.0 * kTolerance))
    return false;
  line.nu = -dv / length;
  line.nv = du / length;
  line.c = -(line.nu * a.get_u() + line.nv * a.get_v());
  return true;
}

// The lines through two of the scored points, for vpRansacLoop(): the residual is the distance to the line.
struct LineEstimator
{
  using Model = Line;
  static constexpr int kSampleSize = 2;
  static constexpr int kMaxModels = 1;
  const std::vector<vpImagePoint> &points;
  const std::vector<int> &scored; //!< the data: indices into points
  int size() const { return static_cast<int>(scored.size()); }
  const vpImagePoint &at(int i) const { return points[static_cast<size_t>(scored[static_cast<size_t>(i)])]; }
  int solveMinimal(const int *sample, Model *models) const
  {
    return lineThrough(at(sample[0]), at(sample[1]), models[0]) ? 1 : 0;
  }
  double residual(const Model &m, int i) const { return m.distance(at(i)); }
  bool refine(const std::vector<int> &, Model &) const { return false; } // no local optimisation
};

// The line through the most of \e scored (indices into points), or false when no pair spans one.
bool bestLine(const std::vector<vpImagePoint> &points, const std::vector<int> &scored, Line &best)
{
  vpRansacOptions options;
  options.threshold = kTolerance;
  options.probability = kLineConfidence;
  options.maxTrials = kLineTrials;
  options.seed = 1; // the same points give the same runs
  options.localOptimisation = false;
  vpRansacReport report;
  return vpRansacLoop(LineEstimator{points, scored}, options, best, report);
}

// The longest stretch of the points of \e remaining within kTolerance of \e line whose gaps are at most
// kMaxGap, marked in \e onRun when it is a run (long and dense enough); returns whether it was.
bool markRun(const std::vector<vpImagePoint> &points, const std::vector<int> &remaining, const Line &line,
             std::vector<unsigned char> &onRun)
{
  std::vector<std::pair<double, int> > near;
  for (int k : remaining)
    if (line.distance(points[static_cast<size_t>(k)]) <= kTolerance)
      near.emplace_back(line.along(points[static_cast<size_t>(k)]), k);
  std::sort(near.begin(), near.end());
  size_t bestFirst = 0, bestLast = 0, first = 0;
  for (size_t k = 1; k <= near.size(); ++k)
    if (k == near.size() || near[k].first - near[k - 1].first > kMaxGap) {
      if (near[k - 1].first - near[first].first > near[bestLast].first - near[bestFirst].first) {
        bestFirst = first;
        bestLast = k - 1;
      }
      first = k;
    }
  if (near.empty())
    return false;
  const double length = near[bestLast].first - near[bestFirst].first;
  if (length < kMinRunLength || static_cast<double>(bestLast - bestFirst + 1) < kMinDensity * length)
    return false;
  for (size_t k = bestFirst; k <= bestLast; ++k)
    onRun[static_cast<size_t>(near[k].second)] = 1;
  return true;
}
} // namespace

std::vector<int> offStraightRuns(const std::vector<vpImagePoint> &points)
{
  std::vector<unsigned char> onRun(points.size(), 0);
  std::vector<int> remaining(points.size());
  for (size_t k = 0; k < points.size(); ++k)
    remaining[k] = static_cast<int>(k);
  for (int run = 0; run < kMaxRuns && remaining.size() >= 2; ++run) {
    std::vector<int> scored;
    const size_t stride = std::max<size_t>(1, remaining.size() / kScoredPoints);
    for (size_t k = 0; k < remaining.size(); k += stride)
      scored.push_back(remaining[k]);
    Line line;
    if (!bestLine(points, scored, line) || !markRun(points, remaining, line, onRun))
      break;
    remaining.erase(std::remove_if(remaining.begin(), remaining.end(),
                                   [&onRun](int k) { return onRun[static_cast<size_t>(k)] != 0; }),
                    remaining.end());
  }
  return remaining;
}
} // namespace vsp::laser_detector
