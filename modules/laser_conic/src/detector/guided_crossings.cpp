/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The crossings a detection kept, after the fact: the stripe's observed width (the guided pass's matched
// filter and the first pass's shape test take it), and the selections of them that an estimate keeps.
#include "guided_detail.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vsp::laser_detector
{
namespace
{
int medianWidth(std::vector<int> &widths, int fallback) { return widths.empty() ? fallback : middleValue(widths); }
} // namespace

int observedStripeWidth(const RidgeWorkspace &work, int fallback)
{
  std::vector<int> widths;
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k)
    if (work.keep[k])
      widths.push_back(work.crossings[k].last - work.crossings[k].first + 1);
  return medianWidth(widths, fallback);
}

int guidedStripeWidth(const RidgeWorkspace &work, int fallback)
{
  std::vector<int> widths;
  widths.reserve(work.guided.size());
  for (const Crossing &c : work.guided)
    widths.push_back(c.last - c.first + 1);
  return medianWidth(widths, fallback);
}

int observedStripeWidth(const RidgeWorkspace &work, const Eigen::Matrix3d &C, const std::vector<int> &inliers,
                        int fallback)
{
  // The kept crossings in order, as the points returned (the inliers index those).
  std::vector<const Crossing *> kept;
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k)
    if (work.keep[k])
      kept.push_back(&work.crossings[k]);
  std::vector<int> widths;
  for (int index : inliers) {
    if (index < 0 || static_cast<size_t>(index) >= kept.size())
      continue;
    const Crossing &c = *kept[static_cast<size_t>(index)];
    // A run along a row is the width across the stripe over |n_u|, along a column over |n_v| (n: the unit
    // normal; the gradient's direction will do).
    const Eigen::Vector3d g = C * Eigen::Vector3d(c.point.get_u(), c.point.get_v(), 1.0);
    const double nu = std::fabs(g(0)), nv = std::fabs(g(1)), steeper = std::max(nu, nv);
    if (!(steeper > 0.0))
      continue;
    const double run = c.last - c.first + 1;
    widths.push_back(static_cast<int>(std::lround(run * (c.alongRow ? nu : nv) / steeper)));
  }
  return medianWidth(widths, fallback);
}

namespace
{
// Of the kept crossings of work (in order, the points of the pass), keeps those \e selected marks.
void keepSelectedCrossings(const std::vector<unsigned char> &selected, RidgeWorkspace &work)
{
  size_t index = 0;
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k)
    if (work.keep[k])
      work.keep[k] = index < selected.size() && selected[index++];
}
} // namespace

std::vector<vpImagePoint> keepSteepRowCrossings(const std::vector<vpImagePoint> &points,
                                                const std::vector<int> &inliers, const Eigen::Matrix3d &C,
                                                RidgeWorkspace &work)
{
  std::vector<unsigned char> steep(points.size(), 0);
  std::vector<vpImagePoint> kept;
  kept.reserve(inliers.size());
  for (int k : inliers) {
    const vpImagePoint &p = points[static_cast<size_t>(k)];
    const Eigen::Vector3d g = C * Eigen::Vector3d(p.get_u(), p.get_v(), 1.0);
    if (std::fabs(g(0)) >= std::fabs(g(1))) {
      steep[static_cast<size_t>(k)] = 1;
      kept.push_back(p);
    }
  }
  keepSelectedCrossings(steep, work);
  return kept;
}

void keepInlierCrossings(size_t count, const std::vector<int> &inliers, RidgeWorkspace &work)
{
  std::vector<unsigned char> selected(count, 0);
  for (int k : inliers)
    selected[static_cast<size_t>(k)] = 1;
  keepSelectedCrossings(selected, work);
}
} // namespace vsp::laser_detector
