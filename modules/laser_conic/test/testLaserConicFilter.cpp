/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpLaserConicFilter on simulated flights: 200 Hz IMU with the ADIS16448 noise densities and bias
// walks, 30 Hz frames 30 ms late, each frame's plane from GP-3 on 120 trace points with 0.5 px noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>

#include <visp3/laser_conic/vpLaserConicFilter.h>

#include "laser_flight_sim.h"

using laser_flight::Flight;
using laser_flight::FrameEvents;
using laser_flight::FrameRecord;
using laser_flight::Sample;

namespace
{
const double kChi2Dof4At95 = 9.4877; // chi-square quantile, 4 degrees of freedom, 95 %
const double kWarmUp = 1.0;          // s: the initial vertical speed and biases settle first

struct Consistency
{
  double neesSum = 0.0;
  int n = 0, inside = 0;
  Eigen::Vector4d perComponent = Eigen::Vector4d::Zero();
  void add(const Sample &s)
  {
    const Eigen::Vector4d e = laser_flight::error(s);
    for (int i = 0; i < 4; ++i)
      perComponent(i) += e(i) * e(i) / s.P(i, i);
    const double nees = e.dot(s.P.ldlt().solve(e));
    neesSum += nees;
    inside += nees <= kChi2Dof4At95;
    ++n;
  }
};
//! One simulated flight through a new filter (laser_flight::fly()): the filter, its IMU-rate outputs and frames.
struct FlightRun
{
  vpLaserConicFilter filter;
  std::vector<Sample> samples;
  std::vector<FrameRecord> frames;
  FlightRun(const Flight &flight, double duration, unsigned int seed, const FrameEvents &events = FrameEvents())
  {
    laser_flight::fly(flight, duration, seed, filter, samples, frames, events);
  }
};
} // namespace

// Over Monte Carlo flights the normalised error of (altitude, vertical speed, roll, pitch) at IMU rate
// is chi-square with 4 degrees of freedom when the covariance is right: mean 4 and 95 % of the samples
// under its 95 % quantile. Samples of one flight are correlated in time, so the mean over 8 flights of
// 7 s carries a few per cent of spread: [0.8, 1.25] x 4 and [0.90, 0.98] fail a covariance off by 25 %.
TEST(LaserConicFilter, CovarianceIsConsistentOverFlights)
{
  Consistency c;
  for (unsigned int run = 0; run < 8; ++run) {
    const FlightRun flown(Flight(100 + run), 8.0, 200 + run);
    for (const Sample &s : flown.samples)
      if (s.t > kWarmUp)
        c.add(s);
  }
  ASSERT_GT(c.n, 10000);
  const double meanNees = c.neesSum / c.n, coverage = double(c.inside) / c.n;
  std::printf("filter NEES mean %.3f (state dimension 4), 95 %% coverage %.3f over %d samples; per output "
              "(altitude, vertical speed, roll, pitch) %.2f %.2f %.2f %.2f\n",
              meanNees, coverage, c.n, c.perComponent(0) / c.n, c.perComponent(1) / c.n, c.perComponent(2) / c.n,
              c.perComponent(3) / c.n);
  EXPECT_GE(meanNees, 0.8 * 4);
  EXPECT_LE(meanNees, 1.25 * 4);
  EXPECT_GE(coverage, 0.90);
  EXPECT_LE(coverage, 0.98);
}

// The IMU carries the altitude between frames and averages the frames' noise: its error at IMU rate
// is at most 0.7 times the per-frame GP-3 error at the frame times.
TEST(LaserConicFilter, AltitudeBeatsPerFrameEstimate)
{
  double filterSq = 0.0, frameSq = 0.0;
  int nf = 0, ns = 0;
  for (unsigned int run = 0; run < 3; ++run) {
    const FlightRun flown(Flight(300 + run), 8.0, 400 + run);
    for (const Sample &s : flown.samples)
      if (s.t > kWarmUp) {
        filterSq += (s.x(0) - s.truth.h) * (s.x(0) - s.truth.h);
        ++ns;
      }
    for (const FrameRecord &f : flown.frames)
      if (f.hasPlane && f.t > kWarmUp) {
        frameSq += (f.h - f.hTrue) * (f.h - f.hTrue);
        ++nf;
      }
  }
  const double ratio = std::sqrt(filterSq / ns) / std::sqrt(frameSq / nf);
  std::printf("altitude RMS: filter %.3f mm at 200 Hz, per-frame GP-3 %.3f mm at 30 Hz, ratio %.3f\n",
              1e3 * std::sqrt(filterSq / ns), 1e3 * std::sqrt(frameSq / nf), ratio);
  EXPECT_LE(ratio, 0.7);
}

