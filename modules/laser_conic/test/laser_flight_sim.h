/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_flight_sim.h
  \brief A simulated flight for the vpLaserConicFilter tests: a smooth trajectory over a ground with an
  optional box step, its exact IMU truth (angular velocity, specific force), the noisy IMU stream
  (vpLaserConicImuSimulator, ADIS16448 densities) and each frame's GP-3 estimate on noisy trace points.
*/
#ifndef VP_LASER_FLIGHT_SIM_H
#define VP_LASER_FLIGHT_SIM_H

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include <visp3/laser_conic/vpLaserConicFilter.h>
#include <visp3/laser_conic/vpLaserConicImuSimulator.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "laser_test_utils.h"

namespace laser_flight
{
//! True state of the camera at one time (world z up, ground z = ground height under the camera).
struct Truth
{
  double h, vz, roll, pitch; //!< the filter's outputs
  Eigen::Vector3d w, f;      //!< angular velocity and specific force, camera frame
  Eigen::Vector3d down;      //!< downward ground normal, camera frame
};

//! A smooth flight: altitude, horizontal motion and tilts are sums of sinusoids (phases from the seed).
struct Flight
{
  double h0 = 1.2, hAmp = 0.25, hFreq = 0.11; //!< altitude (m), its oscillation (m, Hz)
  double xyAmp = 0.5, xyFreq = 0.07;          //!< horizontal motion (m, Hz)
  double tilt = vpMath::rad(8.0), tiltFreq = 0.23;
  double stepTime = 1e9, boxHeight = 0.2; //!< ground raised by boxHeight from stepTime on (flying onto a box)
  double phase[5] = {0, 0, 0, 0, 0};

  explicit Flight(unsigned int seed = 0)
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 2.0 * M_PI);
    for (double &p : phase)
      p = u(rng);
  }
  Eigen::Vector3d position(double t) const
  {
    return Eigen::Vector3d(xyAmp * std::sin(2 * M_PI * xyFreq * t + phase[0]),
                           xyAmp * std::sin(2 * M_PI * xyFreq * 1.3 * t + phase[1]),
                           h0 + hAmp * std::sin(2 * M_PI * hFreq * t + phase[2]));
  }
  Eigen::Vector3d acceleration(double t) const
  {
    const double a = 2 * M_PI * xyFreq, b = 2 * M_PI * xyFreq * 1.3, c = 2 * M_PI * hFreq;
    return Eigen::Vector3d(-xyAmp * a * a * std::sin(a * t + phase[0]), -xyAmp * b * b * std::sin(b * t + phase[1]),
                           -hAmp * c * c * std::sin(c * t + phase[2]));
  }
  //! Camera orientation in the world: optical axis down, tilted by two sinusoids, slow yaw.
  Eigen::Matrix3d rotation(double t) const
  {
    const double a = tilt * std::sin(2 * M_PI * tiltFreq * t + phase[3]);
    const double b = tilt * std::sin(2 * M_PI * tiltFreq * 0.8 * t + phase[4]);
    const Eigen::Matrix3d down = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    return down * Eigen::AngleAxisd(0.1 * t, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY());
  }
  double groundHeight(double t) const { return t >= stepTime ? boxHeight : 0.0; }

  Truth at(double t) const
  {
    Truth s;
    const Eigen::Vector3d p = position(t);
    const double dt = 1e-5;
    s.h = p(2) - groundHeight(t);
    s.vz = (position(t + dt)(2) - position(t - dt)(2)) / (2 * dt);
    const Eigen::Matrix3d R = rotation(t);
    const Eigen::Matrix3d W = R.transpose() * (rotation(t + dt) - rotation(t - dt)) / (2 * dt);
    s.w = Eigen::Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1)) * 0.5;
    s.f = R.transpose() * (acceleration(t) + Eigen::Vector3d(0, 0, 9.80665));
    s.down = R.transpose() * Eigen::Vector3d(0, 0, -1);
    s.roll = std::atan2(-s.down(1), s.down(2));
    s.pitch = std::asin(s.down(0));
    return s;
  }
};

//! One frame's GP-3 estimate on \e n noisy trace points (sigma px); false when GP-3 failed.
inline bool frameEstimate(const Truth &truth, unsigned int n, double sigma, std::mt19937 &rng, vpLaserConicPose &pose)
{
  laser_test::Scene s;
  s.rig.cMl.buildFrom(0.1, 0.0, 0.0, 0.0, 0.0, 0.0);
  s.plane << -truth.down, truth.h;
  std::vector<vpImagePoint> points;
  if (!laser_test::traceImagePoints(s, n, rng, points))
    return false;
  points = laser_test::addNoise(points, sigma, rng);
  pose.setCameraParameters(s.rig.cam);
  pose.setLaser(s.rig.openingAngle, s.rig.cMl);
  pose.setRansacThreshold(3.0 * sigma);
  pose.setCovarianceComputation(true);
  vpPlane plane;
  return pose.computePlane(points, vpLaserConicPose::GP3, plane);
}

//! One sample of a flight: the filter's output and the truth at an IMU time.
struct Sample
{
  double t;
  Truth truth;
  Eigen::Vector4d x; //!< filter (h, vz, roll, pitch)
  Eigen::Matrix4d P;
  vpLaserConicFilter::vpFilterStatus status;
};

