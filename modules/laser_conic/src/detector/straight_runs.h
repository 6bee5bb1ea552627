/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file straight_runs.h
  \brief Long straight runs of ridge points (internal header): a red cable or a strip of red tape on the
  floor, which a ring's image never holds and which the ring's ellipse is located without.
*/
#ifndef VP_LASER_STRAIGHT_RUNS_H
#define VP_LASER_STRAIGHT_RUNS_H

#include <vector>

#include <visp3/core/vpImagePoint.h>

namespace vsp::laser_detector
{
/*!
  The indices of \e points (in their order) that do not lie on a long straight run: up to a few runs are
  found one after the other, each the points within 1.5 px of the line through the most points (vpRansacLoop()
  with a fixed seed: the same points give the same runs) along a stretch of that line at least
  150 px long without long gaps (the tolerances and why: straight_runs.cpp). Every index when there is no
  such run.
*/
std::vector<int> offStraightRuns(const std::vector<vpImagePoint> &points);
} // namespace vsp::laser_detector

#endif
