/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_chains.h
  \brief The continuity filter of the ridge detector (internal header): the crossings chained with their
  neighbours, the short chains dropped.
*/
#ifndef VP_LASER_RIDGE_CHAINS_H
#define VP_LASER_RIDGE_CHAINS_H

#include <vector>

#include "laser_detector.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
/*!
  Marks in work.keep the crossings of work.crossings (in an image of W x H pixels) that belong to chains
  (neighbours within \e link pixels) whose extent, the bounding-box diagonal, is at least \e minLength
  pixels; all when minLength <= 0. Leaves in work.parent, for the crossings in work.order, the root of
  their chain.
*/
void longChains(RidgeWorkspace &work, int W, int H, double link, double minLength);

//! The points of the crossings work.keep marks, in their order.
std::vector<vpImagePoint> keptPoints(const RidgeWorkspace &work);

/*!
  The chain of each crossing work.keep marks, in the order of keptPoints(): the root longChains() left in
  work.parent (any integer, equal for the crossings of one chain). Empty when longChains() linked nothing
  (a minimum length of 0).
*/
std::vector<int> keptChains(const RidgeWorkspace &work);

//! The link radius (pixels) of chains whose lines are \e step pixels apart and linked within \e linkSteps of them.
inline double linkRadius(double linkSteps, int step) { return linkSteps * step + RidgeTuning::linkSlack; }
} // namespace vsp::laser_detector

#endif