// Half a second without any plane: the prediction runs on, its covariance grows, and the altitude
// error stays inside 3 sigma; the status says so; the first frame after it is accepted.
TEST(LaserConicFilter, DropoutKeepsErrorInsideThreeSigma)
{
  for (unsigned int run = 0; run < 4; ++run) {
    FrameEvents events;
    events.dropFrom = 3.0;
    events.dropTo = 3.5;
    const FlightRun flown(Flight(500 + run), 5.0, 600 + run, events);
    double sigmaBefore = 0.0, sigmaEnd = 0.0;
    int predicting = 0;
    for (const Sample &s : flown.samples) {
      if (s.t < events.dropFrom || s.t > events.dropTo + 0.03)
        continue;
      const double sigma = std::sqrt(s.P(0, 0));
      EXPECT_LE(std::abs(s.x(0) - s.truth.h), 3.0 * sigma) << "t = " << s.t;
      predicting += s.status == vpLaserConicFilter::STATUS_PREDICTING;
      (sigmaBefore == 0.0 ? sigmaBefore : sigmaEnd) = sigma;
    }
    EXPECT_GT(sigmaEnd, sigmaBefore);
    EXPECT_GT(predicting, 50); // 0.4 s of 0.5 s at 200 Hz after the 0.1 s timeout
    for (const FrameRecord &f : flown.frames)
      if (f.t >= events.dropTo && f.t < events.dropTo + 0.05) {
        EXPECT_EQ(f.status, vpLaserConicFilter::FRAME_ACCEPTED);
      }
  }
}

// A frame whose plane is off by 5 sigma of the innovation is gated out (99 % gate: distance² 11.34)
// in at least 99 % of the cases, and the filter goes on tracking.
TEST(LaserConicFilter, RejectsFiveSigmaOutliers)
{
  int outliers = 0, rejected = 0;
  for (unsigned int run = 0; run < 6; ++run) {
    FrameEvents events;
    for (int k = 40; k < 240; k += 7)
      events.outlierFrames.push_back(k);
    const FlightRun flown(Flight(700 + run), 8.0, 800 + run, events);
    const std::vector<FrameRecord> &frames = flown.frames;
    for (size_t i = 0; i < frames.size(); ++i)
      for (int o : events.outlierFrames)
        if (static_cast<int>(i) == o && frames[i].hasPlane) {
          ++outliers;
          rejected += frames[i].status == vpLaserConicFilter::FRAME_REJECTED;
        }
    EXPECT_EQ(flown.filter.getGroundStepCount(), 0u);
    EXPECT_EQ(flown.filter.getStatus(), vpLaserConicFilter::STATUS_TRACKING);
  }
  std::printf("5-sigma outliers rejected: %d of %d\n", rejected, outliers);
  ASSERT_GT(outliers, 150);
  EXPECT_GE(rejected, 0.99 * outliers);
}

