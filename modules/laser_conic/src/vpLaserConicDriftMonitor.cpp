/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicDriftMonitor.cpp
  \brief Sliding-window test of the calibration-health figures (see vpLaserConicDriftMonitor).
*/
#include <visp3/laser_conic/vpLaserConicDriftMonitor.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <visp3/laser_conic/vpLaserConicPose.h>

#include "laser_value_check.h"

namespace
{
//! Standard normal quantile (Acklam's rational approximation, relative error below 1.2e-9).
double normalQuantile(double p)
{
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  if (p < 0.02425) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  if (p > 1.0 - 0.02425)
    return -normalQuantile(1.0 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

//! Upper quantile of a chi-square with k degrees of freedom at tail probability alpha (Wilson-Hilferty).
double chiSquareQuantile(double k, double alpha)
{
  // The normal's upper quantile from its lower tail: 1 - alpha rounds to 1 below alpha = 1.1e-16, whose
  // quantile was then NaN (a threshold no sum exceeds: the monitor silently off).
  const double z = -normalQuantile(alpha), v = 2.0 / (9.0 * k);
  const double t = 1.0 - v + z * std::sqrt(v);
  return k * t * t * t;
}

/*!
  The most a frame adds to the window's running sum. A frame whose free fit is nearly exact has a statistic in
  the 1e20s, or infinite: when it left the window, the subtraction left the sum at 0 (cancellation) or NaN
  (inf - inf), and a drift in the frames after it went unreported until the sum was next recomputed. A share
  this large already exceeds every threshold (that of the longest window, 2e5 degrees of freedom, is under
  2.3e5 at the smallest rate), and a sum holding one is still exact to a millionth.
*/
constexpr double kLargestShare = 1e9;
} // namespace

vpLaserConicDriftMonitor::vpLaserConicDriftMonitor()
  : m_window(20), m_rate(0.001), m_threshold(0.0), m_values(), m_next(0), m_count(0), m_skipped(0), m_sum(0.0),
    m_last(std::numeric_limits<double>::quiet_NaN()), m_status(DRIFT_WARMING_UP)
{
  reset();
}

void vpLaserConicDriftMonitor::setWindow(unsigned int frames)
{
  vsp::laser_value_check::require(frames > 0 && frames <= 100000,
                                  "vpLaserConicDriftMonitor: the window must hold 1 to 100000 frames");
  m_window = frames;
  reset();
}

void vpLaserConicDriftMonitor::setFalseAlarmRate(double rate)
{
  vsp::laser_value_check::require(rate > 0.0 && rate < 0.5,
                                  "vpLaserConicDriftMonitor: the false-alarm rate must be in (0, 0.5)");
  m_rate = rate;
  reset();
}

void vpLaserConicDriftMonitor::updateThreshold() { m_threshold = chiSquareQuantile(2.0 * m_window, m_rate); }

void vpLaserConicDriftMonitor::reset()
{
  m_values.assign(m_window, 0.0);
  m_next = m_count = m_skipped = 0;
  m_sum = 0.0;
  m_last = std::numeric_limits<double>::quiet_NaN();
  m_status = DRIFT_WARMING_UP;
  updateThreshold();
}

vpLaserConicDriftMonitor::vpDriftStatus vpLaserConicDriftMonitor::addFrame(const vpLaserConicPose &estimator)
{
  // A frame refused as a calibration mismatch has its final fit's figures: a knock large enough to make the
  // estimator refuse every frame is the drift to report (skipped, it left the monitor at DRIFT_OK).
  const vpLaserConicPose::vpLaserConicStatus status = estimator.getStatus();
  if (status != vpLaserConicPose::STATUS_OK && status != vpLaserConicPose::STATUS_CALIBRATION_MISMATCH) {
    ++m_skipped;
    m_last = std::numeric_limits<double>::quiet_NaN();
    return m_status;
  }
  return addFrame(estimator.getConstrainedRms(), estimator.getFreeRms(), estimator.getRansacNbInliers());
}

vpLaserConicDriftMonitor::vpDriftStatus vpLaserConicDriftMonitor::addFrame(double constrainedRms, double freeRms,
                                                                           unsigned int nbInliers)
{
  if (!(constrainedRms > 0.0) || !(freeRms > 0.0) || !std::isfinite(constrainedRms) || !std::isfinite(freeRms) ||
      nbInliers < 6) {
    ++m_skipped;
    m_last = std::numeric_limits<double>::quiet_NaN();
    return m_status;
  }
  const double ratio = constrainedRms / freeRms;
  m_last = (nbInliers - 5.0) * (ratio * ratio - 1.0);
  const double share = std::min(m_last, kLargestShare);
  m_sum += share - m_values[m_next];
  m_values[m_next] = share;
  m_next = (m_next + 1) % m_window;
  if (m_count < m_window)
    ++m_count;
  if (m_next == 0) { // once per window: the running sum recomputed, so that rounding does not accumulate
    m_sum = 0.0;
    for (double v : m_values)
      m_sum += v;
  }
  m_status = m_count < m_window ? DRIFT_WARMING_UP : (m_sum > m_threshold ? DRIFT_SUSPECTED : DRIFT_OK);
  return m_status;
}

std::string vpLaserConicDriftMonitor::getStatusMessage(vpDriftStatus status)
{
  switch (status) {
  case DRIFT_WARMING_UP:
    return "warming up: fewer frames than the window";
  case DRIFT_OK:
    return "calibration consistent with the images";
  case DRIFT_SUSPECTED:
    return "calibration drift suspected: the calibrated laser no longer explains the traces (mount knocked or moved); "
           "recalibrate (vpLaserConicSelfCalibration on recent frames)";
  }
  return "unknown status";
}
