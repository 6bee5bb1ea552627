/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicFilter.h>

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "laser_filter_impl.h"
#include "laser_filter_model.h"
#include "laser_value_check.h"

using namespace vpLaserFilterModel;
using namespace vsp::laser_filter;
using vsp::laser_value_check::require;
using vsp::laser_value_check::requireNonNegative;
using vsp::laser_value_check::requirePositive;

namespace
{
//! Largest and smallest standard deviation of a frame's altitude (m), roll or pitch (rad) taken (FRAME_BAD_INPUT
//! beyond): a frame that says nothing, or claims more than any sensor, would leave a covariance whose entries
//! span more than the 16 digits of a double, and the next update's would turn negative (found by
//! fuzz-laser-filter: a roll variance of 2e49 then a frame of 1e-4).
constexpr double kMaxFrameSd = 1e4;
constexpr double kMinFrameSd = 1e-12;

/*!
  Whether a frame's (finite) covariance is one: its diagonal within the standard deviations above, symmetric
  entry by entry to 1e-9 of the scale of its two variances (a norm of the whole matrix overflowed on an
  off-diagonal entry of 1e224 and let it through), and positive definite.
*/
bool plausibleCovariance(const Eigen::Matrix3d &R)
{
  for (int i = 0; i < 3; ++i)
    if (!(R(i, i) >= kMinFrameSd * kMinFrameSd && R(i, i) <= kMaxFrameSd * kMaxFrameSd))
      return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < i; ++j)
      if (!(std::fabs(R(i, j) - R(j, i)) <= 1e-9 * std::sqrt(R(i, i) * R(j, j))))
        return false;
  return R.llt().info() == Eigen::Success;
}
} // namespace

// --- IMU ---------------------------------------------------------------------------------------

vpLaserConicFilter::vpImuStatus vpLaserConicFilter::Impl::addImu(double t, const Eigen::Vector3d &w,
                                                                 const Eigen::Vector3d &f)
{
  if (!std::isfinite(t) || !w.allFinite() || !f.allFinite())
    return IMU_NOT_FINITE;
  // Beyond any IMU's range (MEMS gyros stop at 35-70 rad/s, accelerometers at 16-400 g): a corrupt sample,
  // which the propagation would turn into a state that is not finite (found by fuzz-laser-filter: 2e217 rad/s).
  if (!(w.lpNorm<Eigen::Infinity>() <= kMaxImuRate && f.lpNorm<Eigen::Infinity>() <= kMaxImuForce &&
        std::fabs(t) <= kMaxTime))
    return IMU_OUT_OF_RANGE;
  bool restart = false;
  if (count > 0) {
    // Nothing can bridge a gap: start again from this sample. A sample more than a gap before the last one
    // restarts too: the last was stamped far ahead (a corrupt stamp, which ignoring every later sample as not
    // increasing would follow by a blocked filter until the clock reached it), or the clock was reset.
    const double dt = t - last().t;
    if (!(dt >= kMinImuInterval) && !(dt < -maxGap))
      return IMU_NOT_INCREASING;
    restart = std::fabs(dt) > maxGap;
  }
  if (restart) {
    count = 0;
    clearState();
  }
  // The new sample is written in place (the slot of the oldest one): no copy of the state on the way.
  const size_t previous = newest;
  const bool hasPrevious = count > 0;
  newest = hasPrevious ? (newest + 1) % ring.size() : 0;
  count = std::min(count + 1, ring.size());
  Entry &e = ring[newest];
  const Entry &prev = ring[previous];
  e.t = t;
  e.w = cRimu * w;
  e.f = cRimu * f;
  e.valid = hasPrevious && prev.valid;
  if (e.valid) {
    e.x = prev.x;
    e.P = prev.P;
    propagate(e.x, e.P, 0.5 * (prev.w + e.w), 0.5 * (prev.f + e.f), t - prev.t, gravity, noise);
  }
  return restart ? IMU_GAP : IMU_OK;
}

// --- frames ------------------------------------------------------------------------------------

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::Impl::checkFrameTime(double t) const
{
  if (count == 0 || t > last().t + 1e-9)
    return FRAME_AHEAD_OF_IMU;
  const Entry &oldest = ring[(newest + ring.size() + 1 - count) % ring.size()];
  if (t < last().t - maxLatency || t < oldest.t)
    return FRAME_TOO_OLD;
  if (t < lastFrameTime)
    return FRAME_OUT_OF_ORDER;
  return FRAME_ACCEPTED;
}

