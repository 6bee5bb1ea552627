/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The settings of vpLaserConicFilter, checked at the API edge, and its construction and reset.
#include <visp3/laser_conic/vpLaserConicFilter.h>

#include <cmath>

#include <Eigen/LU>

#include "laser_filter_impl.h"
#include "laser_value_check.h"

using namespace vsp::laser_filter;
using vsp::laser_value_check::require;
using vsp::laser_value_check::requireNonNegative;
using vsp::laser_value_check::requirePositive;

// The quantile of the chi-square distribution with 3 degrees of freedom (CDF erf(sqrt(x/2)) - sqrt(2x/pi) e^(-x/2)).
double vsp::laser_filter::chi2Quantile3(double p)
{
  double lo = 0.0, hi = 200.0;
  for (int it = 0; it < 200; ++it) {
    const double x = 0.5 * (lo + hi);
    const double cdf = std::erf(std::sqrt(0.5 * x)) - std::sqrt(2.0 * x / M_PI) * std::exp(-0.5 * x);
    (cdf < p ? lo : hi) = x;
  }
  return 0.5 * (lo + hi);
}

vpLaserConicFilter::vpLaserConicFilter() : m_impl(new Impl) {}
vpLaserConicFilter::~vpLaserConicFilter() = default;

void vpLaserConicFilter::setImuNoise(double gyro, double gyroBiasWalk, double acc, double accBiasWalk)
{
  for (double v : {gyro, gyroBiasWalk, acc, accBiasWalk})
    require(v > 0.0 && v <= kMaxSetting,
            "vpLaserConicFilter::setImuNoise: noise densities must be > 0 and at most 1e3 (an IMU's are 1e-5 to 1)");
  m_impl->noise.gyro = gyro;
  m_impl->noise.gyroBiasWalk = gyroBiasWalk;
  m_impl->noise.acc = acc;
  m_impl->noise.accBiasWalk = accBiasWalk;
}

void vpLaserConicFilter::setInitialUncertainty(double verticalSpeed, double gyroBias, double accBias)
{
  for (double v : {verticalSpeed, gyroBias, accBias})
    require(v > 0.0 && v <= kMaxSetting,
            "vpLaserConicFilter::setInitialUncertainty: standard deviations must be > 0 and at most 1e3");
  m_impl->sigmaVz0 = verticalSpeed;
  m_impl->sigmaBg0 = gyroBias;
  m_impl->sigmaBa0 = accBias;
}

void vpLaserConicFilter::setImuToCameraRotation(const vpRotationMatrix &cRimu)
{
  Eigen::Matrix3d R;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      R(i, j) = cRimu[i][j];
  // Checked before it replaces the mounting: a refused matrix leaves the one set before.
  // A reflection (determinant -1, a mirrored axis) is orthogonal too, but maps the gyro's axial vector the
  // wrong way: the attitude turned against the motion.
  require(R.allFinite() && (R * R.transpose()).isIdentity(1e-6) && R.determinant() > 0.0,
          "vpLaserConicFilter::setImuToCameraRotation: not a rotation matrix (orthogonal, determinant +1)");
  m_impl->cRimu = R;
}

void vpLaserConicFilter::setGravityNorm(double g)
{
  require(g >= 0.1 && g <= kMaxSetting,
          "vpLaserConicFilter::setGravityNorm: the gravity norm must be in [0.1, 1e3] m/s^2");
  m_impl->gravity = g;
}

void vpLaserConicFilter::setMaxLatency(double seconds, unsigned int samples)
{
  require(seconds >= 0.0 && std::isfinite(seconds) && samples >= 2 && samples <= 1000000,
          "vpLaserConicFilter::setMaxLatency: the latency must be finite and >= 0, the history 2 to 1e6 samples");
  m_impl->maxLatency = seconds;
  m_impl->ring.assign(samples, Entry());
  m_impl->count = 0;
  m_impl->clearState();
}

void vpLaserConicFilter::setMaxImuGap(double seconds)
{
  require(seconds > 0.0 && seconds <= kMaxImuGap, "vpLaserConicFilter::setMaxImuGap: the gap must be in (0, 10] s");
  m_impl->maxGap = seconds;
}

void vpLaserConicFilter::setGateProbability(double p)
{
  require(p > 0.0 && p < 1.0, "vpLaserConicFilter::setGateProbability: the probability must be in (0, 1)");
  m_impl->gateProbability = p;
  m_impl->gate = chi2Quantile3(p);
  m_impl->attitudeGate = -2.0 * std::log(1.0 - p); // chi-square quantile, 2 degrees of freedom
}

void vpLaserConicFilter::setStepFrames(unsigned int frames)
{
  require(frames > 0, "vpLaserConicFilter::setStepFrames: at least one frame");
  m_impl->stepFrames = frames;
}

void vpLaserConicFilter::setMinStepHeight(double metres)
{
  requireNonNegative(metres, "vpLaserConicFilter::setMinStepHeight: the height must be finite and >= 0");
  m_impl->minStepHeight = metres;
}

void vpLaserConicFilter::setMaxRejections(unsigned int frames)
{
  require(frames > 0, "vpLaserConicFilter::setMaxRejections: at least one frame");
  m_impl->maxRejections = frames;
}

void vpLaserConicFilter::setInitialisationFrames(unsigned int frames) { m_impl->initFrames = frames; }

void vpLaserConicFilter::setPredictionTimeout(double seconds)
{
  requirePositive(seconds, "vpLaserConicFilter::setPredictionTimeout: the timeout must be finite and > 0");
  m_impl->predictionTimeout = seconds;
}

void vpLaserConicFilter::reset()
{
  m_impl->count = 0;
  m_impl->stepCount = 0;
  m_impl->clearState();
}
