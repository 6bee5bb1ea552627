/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_filter_model.h
  \brief The extended Kalman filter of vpLaserConicFilter: state, IMU propagation, frame update.
  Pure Eigen, fixed sizes, no heap.

  State x = (h, vz, roll, pitch, bgx, bgy, bgz, bax, bay, baz):
  - h: altitude of the camera centre over the ground plane (m), vz = dh/dt (m/s);
  - roll, pitch: the downward unit normal of the ground in the camera frame,
    g = Rx(roll) Ry(pitch) (0, 0, 1) = (sin p, -sin r cos p, cos r cos p) (vpLaserConicPose's convention);
  - bg, ba: gyro (rad/s) and accelerometer (m/s²) biases in the camera frame. The accelerometer bias is
    kept whole: only its component along g enters the vertical acceleration, but that component changes
    as the vehicle tilts, which a scalar bias cannot follow.
  Kinematics (IMU at the camera centre, a world-fixed ground): dg/dt = g x (w - bg), and the vertical
  acceleration d²h/dt² = -g . (f - ba) - gravity, f the specific force in the camera frame.
*/
#ifndef VP_LASER_FILTER_MODEL_H
#define VP_LASER_FILTER_MODEL_H

#include <Eigen/Core>

namespace vpLaserFilterModel
{
constexpr int kStateSize = 10;
enum Index { H = 0, VZ = 1, ROLL = 2, PITCH = 3, BG = 4, BA = 7 };
typedef Eigen::Matrix<double, kStateSize, 1> State;
typedef Eigen::Matrix<double, kStateSize, kStateSize> Covariance;

//! Continuous-time noise densities of the IMU (white noise and bias random walks).
struct Noise
{
  double gyro = 1.7e-4;         //!< rad/s/sqrt(Hz)
  double gyroBiasWalk = 1.9e-5; //!< rad/s²/sqrt(Hz)
  double acc = 2.0e-3;          //!< m/s²/sqrt(Hz)
  double accBiasWalk = 3.0e-3;  //!< m/s³/sqrt(Hz)
};

//! Downward ground normal of (roll, pitch).
Eigen::Vector3d normalOf(double roll, double pitch);

/*!
  Propagates (x, P) over dt seconds with one IMU reading (camera frame: gyro w in rad/s, specific force f
  in m/s²), with the first-order transition and the discretised process noise of \e noise.
*/
void propagate(State &x, Covariance &P, const Eigen::Vector3d &w, const Eigen::Vector3d &f, double dt, double gravity,
               const Noise &noise);

//! Innovation of a measurement z = (h, roll, pitch) of covariance R: y, S and the squared Mahalanobis distance.
double innovation(const State &x, const Covariance &P, const Eigen::Vector3d &z, const Eigen::Matrix3d &R,
                  Eigen::Vector3d &y, Eigen::Matrix3d &S);

//! Kalman update with the innovation (y, S) of a measurement of covariance R (Joseph form).
void update(State &x, Covariance &P, const Eigen::Vector3d &y, const Eigen::Matrix3d &S, const Eigen::Matrix3d &R);
} // namespace vpLaserFilterModel

#endif
