/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_filter_impl.h
  \brief The state of vpLaserConicFilter (internal header): its history of IMU samples, its settings and the
  bookkeeping of its frames, shared by its propagation and update (vpLaserConicFilter.cpp) and its settings
  (vpLaserConicFilterSettings.cpp).
*/
#ifndef VP_LASER_FILTER_IMPL_H
#define VP_LASER_FILTER_IMPL_H

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicFilter.h>

#include "laser_filter_model.h"

namespace vsp::laser_filter
{
using vpLaserFilterModel::Covariance;
using vpLaserFilterModel::State;

//! Largest angular rate (rad/s) and specific force (m/s², about 1000 g) of a sample taken (IMU_OUT_OF_RANGE).
constexpr double kMaxImuRate = 100.0;
constexpr double kMaxImuForce = 1e4;
//! Largest time (s, either sign) of a sample or a frame taken: a double still resolves 2 us there (seconds since
//! 1970 are 1.7e9). A timestamp in nanoseconds given as seconds (1.7e18) resolves 256 s, and a frame time a unit
//! in the last place after a sample's propagated the state over that span (found by fuzz-laser-filter: 3e94 s).
constexpr double kMaxTime = 1e10;
//! Shortest interval between two IMU samples, s: a sample closer to the previous one is a duplicate (no IMU
//! runs at a megahertz), and the process noise of an interval of 1e-316 s, its density over the interval,
//! overflowed into a covariance of NaN.
constexpr double kMinImuInterval = 1e-6;

//! Largest noise density, initial standard deviation and gravity norm a setter takes: larger ones, squared and
//! summed over a second of samples, leave a covariance that is not finite (found by fuzz-laser-filter: 1e300).
constexpr double kMaxSetting = 1e3;
//! Longest IMU gap propagated that setMaxImuGap() takes, s: beyond, nothing an IMU measured holds the state.
constexpr double kMaxImuGap = 10.0;

//! Quantile of the chi-square distribution with 3 degrees of freedom (the gate of setGateProbability()).
double chi2Quantile3(double p);

//! One IMU sample of the history (camera frame) and the state after it.
struct Entry
{
  double t = 0.0;
  Eigen::Vector3d w = Eigen::Vector3d::Zero(), f = Eigen::Vector3d::Zero();
  State x = State::Zero();
  Covariance P = Covariance::Identity();
  bool valid = false; //!< false before the first frame initialised the state
};

//! The state a frame is applied to: that of a sample, or the one an earlier frame left between two samples.
struct FrameStart
{
  State x;
  Covariance P;
  double t;   //!< its time
  bool valid; //!< false before the first frame initialised the state
};
} // namespace vsp::laser_filter

struct vpLaserConicFilter::Impl
{
  using State = vsp::laser_filter::State;
  using Covariance = vsp::laser_filter::Covariance;
  using Entry = vsp::laser_filter::Entry;
  using FrameStart = vsp::laser_filter::FrameStart;

  vpLaserFilterModel::Noise noise;
  double sigmaVz0 = 0.5, sigmaBg0 = 0.01, sigmaBa0 = 0.2;
  Eigen::Matrix3d cRimu = Eigen::Matrix3d::Identity();
  double gravity = 9.80665, maxLatency = 0.1, maxGap = 0.05, predictionTimeout = 0.1, minStepHeight = 0.03;
  double gateProbability = 0.99, gate = vsp::laser_filter::chi2Quantile3(0.99),
         attitudeGate = -2.0 * std::log(1.0 - 0.99);
  unsigned int stepFrames = 2, maxRejections = 30, initFrames = 3;

  std::vector<Entry> ring = std::vector<Entry>(64);
  size_t newest = 0, count = 0;