// Flying onto a 20 cm box: the altitude drops by 0.2 m at once. The filter detects the step within 3
// frames (two consistent rejected frames) and re-initialises the altitude: from 0.1 s later its error
// stays under 5 mm (no transient: the step is 200 mm) and inside 3 sigma in 95 % of the samples, as
// before the step; no other step is reported.
TEST(LaserConicFilter, DetectsGroundStepWithinThreeFrames)
{
  int allAfter = 0, allInside = 0; // samples of one flight are correlated: the fraction is over all flights
  for (unsigned int run = 0; run < 6; ++run) {
    Flight flight(900 + run);
    flight.stepTime = 3.01 + 0.005 * run;
    const FlightRun flown(flight, 5.0, 1000 + run);
    const std::vector<FrameRecord> &frames = flown.frames;
    int first = -1, detected = -1;
    for (size_t i = 0; i < frames.size(); ++i) {
      if (first < 0 && frames[i].t >= flight.stepTime)
        first = static_cast<int>(i);
      if (detected < 0 && frames[i].status == vpLaserConicFilter::FRAME_GROUND_STEP)
        detected = static_cast<int>(i);
    }
    ASSERT_GE(detected, first) << "run " << run;
    EXPECT_LE(detected - first, 2) << "run " << run;
    EXPECT_EQ(flown.filter.getGroundStepCount(), 1u);
    // After the step no transient: the error stays at the noise level (a few sigma, never a part of the
    // 20 cm step) and inside 3 sigma as often as before it.
    const double settled = frames[detected].t + 0.1 + 0.03;
    int after = 0, inside = 0;
    for (const Sample &s : flown.samples)
      if (s.t > settled) {
        ++after;
        inside += std::abs(s.x(0) - s.truth.h) <= 3.0 * std::sqrt(s.P(0, 0));
        EXPECT_LE(std::abs(s.x(0) - s.truth.h), 0.005) << "t = " << s.t;
      }
    allAfter += after;
    allInside += inside;
    EXPECT_EQ(flown.filter.getStatus(), vpLaserConicFilter::STATUS_TRACKING);
  }
  std::printf("after the step: altitude inside 3 sigma in %d of %d samples\n", allInside, allAfter);
  EXPECT_GE(allInside, 0.95 * allAfter);
}

// A ring across a box's edge: for 2.5 s (75 frames, more than setMaxRejections()' 30) every plane is 12 cm
// low and tilted by 15 degrees (GP-3's one plane between the box and the floor). The filter rejects them
// and carries its attitude on the gyros: its pitch stays within a degree of the truth, it never declares a
// divergence (the landing tutorial's servo followed the 15 degrees when a divergence was re-initialised by
// such a frame), and the first frames after the edge are accepted: 0.1 s later its altitude is within 5 mm.
TEST(LaserConicFilter, PlanesTiltedByABoxEdgeDoNotTakeTheAttitude)
{
  for (unsigned int run = 0; run < 4; ++run) {
    FrameEvents events;
    events.tiltedFrom = 2.0;
    events.tiltedTo = 4.5;
    events.tiltedAltitude = -0.12;
    events.tiltedPitch = vpMath::rad(15.0);
    const FlightRun flown(Flight(1100 + run), 6.0, 1200 + run, events);
    int tilted = 0, rejected = 0;
    for (const FrameRecord &f : flown.frames)
      if (f.hasPlane && f.t >= events.tiltedFrom && f.t < events.tiltedTo) {
        ++tilted;
        rejected += f.status == vpLaserConicFilter::FRAME_REJECTED;
      }
    EXPECT_GT(tilted, 60) << "run " << run;
    EXPECT_EQ(rejected, tilted) << "run " << run;
    double worstPitch = 0.0, worstAltitudeAfter = 0.0;
    int diverged = 0;
    for (const Sample &s : flown.samples) {
      diverged += s.status == vpLaserConicFilter::STATUS_DIVERGED;
      if (s.t > kWarmUp)
        worstPitch = std::max(worstPitch, std::abs(laser_flight::error(s)(3)));
      if (s.t > events.tiltedTo + 0.1 + 0.03)
        worstAltitudeAfter = std::max(worstAltitudeAfter, std::abs(s.x(0) - s.truth.h));
    }
    std::printf("run %u: %d tilted planes, %d rejected, worst pitch error after the warm-up %.3f deg, worst altitude "
                "error from 0.1 s after them %.2f mm\n",
                run, tilted, rejected, vpMath::deg(worstPitch), 1e3 * worstAltitudeAfter);
    EXPECT_EQ(diverged, 0) << "run " << run << ": IMU samples with STATUS_DIVERGED";
    EXPECT_LE(worstPitch, vpMath::rad(1.0)) << "run " << run;
    EXPECT_LE(worstAltitudeAfter, 0.005) << "run " << run;
    EXPECT_EQ(flown.filter.getStatus(), vpLaserConicFilter::STATUS_TRACKING) << "run " << run;
  }
}

