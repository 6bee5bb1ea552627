/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_score.h
  \brief The red-dominance score of the ridge detector (internal header): one pixel, and a span of a row
  with its block flags, in plain C++, SSE2 or AVX2.
*/
#ifndef VP_LASER_RIDGE_SCORE_H
#define VP_LASER_RIDGE_SCORE_H

#include <visp3/laser_conic/vpLaserConicDetector.h>

#include "ridge_tuning.h"

namespace vsp::laser_detector
{
/*!
  Score of the RGBA pixel p: the red dominance R - w max(G, B), clipped to [0, 255], where w = 1 below the
  ramp (R <= saturation - RidgeTuning::saturationRamp), falls linearly to 0 at the saturation level and
  stays 0 above. A stripe whose red channel saturates (and a white saturated core) is thus a plateau of 255
  joined continuously to its red flanks. Integer arithmetic without branch over the bytes of the RGBA
  buffer, so that the compiler vectorises it.
*/
inline unsigned char scorePixel(const unsigned char *p, int saturation)
{
  static_assert(RidgeTuning::saturationRamp == 30, "2185 / 65536 is 1 / saturationRamp");
  const int r = p[0], g = p[1], b = p[2];
  const int m = g > b ? g : b;
  int t = saturation - r; // ramp weight x 30
  t = t < 0 ? 0 : (t > RidgeTuning::saturationRamp ? RidgeTuning::saturationRamp : t);
  const int s = r - (m * t * 2185 >> 16); // 2185 / 65536 = 1 / 30 (to 1e-4)
  return static_cast<unsigned char>(s < 0 ? 0 : s);
}

/*!
  Scores the n pixels from \e rgba (a span starting at a column multiple of 16) into \e score, and sets
  the flag of each block of 16 columns (flags[0] for the first) to 0xFF when a score of the block reaches
  the threshold, else 0: no pixel of an unflagged block can be a candidate (a candidate's score exceeds its
  background by the threshold), so the candidate passes skip these blocks, most of a frame, without
  reading their scores again. \e instructions: one the processor has; every choice gives the same bytes.
*/
void scoreSpan(const unsigned char *rgba, unsigned char *score, int n, int saturation, int threshold,
               unsigned char *flags, vpLaserConicDetector::vpInstructionSet instructions);
} // namespace vsp::laser_detector

#endif
