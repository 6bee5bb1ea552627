/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_scan.h
  \brief The scan driver of the ridge detector (internal header): one pass over the rows that scores
  them, searches the rows and the columns for candidates and measures them while they are in cache.
*/
#ifndef VP_LASER_RIDGE_SCAN_H
#define VP_LASER_RIDGE_SCAN_H

#include <vector>

#include "laser_detector.h"
#include "ridge_candidates.h"

namespace vsp::laser_detector
{
/*!
  One ridge detection: the score, the candidate searches along rows and columns and their measurement,
  over the buffers of a RidgeWorkspace (see detectRidge()).
*/
class RidgeScan
{
public:
  //! Prepares the buffers of \e work for \e I; the rejected runs will go to \e runs.
  RidgeScan(const vpImage<vpRGBa> &I, const RidgeSettings &settings, int threshold, RidgeWorkspace &work,
            std::vector<StripeRun> &runs);

  /*!
    The pass over the rows, while they are in cache: row i is scored (over \e scoreRegion only when not
    null: nothing outside it is read) and, when a multiple of \e step, searched along its length; the
    columns multiple of \e step are searched at row i - d, the last row whose neighbours up to d rows away
    are scored (in the image of the coarse columns when \e coarse); the candidates of row i - d - 1, the
    last row whose profiles (up to d + 1 rows away) are scored, are measured.
  */
  void streamRows(const RegionSpans *scoreRegion, const RegionSpans *searchRegion, int step, bool coarse);

  /*!
    Searches the lines of \e region that streamRows() left out (the rows and columns multiple of \e step but
    not of \e coarseStep), row by row over the scored image, and measures each row's candidates at once.
  */
  void searchBetween(const RegionSpans &region, int step, int coarseStep);

  //! Keeps the crossings work.keep marks; the others become rejected runs (for the mask, see drawRuns()).
  void keepMarkedCrossings();

private:
  void scoreRow(int i, const RegionSpans *region);
  const unsigned char *flagsOf(int i) const;
  void searchRow(int i, const RegionSpans *region);
  void searchColumns(int i, const RegionSpans *region, const ColumnSelection &columns);

  // The coarse columns: the column tests read nothing across, so every coarseStep-th column of the score
  // makes an image of its own, coarseStep times narrower, searched whole (all its blocks flagged); its
  // candidates are mapped back to the image's columns. Its rows are padded with zeros to whole pairs of
  // blocks (no pixel-by-pixel end: a zero score is never a candidate).
  int coarseColumns(int coarseStep) const { return (m_W - 1) / coarseStep + 1; }
  int coarseStride(int coarseStep) const { return (coarseColumns(coarseStep) + 31) & ~31; }
  void startCoarseColumns(int coarseStep);
  void keepCoarseColumns(int i, int coarseStep);
  void searchCoarseColumns(int i, int coarseStep);

  // Measures the candidate c: one crossing per run, a later peak inside a measured run is skipped (the
  // candidates come line by line for the rows, row by row for the columns: one run end per column).
  void measure(const Candidate &c, bool alongRow);
  // Measures the candidates of the rows <= r not measured yet.
  void measureUpTo(int r);

  const unsigned char *m_rgba;
  const int m_H, m_W, m_flagStride, m_d, m_threshold;
  const RidgeSettings &m_settings;
  RidgeWorkspace &m_work;
  std::vector<StripeRun> &m_runs;
  int m_lastRow = -1, m_lastRowEnd = -1;
  size_t m_nextRowPeak = 0, m_nextColumnPeak = 0;
};
} // namespace vsp::laser_detector

#endif