  bool initialised = false, diverged = false, stepPending = false;
  double lastFrameTime = -std::numeric_limits<double>::infinity();
  double lastAcceptTime = -std::numeric_limits<double>::infinity();
  // Frames rejected in a row: with an attitude that agrees with the prediction, and (tiltedInRow) with one that
  // does not (see waitsForAgreeingAttitude()).
  unsigned int accepted = 0, rejectedInRow = 0, tiltedInRow = 0, stepCandidates = 0, stepCount = 0;
  //! Frames whose attitude disagrees, in a row, that declare a divergence: this many times maxRejections.
  static constexpr unsigned int kTiltedRejections = 5;
  double stepOffset = 0.0, stepVariance = 0.0;
  vpFrameStatus lastFrameStatus = FRAME_MISSING;
  double lastMahalanobis = std::numeric_limits<double>::quiet_NaN();
  // The state just after the last frame that changed it, at its time, and the time of the sample before that
  // frame (NaN: none). A frame's update is kept in the samples after it (repropagate()), not in the sample
  // before it: a second frame between the same two samples (a camera faster than the IMU, an IMU dropout, a
  // frame given twice) starts from this state, or the first frame would be lost.
  double frameSampleTime = std::numeric_limits<double>::quiet_NaN();
  FrameStart afterFrame{State::Zero(), Covariance::Identity(), 0.0, false};

  //! k-th kept sample, 0 the oldest.
  Entry &at(size_t k) { return ring[(newest + ring.size() + 1 - count + k) % ring.size()]; }
  const Entry &last() const { return ring[newest]; }

  void clearState()
  {
    initialised = diverged = stepPending = false;
    accepted = rejectedInRow = tiltedInRow = stepCandidates = 0;
    lastFrameTime = lastAcceptTime = -std::numeric_limits<double>::infinity();
    frameSampleTime = std::numeric_limits<double>::quiet_NaN();
  }

  //! A frame at \e t updated the state (\e step: by a ground step): the rejection counts start again.
  void frameUsed(double t, bool step)
  {
    rejectedInRow = tiltedInRow = stepCandidates = 0;
    stepPending = step;
    lastAcceptTime = t;
  }

  vpImuStatus addImu(double t, const Eigen::Vector3d &w, const Eigen::Vector3d &f);
  vpFrameStatus checkFrameTime(double t) const;
  vpFrameStatus addFrame(double t, const Eigen::Vector3d &z, const Eigen::Matrix3d &R);
  void initialise(State &x, Covariance &P, const Eigen::Vector3d &z, const Eigen::Matrix3d &R);
  vpFrameStatus gateAndUpdate(double t, State &x, Covariance &P, const Eigen::Vector3d &z, const Eigen::Matrix3d &R);
  bool stepCandidate(const Eigen::Vector3d &y, const Eigen::Matrix3d &S, bool attitudeAgrees);
  bool waitsForAgreeingAttitude(const FrameStart &start, size_t k, double t, const Eigen::Vector3d &z,
                                const Eigen::Matrix3d &R);
  //! The state a frame at \e t after the k-th sample (and before the next) is applied to (see frameSampleTime).
  FrameStart frameStart(size_t k, double t)
  {
    const Entry &sample = at(k);
    if (frameSampleTime == sample.t && afterFrame.t <= t)
      return afterFrame;
    return FrameStart{sample.x, sample.P, sample.t, sample.valid};
  }
  //! Propagates (x, P), the state at time \e from between the k-th sample and the next, to \e t (not after the
  //! next sample) with the mean of the two samples' readings.
  void propagateFrom(size_t k, double from, double t, State &x, Covariance &P)
  {
    const Entry &before = at(k);
    if (t > from) {
      const Entry &after = (k + 1 < count) ? at(k + 1) : before;
      vpLaserFilterModel::propagate(x, P, 0.5 * (before.w + after.w), 0.5 * (before.f + after.f), t - from, gravity,
                                    noise);
    }
  }
  void repropagate(size_t k, double t, const State &x, const Covariance &P);
};

#endif
