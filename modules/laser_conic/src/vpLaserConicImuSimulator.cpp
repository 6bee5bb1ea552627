/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicImuSimulator.h>

#include <cmath>

#include <visp3/laser_conic/vpLaserConicException.h>

#include "laser_value_check.h"

using vsp::laser_value_check::requireNonNegative;

vpLaserConicImuSimulator::vpLaserConicImuSimulator()
  : m_rng(0), m_normal(0.0, 1.0), m_gyro(1.7e-4), m_gyroWalk(1.9e-5), m_acc(2.0e-3),
    m_accWalk(3.0e-3), m_bg{0, 0, 0}, m_ba{0, 0, 0}
{
}

void vpLaserConicImuSimulator::setNoise(double gyro, double gyroBiasWalk, double acc, double accBiasWalk)
{
  for (double v : {gyro, gyroBiasWalk, acc, accBiasWalk})
    requireNonNegative(v, "vpLaserConicImuSimulator::setNoise: densities must be finite and >= 0");
  m_gyro = gyro;
  m_gyroWalk = gyroBiasWalk;
  m_acc = acc;
  m_accWalk = accBiasWalk;
}

void vpLaserConicImuSimulator::drawInitialBias(double gyroSigma, double accSigma)
{
  requireNonNegative(gyroSigma,
                     "vpLaserConicImuSimulator::drawInitialBias: standard deviations must be finite and >= 0");
  requireNonNegative(accSigma,
                     "vpLaserConicImuSimulator::drawInitialBias: standard deviations must be finite and >= 0");
  for (int i = 0; i < 3; ++i) {
    m_bg[i] = gyroSigma * m_normal(m_rng);
    m_ba[i] = accSigma * m_normal(m_rng);
  }
}

void vpLaserConicImuSimulator::measure(double dt, const double w[3], const double f[3], double gyro[3], double acc[3])
{
  vsp::laser_value_check::requirePositive(dt,
                                          "vpLaserConicImuSimulator::measure: the time step must be finite and > 0");
  const double sdt = std::sqrt(dt);
  for (int i = 0; i < 3; ++i) {
    m_bg[i] += m_gyroWalk * sdt * m_normal(m_rng);
    m_ba[i] += m_accWalk * sdt * m_normal(m_rng);
    gyro[i] = w[i] + m_bg[i] + m_gyro / sdt * m_normal(m_rng);
    acc[i] = f[i] + m_ba[i] + m_acc / sdt * m_normal(m_rng);
  }
}
