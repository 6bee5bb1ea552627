/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_noise.h
  \brief The noise of the red-dominance score estimated from the image itself (internal header): it sets
  the ridge detector's contrast threshold.
*/
#ifndef VP_LASER_RIDGE_NOISE_H
#define VP_LASER_RIDGE_NOISE_H

#include <vector>

#include "laser_detector.h"

namespace vsp::laser_detector
{
/*!
  Robust noise of the unclipped score r - max(g, b): 1.4826 MAD / sqrt(2) of its differences two pixels
  apart (two apart: the optical blur correlates neighbours), every 4th pixel of every 8th row of \e region
  (the whole image when null; about 60 000 samples in a 1600 x 1200 image: the median is known to a few
  percent). 0 when there is no sample. \e instructions: one the processor has; every choice gives the
  same estimate.
*/
double estimateNoise(const vpImage<vpRGBa> &I, const RegionSpans *region,
                     vpLaserConicDetector::vpInstructionSet instructions);

/*!
  Begins a ridge detection of \e I: forgets the last detection's crossings (in \e work) and rejected runs,
  estimates the noise over \e region (estimateNoise()) and the contrast threshold it sets, max(minContrast,
  noiseFactor x noise), into \e report; returns that threshold in whole grey levels (at most 255), or -1 for
  an empty image.
*/
int beginDetection(const vpImage<vpRGBa> &I, const RidgeSettings &settings, const RegionSpans *region,
                   RidgeWorkspace &work, std::vector<StripeRun> &runs, RidgeReport &report);
} // namespace vsp::laser_detector

#endif
