/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The search region of vpLaserConicDetector: conic sampling and rasterisation of a band in blocks.
#include "search_region.h"

#include <algorithm>
#include <cmath>

#include "ridge_profile.h"

namespace vsp::laser_detector
{
namespace
{
// Marks the blocks of 16 columns by bands of 8 rows (the width the scans and the block flags process at once,
// the height of the bands of spans) that hold every pixel within \e margin of a point: \e marked, nbY x nbX.
void markBlocks(const std::vector<vpImagePoint> &region, double margin, int H, int W, int nbX,
                std::vector<unsigned char> &marked)
{
  const int blockW = 16, blockH = RegionSpans::bandHeight, nbY = (H + blockH - 1) / blockH;
  marked.assign(static_cast<size_t>(nbX) * nbY, 0);
  // One point per cell of a tenth of the margin marks its square: more points in the cell add little. Every
  // point lies within a cell diagonal of the point marked for its cell, so the square's half side is the
  // margin and that diagonal (with the margin alone, the band reached 0.64 of it around the other points, and
  // a stripe 37 px past a region's last point, margin 40, was not searched).
  const double cellSize = std::max(1.0, 0.1 * margin), m = margin + std::sqrt(2.0) * cellSize;
  const int cellColumns = static_cast<int>((W + 2 * m) / cellSize) + 2,
            cellRows = static_cast<int>((H + 2 * m) / cellSize) + 2;
  std::vector<unsigned char> used(static_cast<size_t>(cellColumns) * cellRows, 0);
  for (const vpImagePoint &p : region) {
    const double u = p.get_u(), v = p.get_v();
    if (u < -m || v < -m || u > W - 1 + m || v > H - 1 + m)
      continue; // the square does not meet the image
    unsigned char &cell =
        used[static_cast<size_t>((v + m) / cellSize) * cellColumns + static_cast<size_t>((u + m) / cellSize)];
    if (cell)
      continue;
    cell = 1;
    const int i0 = std::max(0, static_cast<int>(std::floor(v - m))),
              i1 = std::min(H - 1, static_cast<int>(std::ceil(v + m)));
    const int j0 = std::max(0, static_cast<int>(std::floor(u - m))),
              j1 = std::min(W - 1, static_cast<int>(std::ceil(u + m)));
    for (int bi = i0 / blockH; bi <= i1 / blockH; ++bi)
      std::fill(&marked[static_cast<size_t>(bi) * nbX + j0 / blockW],
                &marked[static_cast<size_t>(bi) * nbX + j1 / blockW] + 1, 1);
  }
}

// The marked blocks dilated by rx blocks along the rows and ry bands along the columns.
std::vector<unsigned char> dilateBlocks(const std::vector<unsigned char> &marked, int nbX, int rx, int ry)
{
  const int nbY = static_cast<int>(marked.size()) / nbX;
  std::vector<unsigned char> wide(marked.size(), 0), out(marked.size(), 0);
  for (int bi = 0; bi < nbY; ++bi)
    for (int b = 0; b < nbX; ++b)
      if (marked[static_cast<size_t>(bi) * nbX + b])
        std::fill(&wide[static_cast<size_t>(bi) * nbX + std::max(0, b - rx)],
                  &wide[static_cast<size_t>(bi) * nbX + std::min(nbX - 1, b + rx)] + 1, 1);
  for (int bi = 0; bi < nbY; ++bi)
    for (int di = -ry; di <= ry; ++di)
      if (bi + di >= 0 && bi + di < nbY)
        for (int b = 0; b < nbX; ++b)
          out[static_cast<size_t>(bi) * nbX + b] |= wide[static_cast<size_t>(bi + di) * nbX + b];
  return out;
}

// The column spans of each band of the marked blocks.
void blocksToSpans(const std::vector<unsigned char> &marked, int nbX, int W, RegionSpans &out)
{
  const int blockW = 16, nbY = static_cast<int>(marked.size()) / nbX;
  out.spans.clear();
  out.bandStart.assign(1, 0);
  for (int bi = 0; bi < nbY; ++bi) {
    const unsigned char *row = &marked[static_cast<size_t>(bi) * nbX];
    for (int b = 0; b < nbX; ++b) {
      if (!row[b])
        continue;
      const int start = b;
      while (b + 1 < nbX && row[b + 1])
        ++b;
      out.spans.push_back(Span(start * blockW, std::min(W - 1, (b + 1) * blockW - 1)));
    }
    out.bandStart.push_back(static_cast<int>(out.spans.size()));
  }
}
} // namespace

int quadraticRoots(double a, double b, double c, double roots[2])
{
  const double scale = std::max(std::fabs(a), std::max(std::fabs(b), std::fabs(c)));
  if (scale == 0.0)
    return 0;
  if (std::fabs(a) <= 1e-14 * scale) {
    if (!(std::fabs(b) > 1e-14 * scale))
      return 0;
    roots[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0)
    return 0;
  // Numerically stable form: no cancellation between b and the square root.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  roots[0] = q / a;
  if (q == 0.0)
    return 1;
  roots[1] = c / q;
  return 2;
}

void solveQuadratic(double a, double b, double c, std::vector<double> &roots)
{
  double found[2];
  roots.insert(roots.end(), found, found + quadraticRoots(a, b, c, found));
}
bool sampleConicOnLines(double a, double b, double c, double d, double e, double f, double margin,
                        std::vector<vpImagePoint> *points)
{
  std::vector<double> roots;
  const int extent = 16384;
  bool any = false;
  // The point (v, u) of a root kept when the root is in range; false once the first point is all the caller
  // asked for.
  auto keep = [&](double root, double v, double u) {
    if (!(root > -margin - 1.0 && root < extent))
      return true;
    any = true;
    if (points == nullptr)
      return false;
    points->push_back(vpImagePoint(v, u));
    return true;
  };
  for (int t = -static_cast<int>(margin) - 1; t < extent; ++t) {
    roots.clear();
    solveQuadratic(a, 2.0 * (b * t + d), c * t * t + 2.0 * e * t + f, roots); // row v = t: roots in u
    for (double u : roots)
      if (!keep(u, t, u))
        return true;
    roots.clear();
    solveQuadratic(c, 2.0 * (b * t + e), a * t * t + 2.0 * d * t + f, roots); // column u = t: roots in v
    for (double v : roots)
      if (!keep(v, v, t))
        return true;
  }
  return any;
}

void rasteriseBand(const std::vector<vpImagePoint> &region, double margin, int stripeWidth, int H, int W,
                   RegionSpans &searched, RegionSpans &scored)
{
  // The ridge tests of a searched pixel read the score up to profileReach() pixels away along its row and its
  // column. The searched blocks are thus dilated by that reach rounded up to whole blocks and bands: every
  // score read is of this frame (the score buffer is kept from frame to frame), whatever part of its block a
  // searched pixel lies in.
  const int nbX = (W + 15) / 16, reach = profileReach(stripeWidth);
  std::vector<unsigned char> marked;
  markBlocks(region, margin, H, W, nbX, marked);
  blocksToSpans(marked, nbX, W, searched);
  blocksToSpans(dilateBlocks(marked, nbX, (reach + 15) / 16,
                             (reach + RegionSpans::bandHeight - 1) / RegionSpans::bandHeight),
                nbX, W, scored);
}
} // namespace vsp::laser_detector