//! One frame of a flight: its time, the per-frame estimate (when any) and the filter's verdict.
struct FrameRecord
{
  double t;
  bool hasPlane;
  double h, roll, pitch; //!< per-frame estimate
  double hTrue;
  vpLaserConicFilter::vpFrameStatus status;
};

//! What a flight does to the frames: drop some, corrupt some (by a plane offset of k sigma).
struct FrameEvents
{
  double dropFrom = -1.0, dropTo = -1.0; //!< no plane in the frames of [dropFrom, dropTo)
  std::vector<int> outlierFrames;        //!< frames whose altitude is offset
  double outlierSigmas = 5.0;            //!< offset, in standard deviations of the innovation
  //! Frames exposed in [tiltedFrom, tiltedTo) give a plane off by tiltedAltitude (m) and tiltedPitch (rad): the
  //! one tilted plane GP-3 fits to a ring across a box's edge.
  double tiltedFrom = -1.0, tiltedTo = -1.0, tiltedAltitude = 0.0, tiltedPitch = 0.0;
};

/*!
  Flies \e flight for \e duration seconds: IMU at \e imuRate, frames at \e frameRate delivered \e latency
  seconds after their exposure, through \e filter. Records every IMU-rate output and every frame.
*/
inline void fly(const Flight &flight, double duration, unsigned int seed, vpLaserConicFilter &filter,
                std::vector<Sample> &samples, std::vector<FrameRecord> &frames,
                const FrameEvents &events = FrameEvents(), double imuRate = 200.0, double frameRate = 30.0,
                double latency = 0.03, double pixelSigma = 0.5)
{
  std::mt19937 rng(seed);
  vpLaserConicImuSimulator imu;
  imu.setSeed(seed + 1);
  imu.drawInitialBias(0.003, 0.03);
  const double dt = 1.0 / imuRate;
  struct Pending
  {
    double t;
    bool ok;
    double h, r, p;
    vpMatrix C;
    double hTrue;
    int index;
  };
  std::vector<Pending> queue;
  int frameIndex = 0;
  double nextFrame = 0.0;
  samples.clear();
  frames.clear();
  vpLaserConicPose pose;
  pose.setRansacSeed(seed);
  for (int k = 0; k * dt <= duration; ++k) {
    const double t = k * dt;
    const Truth truth = flight.at(t);
    double gyro[3], acc[3];
    imu.measure(dt, truth.w.data(), truth.f.data(), gyro, acc);
    filter.addImu(t, gyro, acc);
    while (nextFrame <= t) { // exposure: estimate now, deliver after the latency
      const Truth ft = flight.at(nextFrame);
      // C is never empty: ViSP 3.5 copies an empty vpMatrix with memcpy from a null pointer (UBSan).
      Pending p{nextFrame, false, 0, 0, 0, vpMatrix(3, 3, 0.0), ft.h, frameIndex};
      const bool dropped = nextFrame >= events.dropFrom && nextFrame < events.dropTo;
      if (!dropped && frameEstimate(ft, 120, pixelSigma, rng, pose)) {
        p.ok = true;
        p.h = pose.getAltitude();
        p.r = pose.getRoll();
        p.p = pose.getPitch();
        p.C = pose.getCovarianceMatrix();
      }
      queue.push_back(p);
      ++frameIndex;
      nextFrame = frameIndex / frameRate;
    }
    while (!queue.empty() && queue.front().t + latency <= t + 1e-12) {
      Pending p = queue.front();
      queue.erase(queue.begin());
      FrameRecord rec{p.t, p.ok, p.h, p.r, p.p, p.hTrue, vpLaserConicFilter::FRAME_MISSING};
      if (p.ok) {
        for (int o : events.outlierFrames)
          if (o == p.index && filter.isInitialised()) { // offset along the altitude, in innovation sigmas
            const vpMatrix P = filter.getCovarianceMatrix();
            p.h += events.outlierSigmas * std::sqrt(p.C[0][0] + P[0][0]);
          }
        if (p.t >= events.tiltedFrom && p.t < events.tiltedTo) {
          p.h += events.tiltedAltitude;
          p.p += events.tiltedPitch;
        }
        rec.h = p.h;
        rec.status = filter.addFrame(p.t, p.h, p.r, p.p, p.C);
      } else
        rec.status = filter.addMissingFrame(p.t);
      frames.push_back(rec);
    }
    if (filter.isInitialised()) {
      Sample s;
      s.t = t;
      s.truth = truth;
      const vpColVector x = filter.getState();
      const vpMatrix P = filter.getCovarianceMatrix();
      for (int i = 0; i < 4; ++i) {
        s.x(i) = x[i];
        for (int j = 0; j < 4; ++j)
          s.P(i, j) = P[i][j];
      }
      s.status = filter.getStatus();
      samples.push_back(s);
    }
  }
}

//! Error (filter - truth) of an output sample, angles wrapped.
inline Eigen::Vector4d error(const Sample &s)
{
  return Eigen::Vector4d(s.x(0) - s.truth.h, s.x(1) - s.truth.vz, std::remainder(s.x(2) - s.truth.roll, 2 * M_PI),
                         std::remainder(s.x(3) - s.truth.pitch, 2 * M_PI));
}
} // namespace laser_flight

#endif
