/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The diagnostic mask of the ridge detector, drawn from the runs of the last detection.
#include "laser_detector.h"

#include <algorithm>

namespace vsp::laser_detector
{
void drawRuns(const std::vector<StripeRun> &runs, const RidgeWorkspace &work, unsigned int H, unsigned int W,
              vpImage<unsigned char> &mask)
{
  mask.resize(H, W, 0);
  auto draw = [&mask](bool alongRow, int line, int first, int last, unsigned char value) {
    for (int k = first; k <= last; ++k) {
      unsigned char &m = alongRow ? mask[static_cast<unsigned int>(line)][static_cast<unsigned int>(k)]
                                  : mask[static_cast<unsigned int>(k)][static_cast<unsigned int>(line)];
      m = std::max(m, value);
    }
  };
  for (const StripeRun &r : runs)
    draw(r.alongRow, r.line, r.first, r.last, r.accepted ? 255 : 100);
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k) {
    const Crossing &c = work.crossings[k];
    draw(c.alongRow, c.line, c.first, c.last, work.keep[k] ? 255 : 100);
  }
}
} // namespace vsp::laser_detector
