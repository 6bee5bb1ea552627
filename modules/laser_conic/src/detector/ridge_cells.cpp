/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The coarse cells of the ridge detector's coarse-to-fine search.
#include "ridge_cells.h"

#include "ridge_tuning.h"

namespace vsp::laser_detector
{
int coarseFactor(const RidgeSettings &settings)
{
  return toIntAtMost(settings.minSegment / (RidgeTuning::coarseLinesPerChain * settings.step),
                     RidgeTuning::maxCoarseFactor);
}

void markCellsAroundKept(RidgeWorkspace &work, int W, int H, int reach)
{
  const CellGrid grid(W, H);
  const int cellsAround = (reach + 15) >> 4,
            bandsAround = (reach + RegionSpans::bandHeight - 1) >> RegionSpans::bandShift;
  std::vector<unsigned char> &cells = work.cells;
  cells.assign(static_cast<size_t>(grid.columns) * grid.rows, 0);
  for (size_t k = 0; k < work.crossings.size(); ++k) {
    if (!work.keep[k])
      continue;
    const int ci = grid.rowOf(work.crossings[k].point), cj = grid.columnOf(work.crossings[k].point);
    for (int a = std::max(0, ci - bandsAround); a <= std::min(grid.rows - 1, ci + bandsAround); ++a)
      for (int b = std::max(0, cj - cellsAround); b <= std::min(grid.columns - 1, cj + cellsAround); ++b)
        cells[grid.index(a, b)] = 1;
  }
}

bool inMarkedCell(const RidgeWorkspace &work, int W, int H, size_t k)
{
  const CellGrid grid(W, H);
  const vpImagePoint &p = work.crossings[k].point;
  return work.cells[grid.index(grid.rowOf(p), grid.columnOf(p))] != 0;
}

void markedCellsToSpans(const RidgeWorkspace &work, int W, int H, RegionSpans &region)
{
  const CellGrid grid(W, H);
  region.spans.clear();
  region.bandStart.assign(1, 0);
  for (int a = 0; a < grid.rows; ++a) {
    const unsigned char *row = work.cells.data() + grid.index(a, 0);
    for (int b = 0; b < grid.columns; ++b) {
      const int first = b;
      while (b < grid.columns && row[b])
        ++b;
      if (b > first)
        region.spans.push_back(Span(16 * first, std::min(W - 1, 16 * b - 1)));
    }
    region.bandStart.push_back(static_cast<int>(region.spans.size()));
  }
}
} // namespace vsp::laser_detector
