/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The per-frame covariance of vpLaserConicPose with the detector in the loop: frames rendered by
// vpLaserConicSimulator (lens distortion, blur, bloom, sensor noise), written and read back as JPEG,
// the trace found by vpLaserConicDetector, the plane by GP-3. Its NEES against the truth tells whether
// the covariance vpLaserConicFilter relies on is honest there, not only on points with independent
// Gaussian noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

namespace
{
//! NEES of each frame's (altitude, roll, pitch) with the covariance scaled by \e inflation.
struct RenderedNees
{
  std::vector<double> nees; //!< with the raw covariance
  int failures = 0;
};

RenderedNees measure(int frames, unsigned int seed, double inflation)
{
  const vpCameraParameters cam(500, 500, 320, 240, -0.06, 0.06);
  const vpHomogeneousMatrix cMl(0.08, 0, 0, 0, vpMath::rad(2), 0);
  vpLaserConicSimulator sim;
  sim.setCamera(cam, 640, 480);
  sim.setLaser(vpMath::rad(34), cMl);
  sim.setSeed(seed);
  vpLaserConicPose pose;
  pose.setCameraParameters(cam);
  pose.setLaser(vpMath::rad(34), cMl);
  pose.setCovarianceComputation(true);
  if (inflation > 0.0)
    pose.setCovarianceInflation(inflation);
  vpLaserConicDetector detector;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // A JPEG round trip through a file of the test's working directory (ctest runs in the build tree).
  const std::string jpeg = "vsp-covariance-" + std::to_string(seed) + ".jpg";
  RenderedNees out;
  for (int k = 0; k < frames; ++k) {
    const double h = 1.05 + 0.75 * u(rng), roll = vpMath::rad(10) * u(rng), pitch = vpMath::rad(10) * u(rng);
    // Ground frame below a camera of that attitude (vpLaserConicPose's convention g = Rx(roll) Ry(pitch) e_z).
    const vpRotationMatrix cRw =
        vpRotationMatrix(vpRxyzVector(roll, 0, 0)) * vpRotationMatrix(vpRxyzVector(0, pitch, 0));
    const vpHomogeneousMatrix cMg(cRw * vpTranslationVector(0.3 * u(rng), 0.3 * u(rng), h), cRw);
    sim.setGroundPose(cMg);
    vpLaserConicSimulator::vpRenderSettings settings;
    settings.blur = 0.8 + 0.4 * std::abs(u(rng));
    settings.bloom = 0.2;
    settings.whiteCore = 0.5;
    vpImage<vpRGBa> I;
    sim.render(I, settings);
    vpImageIo::writeJPEG(I, jpeg, vpImageIo::IO_DEFAULT_BACKEND, 90);
    vpImageIo::read(I, jpeg);
    vpPlane plane;
    const std::vector<vpImagePoint> points = detector.detect(I);
    if (points.size() < 20 || !pose.computePlane(points, vpLaserConicPose::GP3, plane)) {
      ++out.failures;
      continue;
    }
    double hTrue, rollTrue, pitchTrue;
    vpLaserConicPose::computeAltitudeRollPitch(sim.getGroundPlane(), hTrue, rollTrue, pitchTrue);
    const vpMatrix C = pose.getCovarianceMatrix();
    vpColVector e(3);
    e[0] = pose.getAltitude() - hTrue;
    e[1] = pose.getRoll() - rollTrue;
    e[2] = pose.getPitch() - pitchTrue;
    // Solve with a scaled matrix: vpMatrix's inverse refuses determinants as small as these (1e-28).
    vpMatrix Cs = C;
    vpColVector es = e;
    const double scale[3] = {1.0 / std::sqrt(C[0][0]), 1.0 / std::sqrt(C[1][1]), 1.0 / std::sqrt(C[2][2])};
    for (unsigned int i = 0; i < 3; ++i) {
      es[i] *= scale[i];
      for (unsigned int j = 0; j < 3; ++j)
        Cs[i][j] *= scale[i] * scale[j];
    }
    out.nees.push_back(es.t() * Cs.inverseByLU() * es);
  }
  vpIoTools::remove(jpeg);
  return out;
}

double mean(const std::vector<double> &v)
{
  double s = 0.0;
  for (double x : v)
    s += x;
  return v.empty() ? 0.0 : s / v.size();
}
} // namespace

// Measured: the raw first-order covariance gives a mean NEES of 55-64 (median 48-53) over 60-frame sets
// (seeds 101-104: 62.8, 63.8, 55.9, 54.6), twenty times its honest value: the detector's errors are not
// independent along the trace, and its guided pass regularises its centres over 20 px of arc, which
// shrinks the residuals the covariance's scale comes from (before the ring was located by a sample of
// rows, most points were the first pass's, unregularised: 13-17 and an inflation of 5). The pose errors
// themselves fell (RMS over the 60 frames of seed 7: altitude 0.34 -> 0.22 mm, roll 0.045 -> 0.036 deg,
// pitch 0.052 -> 0.041 deg). recommendedDetectorInflation() = 20 was set from those four sets; this
// test checks it on another set (seed 7): mean NEES 3 within its spread over 60 frames of a
// heavy-tailed distribution, [2.2, 4.0] (measured 2.59); the raw covariance stays far outside (above 6).
// Since the regularisation spans 40 px of arc (RidgeTuning::guidedSmoothRadius) the raw NEES is 83.7, 83.9,
// 72.5, 72.5 on seeds 101-104 (medians 62-67) and 68.4 on seed 7: measured 3.42 (median 2.53) with 20.
// Since it spans 80 px: 104.7, 102.2, 87.6, 98.6 on seeds 101-104 (medians 72-86; 86.9, 86.6, 74.1, 81.1 along
// 40 px with the detector of then), recommendedDetectorInflation() = 32 from them (3.27, 3.19, 2.74, 3.08),
// and 86.0 on seed 7: measured 2.69 (median 2.08) with 32.
TEST(LaserConicCovarianceRendered, NeesWithTheDetectorInTheLoop)
{
  const double k = vpLaserConicPose::recommendedDetectorInflation();
  const RenderedNees fixed = measure(60, 7, k); // the raw NEES is k times this one
  ASSERT_GE(fixed.nees.size(), 55u);
  std::vector<double> sorted = fixed.nees;
  std::sort(sorted.begin(), sorted.end());
  std::printf("rendered JPEG frames: mean NEES %.2f (median %.2f) with the raw covariance, %.2f (median %.2f) with "
              "the detector inflation %.1f (3 and 2.37 if honest), %d failures\n",
              k * mean(fixed.nees), k * sorted[sorted.size() / 2], mean(fixed.nees), sorted[sorted.size() / 2], k,
              fixed.failures);
  EXPECT_GT(k * mean(fixed.nees), 6.0);
  EXPECT_GE(mean(fixed.nees), 2.2);
  EXPECT_LE(mean(fixed.nees), 4.0);
  vpLaserConicPose pose;
  EXPECT_THROW(pose.setCovarianceInflation(0.0), vpLaserConicException);
  EXPECT_THROW(pose.setCovarianceInflation(NAN), vpLaserConicException);
}