// The other way round: from 2 s on every plane is tilted by 10 degrees and stays so (the filter's attitude,
// not the frames', is what is wrong). After five times setMaxRejections() frames disagreeing in a row (5 s)
// the filter declares the divergence and the next frame re-initialises it: from then on it follows the frames.
TEST(LaserConicFilter, FramesThatKeepDisagreeingOnTheAttitudeReinitialiseIt)
{
  FrameEvents events;
  events.tiltedFrom = 2.0;
  events.tiltedTo = 100.0;
  events.tiltedPitch = vpMath::rad(10.0);
  const FlightRun flown(Flight(1300), 9.0, 1400, events);
  double reinitialised = -1.0;
  for (const FrameRecord &f : flown.frames)
    if (reinitialised < 0.0 && f.t > events.tiltedFrom && f.status == vpLaserConicFilter::FRAME_INITIALISED)
      reinitialised = f.t;
  std::printf("re-initialised by the frame at %.3f s\n", reinitialised);
  EXPECT_GE(reinitialised, events.tiltedFrom + 4.9);
  EXPECT_LE(reinitialised, events.tiltedFrom + 5.3);
  const Sample &last = flown.samples.back();
  EXPECT_NEAR(last.x(3), last.truth.pitch + events.tiltedPitch, vpMath::rad(0.5));
  EXPECT_EQ(flown.filter.getStatus(), vpLaserConicFilter::STATUS_TRACKING);
}

