/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicImuSimulator.h
  \brief Noisy MEMS gyro and accelerometer readings (white noise and bias random walks) from true motion.
*/
#ifndef VP_LASER_CONIC_IMU_SIMULATOR_H
#define VP_LASER_CONIC_IMU_SIMULATOR_H

#include <random>

#include <visp3/core/vpConfig.h>

/*!
  \ingroup group_laser_conic
  \brief Simulated IMU for tests, tutorials and benchmarks of vpLaserConicFilter.

  Each reading is the true value plus the current bias plus white noise of standard deviation
  density / sqrt(dt); the biases walk by density * sqrt(dt) per sample (the continuous-time model of an
  IMU's noise densities, as in Kalibr's and EuRoC's IMU parameters). The defaults are those of the ADIS16448
  of the EuRoC dataset. No rotation is applied: give the true rate and specific force in the IMU frame, and the
  readings are in that frame (gyro rad/s, specific force m/s², 9.81 up at rest).

  \code
  vpLaserConicImuSimulator imu;
  imu.setSeed(7);
  imu.drawInitialBias(0.005, 0.05);      // rad/s, m/s²
  double gyro[3], acc[3];
  imu.measure(0.005, wTrue, fTrue, gyro, acc);
  \endcode
*/
class VISP_EXPORT vpLaserConicImuSimulator
{
public:
  //! ADIS16448 noise densities, zero biases, seed 0.
  vpLaserConicImuSimulator();
  /*!
    Noise densities: gyro (rad/s/sqrt(Hz)), gyro bias walk (rad/s²/sqrt(Hz)), accelerometer
    (m/s²/sqrt(Hz)), accelerometer bias walk (m/s³/sqrt(Hz)); default 1.7e-4, 1.9e-5, 2.0e-3, 3.0e-3.
    \exception vpLaserConicException::badValueError on a negative or non-finite density.
  */
  void setNoise(double gyro, double gyroBiasWalk, double acc, double accBiasWalk);
  //! Seeds the generator.
  void setSeed(unsigned int seed) { m_rng.seed(seed); }
  /*!
    Draws the initial biases, each axis normal with the given standard deviations (rad/s, m/s²).
    \exception vpLaserConicException::badValueError on a negative or non-finite standard deviation.
  */
  void drawInitialBias(double gyroSigma, double accSigma);
  /*!
    Advances the biases by \e dt seconds (> 0) and returns the readings of the true angular velocity
    \e w (rad/s) and specific force \e f (m/s²).
  */
  void measure(double dt, const double w[3], const double f[3], double gyro[3], double acc[3]);
  //! Current gyro bias (rad/s), axis i.
  double getGyroBias(unsigned int i) const { return m_bg[i % 3]; }
  //! Current accelerometer bias (m/s²), axis i.
  double getAccBias(unsigned int i) const { return m_ba[i % 3]; }

private:
  std::mt19937 m_rng;
  std::normal_distribution<double> m_normal;
  double m_gyro, m_gyroWalk, m_acc, m_accWalk;
  double m_bg[3], m_ba[3];
};

#endif
