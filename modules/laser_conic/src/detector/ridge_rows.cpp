/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The row sample of the ridge detector: over the whole image, the coarse rows alone are scored, searched and
// measured, an eighth of the frame read. Their crossings on long chains locate the ring for the guided pass,
// which measures the rest of it along the fitted conic (see vpLaserConicDetector::detect()).
#include "laser_detector.h"

#include <algorithm>
#include <cmath>

#include "ridge_candidates.h"
#include "ridge_cells.h"
#include "ridge_chains.h"
#include "ridge_noise.h"
#include "ridge_profile.h"
#include "ridge_score.h"
#include "ridge_simd.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
namespace
{
// Measures the candidates of a row (in column order): one crossing per run, a later peak inside a measured
// run skipped. The rows around are not scored: a stripe crossing the row is measured whatever its slope.
void measureRow(const ScanLine &line, const std::vector<Candidate> &peaks, const RidgeSettings &settings, int threshold,
                RidgeWorkspace &work, std::vector<StripeRun> &runs)
{
  int end = -1;
  for (const Candidate &c : peaks)
    if (c.pos > end)
      end = std::max(end, measureCandidate(line, c.pos, settings, threshold, false, work, runs));
}
} // namespace

int sampledRowStep(const RidgeSettings &settings) { return std::max(1, coarseFactor(settings)) * settings.step; }

std::vector<vpImagePoint> detectRidgeRows(const vpImage<vpRGBa> &I, const RidgeSettings &settings, RidgeWorkspace &work,
                                          std::vector<StripeRun> &runs, RidgeReport &report)
{
  const int threshold = beginDetection(I, settings, nullptr, work, runs, report);
  if (threshold < 0)
    return std::vector<vpImagePoint>();
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());

  const int step = sampledRowStep(settings), flagStride = (W + 15) >> 4;
  const unsigned char *rgba = reinterpret_cast<const unsigned char *>(I.bitmap);
  work.score.resize(static_cast<size_t>(W) * H);
  work.blockFlags.resize(static_cast<size_t>(flagStride) * H);
  for (int i = 0; i < H; i += step) {
    const size_t offset = static_cast<size_t>(i) * W;
    // The rows read are a coarse step apart, too far for the processor to guess the next one.
    if (i + step < H)
      prefetchBytes(rgba + 4 * (offset + static_cast<size_t>(step) * W), 4 * static_cast<size_t>(W));
    unsigned char *flags = work.blockFlags.data() + static_cast<size_t>(i) * flagStride;
    scoreSpan(rgba + 4 * offset, &work.score[offset], W, settings.saturation, threshold, flags, settings.instructions);
    work.rowPeaks.clear();
    rowCandidates(work.score.data(), flags, W, i, 0, W - 1, settings.maxWidth, threshold, settings.instructions,
                  work.rowPeaks);
    measureRow(ScanLine(work.score.data(), rgba, W, H, true, i), work.rowPeaks, settings, threshold, work, runs);
  }
  // Chains of crossings a coarse step apart, as the coarse chains of the whole search (see detectRidge()).
  const double minLength = std::max(0.0, settings.minSegment - RidgeTuning::coarseShortfallSteps * step);
  longChains(work, W, H, linkRadius(RidgeTuning::coarseLinkSteps, step), minLength);
  return keptPoints(work);
}
} // namespace vsp::laser_detector
