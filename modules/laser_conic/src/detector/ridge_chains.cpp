/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The continuity filter of the ridge detector: union-find over the pairs of crossings within the link
// radius, found by a window sliding over the crossings sorted by bands of rows and by column.
#include "ridge_chains.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace vsp::laser_detector
{
namespace
{
// Union-find root with path halving.
int root(std::vector<int> &parent, int k)
{
  while (parent[k] != k) {
    parent[k] = parent[parent[k]];
    k = parent[k];
  }
  return k;
}

// The crossings sorted by bands of 2^shift rows, each band by column (two counting sorts, by column then by
// band: no comparison whose outcome the processor must guess) into work.order, with their coordinates and
// columns in that order (work.sortedU, sortedV, sortedColumn) and the first of each band (work.bandStart).
void sortByBandAndColumn(RidgeWorkspace &work, int W, int H, int shift)
{
  const std::vector<Crossing> &crossings = work.crossings;
  const int n = static_cast<int>(crossings.size()), bands = (H >> shift) + 1;
  std::vector<int> &bandStart = work.bandStart, &order = work.order, &cursor = work.cursor;
  std::vector<int> &bandOf = work.bandOf, &columnOf = work.columnOf, &byColumn = work.byColumn;
  bandOf.resize(n);
  columnOf.resize(n);
  bandStart.assign(static_cast<size_t>(bands) + 1, 0);
  cursor.assign(static_cast<size_t>(W) + 1, 0); // first the column counts
  for (int k = 0; k < n; ++k) {
    const vpImagePoint &p = crossings[k].point;
    bandOf[k] = std::min(H - 1, std::max(0, static_cast<int>(p.get_v()))) >> shift;
    columnOf[k] = std::min(W - 1, std::max(0, static_cast<int>(p.get_u())));
    ++bandStart[static_cast<size_t>(bandOf[k]) + 1];
    ++cursor[static_cast<size_t>(columnOf[k]) + 1];
  }
  std::partial_sum(bandStart.begin(), bandStart.end(), bandStart.begin());
  std::partial_sum(cursor.begin(), cursor.end(), cursor.begin());
  byColumn.resize(n);
  for (int k = 0; k < n; ++k)
    byColumn[cursor[columnOf[k]]++] = k;
  cursor.assign(bandStart.begin(), bandStart.end() - 1); // the next free place of each band
  order.resize(n);
  for (int k : byColumn)
    order[cursor[bandOf[k]]++] = k;
  work.sortedU.resize(n);
  work.sortedV.resize(n);
  work.sortedColumn.resize(n);
  for (int pos = 0; pos < n; ++pos) {
    work.sortedU[pos] = crossings[order[pos]].point.get_u();
    work.sortedV[pos] = crossings[order[pos]].point.get_v();
    work.sortedColumn[pos] = columnOf[order[pos]];
  }
}

// Joins in work.parent (union-find over the sorted crossings) the pairs within \e link pixels: the
// neighbours of a crossing lie after it in its band or in the next band (bands at least `link` high),
// within ceil(link) columns, each pair seen once, found by a window sliding along the columns.
void joinNeighbours(RidgeWorkspace &work, double link)
{
  const std::vector<double> &u = work.sortedU, &v = work.sortedV;
  const std::vector<int> &column = work.sortedColumn, &bandStart = work.bandStart;
  std::vector<int> &parent = work.parent;
  const int n = static_cast<int>(u.size()), bands = static_cast<int>(bandStart.size()) - 1;
  parent.resize(n);
  std::iota(parent.begin(), parent.end(), 0);
  const double link2 = link * link;
  const int reach = static_cast<int>(std::ceil(link)); // |du| <= link: the columns differ by ceil(link) at most
  auto join = [&](int a, int b) {
    const double du = u[a] - u[b], dv = v[a] - v[b];
    if (du * du + dv * dv <= link2) {
      const int ra = root(parent, a), rb = root(parent, b);
      if (ra != rb)
        parent[ra] = rb;
    }
  };
  for (int band = 0; band < bands; ++band) {
    const int end = bandStart[band + 1], nextEnd = band + 1 < bands ? bandStart[band + 2] : end;
    int next = end; // first crossing of the next band not left of the window
    for (int a = bandStart[band]; a < end; ++a) {
      for (int b = a + 1; b < end && column[b] <= column[a] + reach; ++b)
        join(a, b);
      while (next < nextEnd && column[next] < column[a] - reach)
        ++next;
      for (int b = next; b < nextEnd && column[b] <= column[a] + reach; ++b)
        join(a, b);
    }
  }
}

// work.keep from the extent (bounding-box diagonal) of each chain of work.parent.
void keepByExtent(RidgeWorkspace &work, double minLength)
{
  const std::vector<double> &u = work.sortedU, &v = work.sortedV;
  std::vector<int> &parent = work.parent;
  const int n = static_cast<int>(u.size());
  work.minU.assign(n, 1e30);
  work.maxU.assign(n, -1e30);
  work.minV.assign(n, 1e30);
  work.maxV.assign(n, -1e30);
  for (int k = 0; k < n; ++k) {
    parent[k] = root(parent, k);
    const int r = parent[k];
    work.minU[r] = std::min(work.minU[r], u[k]);
    work.maxU[r] = std::max(work.maxU[r], u[k]);
    work.minV[r] = std::min(work.minV[r], v[k]);
    work.maxV[r] = std::max(work.maxV[r], v[k]);
  }
  const double min2 = minLength * minLength;
  for (int k = 0; k < n; ++k) {
    const int r = parent[k];
    const double du = work.maxU[r] - work.minU[r], dv = work.maxV[r] - work.minV[r];
    work.keep[work.order[k]] = du * du + dv * dv >= min2;
  }
}
} // namespace

void longChains(RidgeWorkspace &work, int W, int H, double link, double minLength)
{
  const int n = static_cast<int>(work.crossings.size());
  work.keep.assign(n, 1);
  if (minLength <= 0.0 || n == 0) {
    work.order.clear(); // no chains (keptChains())
    return;
  }
  // The buffers have the size of the crossings and of the image's width and height: nothing to reset
  // between frames, and little memory to bring to cache (a grid of cells over the image is touched at
  // random). Bands of 2^shift >= max(4, link) rows: the band of a crossing is the integer part of v shifted.
  int shift = 2;
  while ((1 << shift) < link)
    ++shift;
  sortByBandAndColumn(work, W, H, shift);
  joinNeighbours(work, link);
  keepByExtent(work, minLength);
}

std::vector<vpImagePoint> keptPoints(const RidgeWorkspace &work)
{
  std::vector<vpImagePoint> points;
  points.reserve(static_cast<size_t>(std::count(work.keep.begin(), work.keep.end(), 1)));
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k)
    if (work.keep[k])
      points.push_back(work.crossings[k].point);
  return points;
}

std::vector<int> keptChains(const RidgeWorkspace &work)
{
  const size_t n = work.crossings.size();
  if (work.order.size() != n || work.parent.size() != n || work.keep.size() != n)
    return std::vector<int>();
  std::vector<int> chainOf(n);
  for (size_t pos = 0; pos < n; ++pos)
    chainOf[static_cast<size_t>(work.order[pos])] = work.parent[pos];
  std::vector<int> kept;
  for (size_t k = 0; k < n; ++k)
    if (work.keep[k])
      kept.push_back(chainOf[k]);
  return kept;
}
} // namespace vsp::laser_detector