// Bad input never crashes, names what is wrong and keeps the earlier estimate.
TEST(LaserConicFilter, BadInputHasAStatus)
{
  vpLaserConicFilter filter;
  const double w[3] = {0, 0, 0}, f[3] = {0, 0, -9.80665}, nanv[3] = {NAN, 0, 0};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-6;
  EXPECT_EQ(filter.addFrame(0.0, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_AHEAD_OF_IMU);
  EXPECT_EQ(filter.addImu(0.0, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addImu(0.005, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addFrame(0.005, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_INITIALISED);
  EXPECT_EQ(filter.addImu(0.010, nanv, f), vpLaserConicFilter::IMU_NOT_FINITE);
  EXPECT_EQ(filter.addImu(0.005, w, f), vpLaserConicFilter::IMU_NOT_INCREASING);
  EXPECT_EQ(filter.addImu(0.010, w, f), vpLaserConicFilter::IMU_OK);
  const double altitude = filter.getAltitude();
  EXPECT_NEAR(altitude, 1.0, 1e-6);
  EXPECT_EQ(filter.addFrame(0.002, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_OUT_OF_ORDER);
  EXPECT_EQ(filter.addFrame(0.020, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_AHEAD_OF_IMU);
  EXPECT_EQ(filter.addFrame(0.010, NAN, 0.0, 0.0, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_EQ(filter.addFrame(0.010, -1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  vpMatrix notPd(3, 3);
  notPd.eye();
  notPd[2][2] = -1.0;
  EXPECT_EQ(filter.addFrame(0.010, 1.0, 0.0, 0.0, notPd), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_EQ(filter.addFrame(0.010, 1.0, 0.0, 0.0, vpMatrix(2, 2)), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_EQ(filter.getAltitude(), altitude); // nothing above changed the estimate
  for (int k = 3; k < 40; ++k)
    filter.addImu(0.005 * k, w, f);
  EXPECT_EQ(filter.addFrame(0.010, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_TOO_OLD);
  EXPECT_EQ(filter.addImu(1.0, w, f), vpLaserConicFilter::IMU_GAP);
  EXPECT_FALSE(filter.isInitialised());
  EXPECT_TRUE(std::isnan(filter.getAltitude()));
  EXPECT_THROW(filter.setGateProbability(1.0), vpLaserConicException);
  EXPECT_THROW(filter.setImuNoise(0.0, 1, 1, 1), vpLaserConicException);
  EXPECT_THROW(filter.setMaxLatency(-1.0), vpLaserConicException);
  EXPECT_THROW(filter.setMaxLatency(0.1, 1000001), vpLaserConicException); // a mistake: over 1 GB of history
  EXPECT_THROW(filter.addImu(0.0, vpColVector(2), vpColVector(3)), vpLaserConicException);
  EXPECT_THROW(vpLaserConicFilter::loadImuCsv("/nonexistent/imu.csv"), vpLaserConicException);
  // A non-finite reading is refused at its line as one (it was "a field is not a number").
  const std::string nanFile = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/vsp_imu_nan.csv";
  {
    std::ofstream out(nanFile.c_str());
    out << "1,0,0,0,0,0,9.8\n2,0,0,nan,0,0,9.8\n";
  }
  try {
    vpLaserConicFilter::loadImuCsv(nanFile, 1.0);
    ADD_FAILURE() << "a NaN reading was read";
  } catch (const vpLaserConicException &e) {
    EXPECT_NE(e.getStringMessage().find("vsp_imu_nan.csv:2: non-finite"), std::string::npos) << e.getStringMessage();
  }
  EXPECT_FALSE(vpLaserConicFilter::getFrameStatusMessage(vpLaserConicFilter::FRAME_TOO_OLD).empty());
}

// A roll or pitch outside (-pi/2, pi/2) is no ground in front of the camera (an estimate never gives one): most often
// degrees given as radians. It initialised the filter (pitch 10 rad: a state 573 degrees off) and updated it.
TEST(LaserConicFilter, AnAttitudeOutsideAQuarterTurnIsBadInput)
{
  vpLaserConicFilter filter;
  const double w[3] = {0, 0, 0}, f[3] = {0, 0, -9.80665};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-6;
  EXPECT_EQ(filter.addImu(0.0, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addImu(0.005, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addFrame(0.001, 1.0, 0.0, 10.0, C), vpLaserConicFilter::FRAME_BAD_INPUT); // 10 degrees?
  EXPECT_EQ(filter.addFrame(0.002, 1.0, -2.0, 0.0, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_EQ(filter.addFrame(0.003, 1.0, 0.0, M_PI_2, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_FALSE(filter.isInitialised());
  EXPECT_EQ(filter.addFrame(0.004, 1.0, 0.2, -0.3, C), vpLaserConicFilter::FRAME_INITIALISED);
  EXPECT_NEAR(filter.getPitch(), -0.3, 1e-3);
  EXPECT_EQ(filter.addFrame(0.005, 1.0, 0.2, 1.6, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_NEAR(filter.getPitch(), -0.3, 1e-3);
  // The status's message names the likely mistake.
  EXPECT_NE(
      vpLaserConicFilter::getFrameStatusMessage(vpLaserConicFilter::FRAME_BAD_INPUT).find("degrees given as radians"),
      std::string::npos);
}

// Finite values that no sensor gives, each found by the fuzz target fuzz-laser-filter to leave a state or a
// covariance that is not finite (or a negative variance): a gyro rate of 2e217 rad/s, times in nanoseconds given
// as seconds (a frame a unit in the last place after a sample propagated the state over 256 s and more), a
// frame's variance of 2e49 followed by one of 1e-4 (the update's covariance turned negative), an off-diagonal
// entry of 1e224 (the symmetry test's norm overflowed), and noise densities or gaps of 1e300. Each now has a
// status or an exception, and the filter fed right afterwards stays finite.
TEST(LaserConicFilter, ValuesNoSensorGivesHaveAStatus)
{
  vpLaserConicFilter filter;
  const double w[3] = {0, 0, 0}, f[3] = {0, 0, -9.80665}, spinning[3] = {2e217, 0, 0}, crushing[3] = {0, 0, -1e5};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-4;
  EXPECT_EQ(filter.addImu(0.0, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addImu(0.005, spinning, f), vpLaserConicFilter::IMU_OUT_OF_RANGE);
  EXPECT_EQ(filter.addImu(0.005, w, crushing), vpLaserConicFilter::IMU_OUT_OF_RANGE);
  EXPECT_EQ(filter.addImu(1.7e18, w, f), vpLaserConicFilter::IMU_OUT_OF_RANGE);
  EXPECT_EQ(filter.addImu(0.005, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addFrame(1.7e18, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_BAD_INPUT);
  vpMatrix saysNothing = C;
  saysNothing[1][1] = 2e49;
  EXPECT_EQ(filter.addFrame(0.005, 1.0, 0.0, 0.0, saysNothing), vpLaserConicFilter::FRAME_BAD_INPUT);
  vpMatrix lopsided = C;
  lopsided[0][1] = 1e224;
  EXPECT_EQ(filter.addFrame(0.005, 1.0, 0.0, 0.0, lopsided), vpLaserConicFilter::FRAME_BAD_INPUT);
  EXPECT_EQ(filter.addFrame(0.005, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_INITIALISED);
  for (int k = 2; k < 20; ++k)
    EXPECT_EQ(filter.addImu(0.005 * k, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addFrame(0.09, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_ACCEPTED);
  const vpColVector x = filter.getState();
  const vpMatrix P = filter.getStateCovarianceMatrix();
  for (unsigned int i = 0; i < x.size(); ++i) {
    EXPECT_TRUE(std::isfinite(x[i])) << "state " << i;
    EXPECT_TRUE(std::isfinite(P[i][i]) && P[i][i] >= 0.0) << "variance " << i << ": " << P[i][i];
  }
  EXPECT_NEAR(filter.getAltitude(), 1.0, 1e-3);
  EXPECT_THROW(filter.setImuNoise(1e300, 1e-5, 1e-3, 1e-3), vpLaserConicException);
  EXPECT_THROW(filter.setInitialUncertainty(1e300, 0.01, 0.2), vpLaserConicException);
  EXPECT_THROW(filter.setMaxImuGap(1e300), vpLaserConicException);
  EXPECT_THROW(filter.setGravityNorm(1e300), vpLaserConicException);
  EXPECT_FALSE(vpLaserConicFilter::getImuStatusMessage(vpLaserConicFilter::IMU_OUT_OF_RANGE).empty());
}

// A rotation refused by setImuToCameraRotation() leaves the one set before it: the filter fed afterwards gives
// exactly what a filter that never saw the refused matrix gives (a tilted mounting, so that the rotation
// matters to every output).
TEST(LaserConicFilter, ARefusedImuRotationLeavesTheMountingUnchanged)
{
  const vpRotationMatrix cRimu(vpRxyzVector(0.2, -0.1, 0.3));
  vpLaserConicFilter kept, refused;
  kept.setImuToCameraRotation(cRimu);
  refused.setImuToCameraRotation(cRimu);
  vpRotationMatrix notFinite = cRimu, scaled = cRimu;
  notFinite[1][2] = std::numeric_limits<double>::quiet_NaN();
  for (unsigned int i = 0; i < 3; ++i)
    scaled[i][0] *= 2.0;
  EXPECT_THROW(refused.setImuToCameraRotation(notFinite), vpLaserConicException);
  EXPECT_THROW(refused.setImuToCameraRotation(scaled), vpLaserConicException);
  // A mirrored axis: orthogonal, determinant -1 (taken before: a roll at +0.5 rad/s read as -0.5).
  vpRotationMatrix mirrored = cRimu;
  for (unsigned int i = 0; i < 3; ++i)
    mirrored[i][2] = -mirrored[i][2];
  EXPECT_THROW(refused.setImuToCameraRotation(mirrored), vpLaserConicException);

  // At rest, the camera looking straight down: the specific force, 9.81 up (-Z of the camera), read in the IMU's
  // frame.
  const vpColVector up = cRimu.t() * vpColVector({0.0, 0.0, -9.80665});
  const double w[3] = {0.01, -0.02, 0.005}, f[3] = {up[0], up[1], up[2]};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-6;
  for (vpLaserConicFilter *filter : {&kept, &refused}) {
    for (int k = 0; k <= 2; ++k)
      filter->addImu(0.005 * k, w, f);
    ASSERT_EQ(filter->addFrame(0.005, 1.0, 0.0, 0.0, C), vpLaserConicFilter::FRAME_INITIALISED);
    for (int k = 3; k <= 40; ++k)
      filter->addImu(0.005 * k, w, f);
  }
  ASSERT_TRUE(std::isfinite(kept.getRoll()));
  EXPECT_EQ(refused.getAltitude(), kept.getAltitude());
  EXPECT_EQ(refused.getRoll(), kept.getRoll());
  EXPECT_EQ(refused.getPitch(), kept.getPitch());
  EXPECT_EQ(refused.getVerticalSpeed(), kept.getVerticalSpeed());
}

namespace
{
//! Feeds \e filter at rest (IMU every 5 ms up to 80 ms, the camera looking down), initialised by a frame at 1 m at 0.
void startAtRest(vpLaserConicFilter &filter)
{
  filter.setInitialisationFrames(1);
  const double w[3] = {0.0, 0.0, 0.0}, f[3] = {0.0, 0.0, -9.80665};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-4;
  filter.addImu(0.0, w, f);
  filter.addFrame(0.0, 1.0, 0.0, 0.0, C);
  for (int k = 1; k <= 16; ++k)
    filter.addImu(0.005 * k, w, f);
}
} // namespace

// Frames between the same two IMU samples (a camera faster than the IMU, an IMU dropout, a frame given twice):
// the update of the first was kept in the samples after it but not in the one before, from which the second
// started again: the first was lost (both returned FRAME_ACCEPTED; altitude and variance were those of the
// second alone, to the last bit).
TEST(LaserConicFilter, FramesBetweenTheSameTwoImuSamplesAreEachApplied)
{
  vpMatrix C(3, 3), half(3, 3);
  C.eye();
  C *= 1e-4; // 1 cm, 10 mrad
  half = 0.5 * C;
  // The same frame twice at 31.2 ms (between the samples at 30 and 35 ms) is one frame of half the variance: the
  // information of a linear measurement adds up.
  vpLaserConicFilter twice, once;
  startAtRest(twice);
  startAtRest(once);
  EXPECT_EQ(twice.addFrame(0.0312, 1.02, 0.0, 0.0, C), vpLaserConicFilter::FRAME_ACCEPTED);
  EXPECT_EQ(twice.addFrame(0.0312, 1.02, 0.0, 0.0, C), vpLaserConicFilter::FRAME_ACCEPTED);
  EXPECT_EQ(once.addFrame(0.0312, 1.02, 0.0, 0.0, half), vpLaserConicFilter::FRAME_ACCEPTED);
  EXPECT_NEAR(twice.getAltitude(), once.getAltitude(), 1e-12);
  EXPECT_NEAR(twice.getCovarianceMatrix()[0][0], once.getCovarianceMatrix()[0][0], 1e-12);
  // Two frames at 30.0 and 32.0 ms: the altitude's variance falls below what the second alone leaves.
  vpLaserConicFilter both, second;
  startAtRest(both);
  startAtRest(second);
  both.addFrame(0.0300, 1.02, 0.0, 0.0, C);
  both.addFrame(0.0320, 1.02, 0.0, 0.0, C);
  second.addFrame(0.0320, 1.02, 0.0, 0.0, C);
  std::cout << "altitude variance: both frames " << both.getCovarianceMatrix()[0][0] << ", the second alone "
            << second.getCovarianceMatrix()[0][0] << std::endl;
  EXPECT_LT(both.getCovarianceMatrix()[0][0], 0.8 * second.getCovarianceMatrix()[0][0]);
}

// An IMU sample less than a microsecond after the previous one is a duplicate: its interval's process noise (the
// density over the interval) overflowed, and the covariance became NaN while addImu() returned IMU_OK.
TEST(LaserConicFilter, AnImuSampleAMicrosecondAfterTheLastIsRefused)
{
  vpLaserConicFilter filter;
  startAtRest(filter);
  const double w[3] = {0.0, 0.0, 0.0}, f[3] = {0.0, 0.0, -9.80665};
  EXPECT_EQ(filter.addImu(0.080 + 1e-9, w, f), vpLaserConicFilter::IMU_NOT_INCREASING);
  EXPECT_EQ(filter.addImu(0.085, w, f), vpLaserConicFilter::IMU_OK);
  const vpMatrix P = filter.getCovarianceMatrix();
  for (unsigned int i = 0; i < P.getRows(); ++i)
    EXPECT_TRUE(std::isfinite(P[i][i]) && P[i][i] > 0.0) << i;
  vpLaserConicFilter atZero;
  atZero.addImu(0.0, w, f);
  EXPECT_EQ(atZero.addImu(std::numeric_limits<double>::denorm_min(), w, f), vpLaserConicFilter::IMU_NOT_INCREASING);
}

// One IMU sample stamped far ahead (a corrupt timestamp, a clock that jumped) restarted the filter there, and every
// sample after it, back on the true clock, was IMU_NOT_INCREASING: the filter stayed blocked until the true clock
// reached the bad stamp (here 1000 s). A sample more than the largest gap before the last one restarts it too.
TEST(LaserConicFilter, AnImuSampleStampedFarAheadDoesNotBlockTheFilter)
{
  vpLaserConicFilter filter;
  startAtRest(filter);
  const double w[3] = {0.0, 0.0, 0.0}, f[3] = {0.0, 0.0, -9.80665};
  vpMatrix C(3, 3);
  C.eye();
  C *= 1e-4;
  EXPECT_EQ(filter.addImu(1000.0, w, f), vpLaserConicFilter::IMU_GAP);
  EXPECT_EQ(filter.addImu(0.085, w, f), vpLaserConicFilter::IMU_GAP); // the stream again: restarted from it
  EXPECT_EQ(filter.addImu(0.090, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_EQ(filter.addFrame(0.090, 1.2, 0.0, 0.0, C), vpLaserConicFilter::FRAME_INITIALISED);
  EXPECT_EQ(filter.addImu(0.095, w, f), vpLaserConicFilter::IMU_OK);
  EXPECT_NEAR(filter.getAltitude(), 1.2, 1e-6);
  // A sample a little late (within the largest gap) is still ignored, the state kept.
  EXPECT_EQ(filter.addImu(0.060, w, f), vpLaserConicFilter::IMU_NOT_INCREASING);
  EXPECT_TRUE(filter.isInitialised());
}

// The simulated IMU refuses what would make every reading NaN or its noise imaginary.
TEST(LaserConicFilter, ImuSimulatorRefusesBadNoiseAndTimeSteps)
{
  vpLaserConicImuSimulator imu;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(imu.setNoise(1e-4, -1e-5, 2e-3, 3e-3), vpLaserConicException);
  EXPECT_THROW(imu.setNoise(1e-4, 1e-5, nan, 3e-3), vpLaserConicException);
  EXPECT_THROW(imu.drawInitialBias(nan, 0.05), vpLaserConicException);
  EXPECT_THROW(imu.drawInitialBias(0.005, -0.05), vpLaserConicException);
  const double w[3] = {0, 0, 0}, f[3] = {0, 0, -9.80665};
  double gyro[3], acc[3];
  EXPECT_THROW(imu.measure(0.0, w, f, gyro, acc), vpLaserConicException);
  EXPECT_NO_THROW(imu.drawInitialBias(0.0, 0.0));
  imu.setNoise(0.0, 0.0, 0.0, 0.0);
  imu.measure(0.005, w, f, gyro, acc); // noiseless and unbiased: the truth
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(gyro[i], w[i]);
    EXPECT_EQ(acc[i], f[i]);
  }
}

// The latency is handled exactly: frames delivered 30 ms late give the same state as frames delivered
// at once (the history is re-propagated, not approximated).
TEST(LaserConicFilter, LatencyIsExact)
{
  vpLaserConicFilter late, onTime;
  std::vector<Sample> sLate, sOnTime;
  std::vector<FrameRecord> fLate, fOnTime;
  laser_flight::fly(Flight(11), 2.0, 12, late, sLate, fLate, FrameEvents(), 200.0, 30.0, 0.03);
  FrameEvents undelivered; // the late run has not received the frames of its last 30 ms yet
  undelivered.dropFrom = 2.0 - 0.03;
  undelivered.dropTo = 10.0;
  laser_flight::fly(Flight(11), 2.0, 12, onTime, sOnTime, fOnTime, undelivered, 200.0, 30.0, 0.0);
  const vpColVector a = late.getState(), b = onTime.getState();
  for (unsigned int i = 0; i < a.getRows(); ++i)
    EXPECT_NEAR(a[i], b[i], 1e-9 * (1.0 + std::abs(b[i]))) << i;
}
