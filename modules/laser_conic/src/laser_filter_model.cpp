/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_filter_model.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace vpLaserFilterModel
{
namespace
{
Eigen::Matrix3d skew(const Eigen::Vector3d &v)
{
  Eigen::Matrix3d S;
  S << 0.0, -v(2), v(1), v(2), 0.0, -v(0), -v(1), v(0), 0.0;
  return S;
}

//! d g / d(roll, pitch), 3x2.
Eigen::Matrix<double, 3, 2> normalJacobian(double roll, double pitch)
{
  const double sr = std::sin(roll), cr = std::cos(roll), sp = std::sin(pitch), cp = std::cos(pitch);
  Eigen::Matrix<double, 3, 2> J;
  J << 0.0, cp, -cr * cp, sr * sp, -sr * cp, -cr * sp;
  return J;
}

//! d(roll, pitch) / d g at the unit vector g, 2x3 (roll = atan2(-gy, gz), pitch = asin(gx)).
Eigen::Matrix<double, 2, 3> angleJacobian(const Eigen::Vector3d &g)
{
  const double q = g(1) * g(1) + g(2) * g(2); // cos² pitch
  Eigen::Matrix<double, 2, 3> J;
  J << 0.0, -g(2) / q, g(1) / q, 1.0 / std::sqrt(q), 0.0, 0.0;
  return J;
}

//! Rotation exp([w]x) by Rodrigues' formula (second order below 1e-8 rad).
Eigen::Matrix3d expRotation(const Eigen::Vector3d &w)
{
  const double theta = w.norm();
  const Eigen::Matrix3d W = skew(w);
  if (theta < 1e-8)
    return Eigen::Matrix3d::Identity() + W + 0.5 * W * W;
  return Eigen::Matrix3d::Identity() + (std::sin(theta) / theta) * W +
         ((1.0 - std::cos(theta)) / (theta * theta)) * W * W;
}
} // namespace

Eigen::Vector3d normalOf(double roll, double pitch)
{
  const double cp = std::cos(pitch);
  return Eigen::Vector3d(std::sin(pitch), -std::sin(roll) * cp, std::cos(roll) * cp);
}

void propagate(State &x, Covariance &P, const Eigen::Vector3d &w, const Eigen::Vector3d &f, double dt, double gravity,
               const Noise &noise)
{
  const Eigen::Vector3d g = normalOf(x(ROLL), x(PITCH));
  // The camera turns by R = exp([(w - bg) dt]x): a world-fixed direction becomes R^T g in the new frame.
  const Eigen::Matrix3d Rt = expRotation((w - x.segment<3>(BG)) * dt).transpose();
  const Eigen::Vector3d gNext = Rt * g;
  const Eigen::Vector3d gMid = (0.5 * (g + gNext)).normalized();
  const Eigen::Vector3d fc = f - x.segment<3>(BA); // bias-corrected specific force
  const double acc = -gMid.dot(fc) - gravity;

  const Eigen::Matrix<double, 2, 3> A = angleJacobian(gNext);
  const Eigen::Matrix<double, 3, 2> Jg = normalJacobian(x(ROLL), x(PITCH));
  const Eigen::Matrix3d dgdb = -dt * Rt * skew(g); // d gNext / d bg
  const Eigen::Matrix<double, 1, 2> dAccdAtt = -fc.transpose() * 0.5 * (Jg + Rt * Jg);
  const Eigen::Matrix<double, 1, 3> dAccdBg = -0.5 * fc.transpose() * dgdb;
  const Eigen::Matrix<double, 1, 3> dAccdBa = gMid.transpose();

  Covariance F = Covariance::Identity();
  const double half = 0.5 * dt * dt;
  F(H, VZ) = dt;
  F.block<1, 2>(H, ROLL) = half * dAccdAtt;
  F.block<1, 3>(H, BG) = half * dAccdBg;
  F.block<1, 3>(H, BA) = half * dAccdBa;
  F.block<1, 2>(VZ, ROLL) = dt * dAccdAtt;
  F.block<1, 3>(VZ, BG) = dt * dAccdBg;
  F.block<1, 3>(VZ, BA) = dt * dAccdBa;
  F.block<2, 2>(ROLL, ROLL) = A * Rt * Jg;
  F.block<2, 3>(ROLL, BG) = A * dgdb;

  x(H) += x(VZ) * dt + half * acc;
  x(VZ) += acc * dt;
  x(ROLL) = std::atan2(-gNext(1), gNext(2));
  x(PITCH) = std::asin(std::max(-1.0, std::min(1.0, gNext(0))));

  // Discretised process noise: the gyro noise turns g as a bias error does, the accelerometer noise
  // along g integrates twice, the biases walk.
  const Eigen::Matrix<double, 2, 3> Gw = A * dgdb; // per unit of rate error
  const double qa = noise.acc * noise.acc;
  // F differs from the identity in its first four rows only (A): F P F^T changes the rows and columns
  // of (h, vz, roll, pitch) and leaves the bias block, a quarter of the dense product's cost.
  const Eigen::Matrix<double, 4, kStateSize> A4 = F.topRows<4>();
  const Eigen::Matrix<double, 4, kStateSize> M = A4 * P;
  P.topLeftCorner<4, 4>() = M * A4.transpose();
  P.topRightCorner<4, kStateSize - 4>() = M.rightCols<kStateSize - 4>();
  P.bottomLeftCorner<kStateSize - 4, 4>() = M.rightCols<kStateSize - 4>().transpose();
  P.block<2, 2>(ROLL, ROLL) += (noise.gyro * noise.gyro / dt) * Gw * Gw.transpose();
  P(H, H) += qa * dt * dt * dt / 3.0;
  P(H, VZ) += qa * half;
  P(VZ, H) += qa * half;
  P(VZ, VZ) += qa * dt;
  P.diagonal().segment<3>(BG).array() += noise.gyroBiasWalk * noise.gyroBiasWalk * dt;
  P.diagonal().segment<3>(BA).array() += noise.accBiasWalk * noise.accBiasWalk * dt;
}

double innovation(const State &x, const Covariance &P, const Eigen::Vector3d &z, const Eigen::Matrix3d &R,
                  Eigen::Vector3d &y, Eigen::Matrix3d &S)
{
  y(0) = z(0) - x(H);
  y(1) = std::remainder(z(1) - x(ROLL), 2.0 * M_PI);
  y(2) = std::remainder(z(2) - x(PITCH), 2.0 * M_PI);
  const int idx[3] = {H, ROLL, PITCH};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      S(i, j) = P(idx[i], idx[j]) + R(i, j);
  return y.dot(S.ldlt().solve(y));
}

void update(State &x, Covariance &P, const Eigen::Vector3d &y, const Eigen::Matrix3d &S, const Eigen::Matrix3d &R)
{
  const int idx[3] = {H, ROLL, PITCH};
  Eigen::Matrix<double, kStateSize, 3> PHt;
  for (int j = 0; j < 3; ++j)
    PHt.col(j) = P.col(idx[j]);
  const Eigen::Matrix<double, kStateSize, 3> K = S.ldlt().solve(PHt.transpose()).transpose();
  x += K * y;
  Covariance IKH = Covariance::Identity();
  for (int j = 0; j < 3; ++j)
    IKH.col(idx[j]) -= K.col(j);
  P = IKH * P * IKH.transpose() + K * R * K.transpose();
  P = 0.5 * (P + P.transpose()).eval();
}
} // namespace vpLaserFilterModel