void vpLaserConicFilter::Impl::initialise(State &x, Covariance &P, const Eigen::Vector3d &z, const Eigen::Matrix3d &R)
{
  x.setZero();
  x(H) = z(0);
  x(ROLL) = z(1);
  x(PITCH) = z(2);
  P.setZero();
  const int idx[3] = {H, ROLL, PITCH};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      P(idx[i], idx[j]) = R(i, j);
  P(VZ, VZ) = sigmaVz0 * sigmaVz0;
  P.diagonal().segment<3>(BG).setConstant(sigmaBg0 * sigmaBg0);
  P.diagonal().segment<3>(BA).setConstant(sigmaBa0 * sigmaBa0);
  initialised = true;
  diverged = stepPending = false;
  accepted = 1;
  rejectedInRow = tiltedInRow = stepCandidates = 0;
}

namespace
{
//! Whether the attitude part (roll, pitch) of an innovation y of covariance S passes \e gate, a squared
//! Mahalanobis distance (false when that distance is not a number).
bool attitudeWithin(const Eigen::Vector3d &y, const Eigen::Matrix3d &S, double gate)
{
  const Eigen::Vector2d ya = y.tail<2>();
  return ya.dot(S.bottomRightCorner<2, 2>().ldlt().solve(ya)) <= gate;
}
} // namespace

