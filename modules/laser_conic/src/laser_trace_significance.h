/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_trace_significance.h
  \brief Private tests that points can hold a trace: not all on one line, and a trace that stands out from
  clutter, by the expected number of conics that points spread at random over the same area would support as
  well (an a-contrario number of false alarms). Without it, 150 points at random with no trace in them gave
  STATUS_OK on 27 of 40 sets (GP-3): RANSAC, over every sample of three points, always finds a conic that a few
  of them lie on.
*/
#ifndef VP_LASER_TRACE_SIGNIFICANCE_H
#define VP_LASER_TRACE_SIGNIFICANCE_H

#include <string>
#include <vector>

#include <Eigen/Core>

#include "laser_estimators.h"
#include "laser_robust_fit.h"

namespace vsp::laser_trace_significance
{
//! True when all \e points lie on one line (or one point), up to rounding.
bool allCollinear(const vsp::laser_estimators::PointList &points);

/*!
  log10 of the number of false alarms of a trace: \e inliers of the \e points (normalized coordinates) within
  \e halfWidth (normalized units) of the ellipse \e conic, covering \e coverage radians of it, found by
  samples of \e sampleSize points. It is the number of such samples, C(N, sampleSize), times the probability
  that at least inliers - sampleSize of the other points fall by chance in the band of that width along the
  covered arc, the points spread uniformly over their bounding box. Far below 0 for a trace (-400 for 360
  points of a ring among 3000 of clutter); around or above 0 for clutter alone. +infinity when the conic is no
  ellipse.
*/
double log10FalseAlarms(const vsp::laser_estimators::PointList &points, size_t inliers, const Eigen::Matrix3d &conic,
                        double coverage, double halfWidth, int sampleSize);

/*!
  log10FalseAlarms() of the trace of a final fit (\e result with \e settings): its inliers within the band that
  collected them, max(threshold, scaleFactor x sigma), around its conic.
*/
double log10FalseAlarms(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                        const vsp::laser_robust_fit::Settings &settings, int sampleSize);

//! A trace is one when clutter would give fewer than 10^kMaxLog10FalseAlarms as good (1 frame of clutter in 100).
constexpr double kMaxLog10FalseAlarms = -2.0;

/*!
  Empty when the trace of a final fit stands out from clutter (log10FalseAlarms() under kMaxLog10FalseAlarms) or
  holds every point (nothing to tell it from), else why not, as status details.
*/
std::string clutterReason(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                          const vsp::laser_robust_fit::Settings &settings, int sampleSize);

//! log of the probability that a binomial variable of \e n trials of probability \e p is \e k or more.
double logBinomialTail(double n, double k, double p);
} // namespace vsp::laser_trace_significance

#endif
