/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_cells.h
  \brief The coarse cells of the ridge detector's coarse-to-fine search (internal header): which lines
  are coarse, and the cells of the image near the kept coarse crossings, where the other lines are searched.
*/
#ifndef VP_LASER_RIDGE_CELLS_H
#define VP_LASER_RIDGE_CELLS_H

#include <algorithm>
#include <cstddef>

#include "laser_detector.h"

namespace vsp::laser_detector
{
/*!
  Coarse to fine (see detectRidge()): the coarse lines are every coarseFactor() x step-th. The largest
  factor up to RidgeTuning::maxCoarseFactor for which a chain of the minimum length still crosses
  RidgeTuning::coarseLinesPerChain coarse lines; below 2 (short chains kept, or a sampling step already
  coarse), one pass.
*/
int coarseFactor(const RidgeSettings &settings);

//! Cells of 16 columns x RegionSpans::bandHeight rows over an image of W x H pixels.
struct CellGrid
{
  int columns, rows; //!< cells along a row, along a column
  CellGrid(int W, int H) : columns((W + 15) >> 4), rows((H + RegionSpans::bandHeight - 1) >> RegionSpans::bandShift) {}
  //! Row of the cell of p.
  int rowOf(const vpImagePoint &p) const
  {
    return std::min(rows - 1, std::max(0, static_cast<int>(p.get_v()) >> RegionSpans::bandShift));
  }
  //! Column of the cell of p.
  int columnOf(const vpImagePoint &p) const
  {
    return std::min(columns - 1, std::max(0, static_cast<int>(p.get_u()) >> 4));
  }
  //! Index of a cell in a row-major buffer.
  size_t index(int row, int column) const { return static_cast<size_t>(row) * columns + column; }
};

//! The cells (work.cells, see CellGrid) within \e reach pixels (at least, in whole cells) of a crossing that
//! work.keep marks: 1, the others 0.
void markCellsAroundKept(RidgeWorkspace &work, int W, int H, int reach);

//! Whether the crossing k lies in a marked cell (see markCellsAroundKept()).
bool inMarkedCell(const RidgeWorkspace &work, int W, int H, size_t k);

//! The marked cells (see markCellsAroundKept()) rasterised into \e region (spans on multiples of 16 columns).
void markedCellsToSpans(const RidgeWorkspace &work, int W, int H, RegionSpans &region);
} // namespace vsp::laser_detector

#endif
