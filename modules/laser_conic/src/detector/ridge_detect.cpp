/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The ridge detector of vpLaserConicDetector (DETECTION_RIDGE): red-dominance score in one pass over the
// RGBA buffer, top-hat candidates along rows and columns against a threshold estimated from the image,
// profile checks and sub-pixel centre around each candidate only, then a continuity filter; over the whole
// image coarse to fine (every 8th line first, the others near the long coarse chains).
#include "laser_detector.h"

#include <algorithm>
#include <cmath>

#include "ridge_cells.h"
#include "ridge_chains.h"
#include "ridge_noise.h"
#include "ridge_scan.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
namespace
{
// Over the whole image, coarse to fine: on a textured floor nearly every block of the image has candidates,
// most of them short ridges (a patch corner between two grout lines is a thin wedge of its colour), and
// measuring them all took most of a frame's time. The pass over the rows measures the candidates of the
// coarse lines only (every coarseStep-th row and column), whose crossings are chained; the other lines are
// then searched only near the coarse crossings on chains that may reach the minimum length. A chain of that
// length crosses four coarse lines at least; its coarse crossings may fall short of its ends by up to a
// coarse step each way (hence the shorter coarse length).
void coarseToFine(RidgeScan &scan, RidgeWorkspace &work, const RidgeSettings &settings, int W, int H, int coarseStep)
{
  scan.streamRows(nullptr, nullptr, coarseStep, true);
  // The coarse chains: linked within two coarse steps, as the lines of the fine pass; then the short ones
  // near the long ones are linked within three steps: a dim stripe misses a coarse crossing here and there
  // (the dim frames of the shipped hard sequence lost pieces of trace). Only near the long chains: linked
  // within three steps everywhere, the wedges of a mosaic make networks, all to be searched.
  const double coarseMin = std::max(0.0, settings.minSegment - RidgeTuning::coarseShortfallSteps * coarseStep);
  longChains(work, W, H, linkRadius(RidgeTuning::coarseLinkSteps, coarseStep), coarseMin);
  const int bridgeReach = RidgeTuning::coarseReachSteps * coarseStep + RidgeTuning::coarseReachExtra;
  markCellsAroundKept(work, W, H, bridgeReach);
  for (size_t k = 0; k < work.crossings.size(); ++k)
    work.keep[k] = work.keep[k] || inMarkedCell(work, W, H, k);
  scan.keepMarkedCrossings();
  longChains(work, W, H, linkRadius(RidgeTuning::coarseBridgeSteps, coarseStep), coarseMin);
  // The other lines are searched around the coarse crossings kept, a few pixels beyond half the distance
  // of two linked ones (16 pixels for coarse lines every 8th).
  markCellsAroundKept(work, W, H, bridgeReach / 2 + RidgeTuning::fineReachExtra);
  markedCellsToSpans(work, W, H, work.fineRegion);
  scan.keepMarkedCrossings();
  scan.searchBetween(work.fineRegion, settings.step, coarseStep);
}
} // namespace

std::vector<vpImagePoint> detectRidge(const vpImage<vpRGBa> &I, const RidgeSettings &settings,
                                      const RegionSpans *scoreRegion, const RegionSpans *searchRegion,
                                      RidgeWorkspace &work, std::vector<StripeRun> &runs, RidgeReport &report)
{
  // 1. Threshold from the image's own noise (a sparse sample of rows).
  const int threshold = beginDetection(I, settings, scoreRegion, work, runs, report);
  if (threshold < 0)
    return std::vector<vpImagePoint>();
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());

  // 2. Score, candidates and profiles; over the whole image coarse to fine, in a search region (already
  // small) in one pass.
  const int step = settings.step, factor = searchRegion == nullptr ? coarseFactor(settings) : 1;
  RidgeScan scan(I, settings, threshold, work, runs);
  if (factor < 2)
    scan.streamRows(scoreRegion, searchRegion, step, false);
  else
    coarseToFine(scan, work, settings, W, H, factor * step);

  // 3. Continuity: drop the short chains.
  longChains(work, W, H, linkRadius(RidgeTuning::linkSteps, step), settings.minSegment);
  // The runs of the crossings stay in the workspace for the mask (see drawRuns()).
  return keptPoints(work);
}
} // namespace vsp::laser_detector