/*!
  A rejected frame is a ground-step candidate when its attitude agrees with the prediction (\e attitudeAgrees),
  its altitude is off by a jump (not by a tail of the noise) and that jump agrees with the previous
  candidate's (the ground moved, the vehicle did not jump).
*/
bool vpLaserConicFilter::Impl::stepCandidate(const Eigen::Vector3d &y, const Eigen::Matrix3d &S, bool attitudeAgrees)
{
  // A step is a jump no noise explains: at least minStepHeight, and twice the gate's distance in altitude.
  const bool large = std::abs(y(0)) >= minStepHeight && y(0) * y(0) >= 4.0 * gate * S(0, 0);
  if (!attitudeAgrees || !large) {
    stepCandidates = 0;
    return false;
  }
  const double d = y(0) - stepOffset;
  const bool sameStep = stepCandidates > 0 && d * d <= gate * (S(0, 0) + stepVariance);
  stepCandidates = sameStep ? stepCandidates + 1 : 1;
  stepOffset = y(0);
  stepVariance = S(0, 0);
  return stepCandidates >= stepFrames;
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::Impl::gateAndUpdate(double t, State &x, Covariance &P,
                                                                          const Eigen::Vector3d &z,
                                                                          const Eigen::Matrix3d &R)
{
  Eigen::Vector3d y;
  Eigen::Matrix3d S;
  lastMahalanobis = innovation(x, P, z, R, y, S);
  if (lastMahalanobis <= gate) {
    update(x, P, y, S, R);
    ++accepted;
    frameUsed(t, false);
    return FRAME_ACCEPTED;
  }
  const bool attitudeAgrees = attitudeWithin(y, S, attitudeGate);
  if (stepCandidate(y, S, attitudeAgrees)) {
    // Re-initialise the altitude: forget what it was (and its correlations), then update normally,
    // so that the altitude takes this frame's value and the attitude still gains from it.
    x(H) = z(0);
    P.row(H).setZero();
    P.col(H).setZero();
    P(H, H) = 1e4 * R(0, 0);
    lastMahalanobis = innovation(x, P, z, R, y, S);
    update(x, P, y, S, R);
    ++stepCount;
    frameUsed(t, true);
    return FRAME_GROUND_STEP;
  }
  // A frame whose attitude disagrees with the gyros' is more likely biased (a ring across a box's edge) than
  // the prediction wrong: such frames declare a divergence only after kTiltedRejections times as many.
  if (attitudeAgrees ? ++rejectedInRow >= maxRejections : ++tiltedInRow >= kTiltedRejections * maxRejections)
    diverged = true;
  return FRAME_REJECTED;
}

/*!
  Whether the diverged filter refuses the frame at \e t (after the k-th sample, \e before) instead of being
  re-initialised by it: its roll and pitch disagree with those the gyros carried on. A ring across a box's
  edge gives GP-3 one plane tilted between the two surfaces, its trace explained within a pixel or two,
  for as long as the edge stays in the ring (2-3 s, 60-90 frames, in the landing tutorial's descent), and a
  divergence declared meanwhile by frames whose altitude alone disagreed was re-initialised by the next
  such plane, tilted by 15 degrees, which the servo then followed. The gyros' attitude stays right over
  such a stretch; the frames' is taken only once kTiltedRejections times setMaxRejections() frames in a
  row have disagreed with it (the filter's own attitude is then in doubt).
*/
bool vpLaserConicFilter::Impl::waitsForAgreeingAttitude(const FrameStart &start, size_t k, double t,
                                                        const Eigen::Vector3d &z, const Eigen::Matrix3d &R)
{
  if (!initialised || !diverged || !start.valid || tiltedInRow >= kTiltedRejections * maxRejections)
    return false;
  State x = start.x;
  Covariance P = start.P;
  propagateFrom(k, start.t, t, x, P);
  Eigen::Vector3d y;
  Eigen::Matrix3d S;
  lastMahalanobis = innovation(x, P, z, R, y, S);
  if (attitudeWithin(y, S, attitudeGate))
    return false;
  ++tiltedInRow;
  lastFrameTime = t;
  return true;
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::Impl::addFrame(double t, const Eigen::Vector3d &z,
                                                                     const Eigen::Matrix3d &R)
{
  const vpFrameStatus timing = checkFrameTime(t);
  if (timing != FRAME_ACCEPTED)
    return timing;
  size_t k = count - 1; // the last sample at or before t
  while (k > 0 && at(k).t > t)
    --k;
  const FrameStart start = frameStart(k, t);
  if (waitsForAgreeingAttitude(start, k, t, z, R))
    return FRAME_REJECTED;
  State x = start.x;
  Covariance P = start.P;
  vpFrameStatus status = FRAME_INITIALISED;
  // Until setInitialisationFrames() frames agree, a frame that disagrees starts the state again: the
  // first frame may be the wrong one.
  const bool confirmed = accepted >= initFrames;
  if (!initialised || diverged || !start.valid) {
    initialise(x, P, z, R);
    lastAcceptTime = t;
    lastMahalanobis = std::numeric_limits<double>::quiet_NaN();
  } else {
    propagateFrom(k, start.t, t, x, P);
    status = gateAndUpdate(t, x, P, z, R);
    if (status == FRAME_REJECTED && !confirmed) {
      initialise(x, P, z, R);
      lastAcceptTime = t;
      status = FRAME_INITIALISED;
    }
  }
  lastFrameTime = t;
  if (status != FRAME_REJECTED) {
    repropagate(k, t, x, P);
    frameSampleTime = at(k).t;
    afterFrame = FrameStart{x, P, t, true};
  }
  return status;
}

//! Replaces the states of the samples after the k-th by those propagated from (x, P) at time t.
void vpLaserConicFilter::Impl::repropagate(size_t k, double t, const State &x, const Covariance &P)
{
  State xs = x;
  Covariance Ps = P;
  double time = t;
  for (size_t j = k + 1; j < count; ++j) {
    const Entry &prev = at(j - 1);
    Entry &e = at(j);
    propagate(xs, Ps, 0.5 * (prev.w + e.w), 0.5 * (prev.f + e.f), e.t - time, gravity, noise);
    time = e.t;
    e.x = xs;
    e.P = Ps;
    e.valid = true;
  }
  if (k + 1 == count) { // the frame is at the last sample's time
    Entry &e = at(k);
    e.x = xs;
    e.P = Ps;
    e.valid = true;
  }
}

vpLaserConicFilter::vpImuStatus vpLaserConicFilter::addImu(double t, const double gyro[3], const double acc[3])
{
  return m_impl->addImu(t, Eigen::Vector3d(gyro[0], gyro[1], gyro[2]), Eigen::Vector3d(acc[0], acc[1], acc[2]));
}

vpLaserConicFilter::vpImuStatus vpLaserConicFilter::addImu(double t, const vpColVector &gyro, const vpColVector &acc)
{
  require(gyro.getRows() == 3 && acc.getRows() == 3,
          "vpLaserConicFilter::addImu: gyro and accelerometer readings must be 3-vectors");
  return addImu(t, gyro.data, acc.data);
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::addFrame(double t, double altitude, double roll, double pitch,
                                                               const vpMatrix &covariance)
{
  Impl &d = *m_impl;
  d.lastMahalanobis = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3d R;
  bool ok = covariance.getRows() == 3 && covariance.getCols() == 3 && std::fabs(t) <= kMaxTime &&
            std::isfinite(altitude) && altitude > 0.0 && vsp::laser_value_check::isGroundAttitude(roll, pitch);
  for (unsigned int i = 0; ok && i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      R(i, j) = covariance[i][j];
  ok = ok && R.allFinite() && plausibleCovariance(R);
  d.lastFrameStatus = ok ? d.addFrame(t, Eigen::Vector3d(altitude, roll, pitch), R) : FRAME_BAD_INPUT;
  return d.lastFrameStatus;
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::addFrame(double t, const vpLaserConicPose &estimator)
{
  if (estimator.getStatus() != vpLaserConicPose::STATUS_OK)
    return addMissingFrame(t);
  return addFrame(t, estimator.getAltitude(), estimator.getRoll(), estimator.getPitch(),
                  estimator.getCovarianceMatrix());
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::addMissingFrame(double t)
{
  Impl &d = *m_impl;
  d.lastMahalanobis = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(t))
    return d.lastFrameStatus = FRAME_BAD_INPUT;
  const vpFrameStatus timing = d.checkFrameTime(t);
  if (timing != FRAME_ACCEPTED)
    return d.lastFrameStatus = timing;
  d.lastFrameTime = t;
  return d.lastFrameStatus = FRAME_MISSING;
}

bool vpLaserConicFilter::isInitialised() const { return m_impl->count > 0 && m_impl->last().valid; }
double vpLaserConicFilter::getTime() const
{
  return m_impl->count > 0 ? m_impl->last().t : std::numeric_limits<double>::quiet_NaN();
}

double vpLaserConicFilter::getAltitude() const { return getState()[H]; }
double vpLaserConicFilter::getVerticalSpeed() const { return getState()[VZ]; }
double vpLaserConicFilter::getRoll() const { return getState()[ROLL]; }
double vpLaserConicFilter::getPitch() const { return getState()[PITCH]; }

vpColVector vpLaserConicFilter::getState() const
{
  vpColVector x(kStateSize, std::numeric_limits<double>::quiet_NaN());
  if (isInitialised())
    for (int i = 0; i < kStateSize; ++i)
      x[i] = m_impl->last().x(i);
  return x;
}

vpMatrix vpLaserConicFilter::getStateCovarianceMatrix() const
{
  vpMatrix P(kStateSize, kStateSize);
  for (int i = 0; i < kStateSize; ++i)
    for (int j = 0; j < kStateSize; ++j)
      P[i][j] = isInitialised() ? m_impl->last().P(i, j) : std::numeric_limits<double>::quiet_NaN();
  return P;
}

vpMatrix vpLaserConicFilter::getCovarianceMatrix() const
{
  const vpMatrix P = getStateCovarianceMatrix();
  vpMatrix C(4, 4);
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      C[i][j] = P[i][j];
  return C;
}

vpLaserConicFilter::vpFilterStatus vpLaserConicFilter::getStatus() const
{
  const Impl &d = *m_impl;
  if (!isInitialised())
    return STATUS_INITIALISING;
  if (d.diverged)
    return STATUS_DIVERGED;
  if (d.stepPending)
    return STATUS_GROUND_STEP;
  if (d.accepted < d.initFrames)
    return STATUS_INITIALISING;
  if (d.last().t - d.lastAcceptTime > d.predictionTimeout)
    return STATUS_PREDICTING;
  return STATUS_TRACKING;
}

vpLaserConicFilter::vpFrameStatus vpLaserConicFilter::getLastFrameStatus() const { return m_impl->lastFrameStatus; }
double vpLaserConicFilter::getLastMahalanobis() const { return m_impl->lastMahalanobis; }
double vpLaserConicFilter::getGateThreshold() const { return m_impl->gate; }
unsigned int vpLaserConicFilter::getGroundStepCount() const { return m_impl->stepCount; }
