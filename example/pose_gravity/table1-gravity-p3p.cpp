/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \example table1-gravity-p3p.cpp

  Reproduction of Table I of D'Alfonso, Garone, Muraca, Pugliese, "P3P and P2P problems with known
  camera and object vertical directions" (MED 2013), Section VI: percentage of trials whose relative
  reprojection error is under 0.02 / 0.05 / 0.15 / 0.3, and its mean, for

  - P3P_IMU         vpPoseGravity::computePose(vpPoseGravity::P3P) on A, B, C with both noisy gravities;
  - P3P_IMU_REFINED the P3P_IMU pose refined by vpPoseGravity::refinePose() over A, B, C with the two
                    gravity measurements as priors (all 6 DOF, sigma_g = 0.01, sigma_img = 2 px / f);
  - P3P_NM          the paper's baseline: full rotation from the two IMUs plus a compass heading, then the
                    translation of eq. 14 for each pair (A,B), (B,C), (C,A), averaged (implemented here);
  - P4P             classical image-only pose on the four coplanar points A, B, C, D: OpenCV
                    cv::solvePnP(SOLVEPNP_IPPE);
  - P4P_VISP        extra row: ViSP vpPose::computePose(DEMENTHON_VIRTUAL_VS) on the same four points.

  Usage: table1-gravity-p3p [--trials N] [--seed S] [--camera vga|uxga] [--reference true|measured] [--check]

  Protocol choices (the paper leaves them open; each is stated where it is implemented):
  - camera: 640 x 480 pinhole without distortion, px = py = 800 (about 44 x 33 degrees field of view),
    principal point (320, 240); --camera uxga: 1600 x 1200, px = py = 2000, same field of view;
  - the 5 m cube: x, y in [-2.5, 2.5] m around the optical axis, depth z in [0.5, 5.5] m;
  - a trial is redrawn until the four points are in front of the camera and inside the image;
  - the relative error divides by the norm of the pixel coordinates measured from the image corner
    (the paper's eq. with + x_CI), against the noise-free projection by default.
*/
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>
#include <visp3/vision/vpPose.h>

#include "vpCommandLine.h"
#include "vpProgress.h"

namespace
{
// ---- Experiment constants (paper Sec. VI unless stated otherwise) --------------------------------

//! A distortion-free pinhole camera with its principal point at the image centre.
struct CameraModel
{
  const char *name;
  double width, height; //!< image size, pixels
  double focal;         //!< px = py, pixels
  double u0() const { return 0.5 * width; }
  double v0() const { return 0.5 * height; }
};

// The paper gives no camera. Its error index is relative to the pixel coordinates, so the image size sets
// the scale of the denominator while the noise stays 2 px: the default is a common VGA sensor with a
// moderate lens (about 44 x 33 degrees field of view); "uxga" is a 1600 x 1200 sensor with the same field
// of view, to show how much the numbers depend on that choice.
const CameraModel kCameraVga = {"vga", 640.0, 480.0, 800.0};
const CameraModel kCameraUxga = {"uxga", 1600.0, 1200.0, 2000.0};

// The object is placed "randomly in a cube with a side of 5 m": we centre the cube laterally on the
// optical axis and start it 0.5 m in front of the camera, closer than that the 10 cm target would
// rarely be seen whole.
constexpr double kCubeSide = 5.0;
constexpr double kCubeNearDepth = 0.5;

// Noise (paper Sec. VI).
constexpr double kSigmaGravity = 0.01; // added to each component of the unit gravity, then renormalised
constexpr double kSigmaPixel = 2.0;    // on each image coordinate, in pixels
const double kSigmaCompass = vpMath::rad(4.0);

// Thresholds of Table I.
const std::array<double, 4> kThresholds = {0.02, 0.05, 0.15, 0.3};

// Published Table I, for the comparison printed with the results.
struct PublishedRow
{
  const char *name;
  const char *values;
};
const std::array<PublishedRow, 3> kPublished = {{{"P3P_IMU", "93 / 99 / 100 / 100 %, mean 0.008"},
                                                 {"P3P_NM", "92 / 98 / 99 / 100 %, mean 0.012"},
                                                 {"P4P", "56 / 81 / 95 / 98 %, mean 0.045"}}};

constexpr int kNumFeaturePoints = 4;
const std::array<Eigen::Vector3d, kNumFeaturePoints> kFeature = {
    Eigen::Vector3d(0.0, 0.0, 0.0),  // A
    Eigen::Vector3d(0.1, 0.1, 0.0),  // B
    Eigen::Vector3d(0.1, 0.0, 0.0),  // C
    Eigen::Vector3d(0.0, 0.1, 0.0)}; // D (used by P4P only, and by every error index)

// ---- Command line ------------------------------------------------------------------------------

struct Options
{
  int trials = 8000;
  unsigned int seed = 1;
  bool check = false;
  std::string camera = "vga";
  std::string reference = "true"; // "true": error against the noise-free projections
};

//! Declares the options of the program; \e opt receives their values.
vpCommandLine commandLine(Options &opt)
{
  vpCommandLine cli("[--trials N] [--seed S] [--camera vga|uxga] [--reference true|measured] [--check]",
                    "Reproduces Table I of D'Alfonso et al. (MED 2013): relative reprojection error of P3P with two "
                    "IMUs\nagainst a P3P with IMUs + compass and an image-only P4P.");
  cli.addInt("--trials", opt.trials, "N", "number of random trials, N >= 1 (default 8000)", 1, 100000000);
  cli.addUnsigned("--seed", opt.seed, "S", "seed of the random generator (default 1)");
  cli.addChoice("--camera", opt.camera, {"vga", "uxga"}, "CAMERA",
                "'vga' 640x480 px, f = 800 px (default) or 'uxga' 1600x1200 px, f = 2000 px");
  cli.addChoice("--reference", opt.reference, {"true", "measured"}, "REFERENCE",
                "pixels the error is measured against: 'true' noise-free projections (default)\n"
                "or 'measured' noisy image points");
  cli.addFlag("--check", opt.check, "exit with status 1 unless P3P_IMU meets the bounds checked by ctest");
  return cli;
}

// ---- Simulation --------------------------------------------------------------------------------

//! One random scene: ground truth, true and noisy sensor readings.
struct Trial
{
  CameraModel camera;
  Eigen::Matrix3d wRc, wRo;   // orientations in the world frame (z axis = gravity, x = north)
  Eigen::Matrix3d cRo;        // true relative pose...
  Eigen::Vector3d cto;        // ...object to camera
  Eigen::Vector3d gCam, gObj; // noisy unit gravity measured by each IMU
  double headingError = 0.0;  // compass error used by P3P_NM, radians
  std::array<Eigen::Vector2d, kNumFeaturePoints> uvTrue, uvMeasured; // pixels, noise-free and noisy
};

vpCameraParameters cameraParameters(const CameraModel &camera)
{
  return vpCameraParameters(camera.focal, camera.focal, camera.u0(), camera.v0());
}

//! Pixel coordinates (from the image corner) of a camera-frame point; false behind the camera.
bool projectToPixel(const CameraModel &camera, const Eigen::Vector3d &cX, Eigen::Vector2d &uv)
{
  if (!(cX.z() > 0.0))
    return false;
  double u = 0.0, v = 0.0;
  vpMeterPixelConversion::convertPoint(cameraParameters(camera), cX.x() / cX.z(), cX.y() / cX.z(), u, v);
  uv = Eigen::Vector2d(u, v);
  return true;
}

bool insideImage(const CameraModel &camera, const Eigen::Vector2d &uv)
{
  return uv.x() >= 0.0 && uv.x() <= camera.width - 1.0 && uv.y() >= 0.0 && uv.y() <= camera.height - 1.0;
}

//! Uniformly distributed rotation (normalised 4D Gaussian quaternion).
Eigen::Matrix3d randomRotation(std::mt19937 &rng)
{
  std::normal_distribution<double> n01(0.0, 1.0);
  Eigen::Quaterniond q(n01(rng), n01(rng), n01(rng), n01(rng));
  q.normalize();
  return q.toRotationMatrix();
}

//! What a gravity sensor reads: N(0, sigma_g^2) on each component of the unit vector, renormalised.
Eigen::Vector3d noisyGravity(const Eigen::Vector3d &g, std::mt19937 &rng)
{
  std::normal_distribution<double> noise(0.0, kSigmaGravity);
  const Eigen::Vector3d measured = g + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  return measured.normalized();
}

/*!
  Draws a scene. Camera and object orientations are independent uniform rotations in a world frame whose
  z axis is gravity (so the true gravity in each frame is the third row of its rotation from the world);
  the object origin is uniform in the 5 m cube. The draw is repeated until the four feature points are in
  front of the camera and inside the image (the paper needs all points seen). Noise is then drawn once
  per trial and shared by every method.
*/
Trial drawTrial(const CameraModel &camera, std::mt19937 &rng)
{
  std::uniform_real_distribution<double> lateral(-0.5 * kCubeSide, 0.5 * kCubeSide);
  std::uniform_real_distribution<double> depth(kCubeNearDepth, kCubeNearDepth + kCubeSide);
  Trial trial;
  trial.camera = camera;
  for (;;) {
    trial.wRc = randomRotation(rng);
    trial.wRo = randomRotation(rng);
    trial.cRo = trial.wRc.transpose() * trial.wRo;
    const double tx = lateral(rng), ty = lateral(rng), tz = depth(rng);
    trial.cto = Eigen::Vector3d(tx, ty, tz);
    bool visible = true;
    for (int q = 0; q < kNumFeaturePoints && visible; ++q)
      visible = projectToPixel(camera, trial.cRo * kFeature[q] + trial.cto, trial.uvTrue[q]) &&
                insideImage(camera, trial.uvTrue[q]);
    if (visible)
      break;
  }
  const Eigen::Vector3d gravityWorld = Eigen::Vector3d::UnitZ();
  trial.gCam = noisyGravity(trial.wRc.transpose() * gravityWorld, rng);
  trial.gObj = noisyGravity(trial.wRo.transpose() * gravityWorld, rng);
  std::normal_distribution<double> pixelNoise(0.0, kSigmaPixel);
  for (int q = 0; q < kNumFeaturePoints; ++q)
    trial.uvMeasured[q] = trial.uvTrue[q] + Eigen::Vector2d(pixelNoise(rng), pixelNoise(rng));
  std::normal_distribution<double> compassNoise(0.0, kSigmaCompass);
  trial.headingError = compassNoise(rng);
  return trial;
}

//! Normalized image coordinates of the measured pixel of feature point q, as a bearing (x, y, 1).
Eigen::Vector3d measuredBearing(const Trial &trial, int q)
{
  double x = 0.0, y = 0.0;
  const Eigen::Vector2d &uv = trial.uvMeasured[q];
  vpPixelMeterConversion::convertPoint(cameraParameters(trial.camera), uv.x(), uv.y(), x, y);
  return Eigen::Vector3d(x, y, 1.0);
}

//! vpPoint of feature point q with its object coordinates and measured normalized image coordinates.
vpPoint measuredPoint(const Trial &trial, int q)
{
  vpPoint P(kFeature[q].x(), kFeature[q].y(), kFeature[q].z());
  const Eigen::Vector3d x = measuredBearing(trial, q);
  P.set_x(x.x());
  P.set_y(x.y());
  return P;
}

vpColVector toColVector(const Eigen::Vector3d &v)
{
  vpColVector c(3);
  for (unsigned int i = 0; i < 3; ++i)
    c[i] = v[static_cast<int>(i)];
  return c;
}

void fromHomogeneous(const vpHomogeneousMatrix &cMo, Eigen::Matrix3d &R, Eigen::Vector3d &t)
{
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      R(i, j) = cMo[i][j];
    t[i] = cMo[i][3];
  }
}

// ---- Methods -----------------------------------------------------------------------------------

//! An estimated pose, or nothing when the method failed.
struct Estimate
{
  bool ok = false;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

Estimate fromHomogeneous(bool ok, const vpHomogeneousMatrix &cMo)
{
  Estimate e;
  e.ok = ok;
  if (ok)
    fromHomogeneous(cMo, e.R, e.t);
  return e;
}

//! Facade set up with both noisy gravities and the measured A, B, C.
void setupGravityPose(const Trial &trial, vpPoseGravity &pose)
{
  pose.setCameraGravity(toColVector(trial.gCam));
  pose.setObjectGravity(toColVector(trial.gObj));
  for (int q = 0; q < 3; ++q)
    pose.addPoint(measuredPoint(trial, q));
}

//! P3P_IMU, and P3P_IMU_REFINED from it (refinement only if the P3P succeeded).
void estimateGravityP3P(const Trial &trial, Estimate &p3p, Estimate &refined)
{
  try {
    vpPoseGravity pose;
    setupGravityPose(trial, pose);
    // The sensors' own noise levels: gravity components sigma_g, image points sigma_px expressed in
    // normalized coordinates. The consistency check of computePose() compares the gravity-sign test
    // with them, the refinement weighs the measurements by them (maximum likelihood).
    pose.setGravityStdDev(kSigmaGravity);
    pose.setImageStdDev(kSigmaPixel / trial.camera.focal);
    vpHomogeneousMatrix cMo;
    p3p = fromHomogeneous(pose.computePose(vpPoseGravity::P3P, cMo), cMo);
    if (!p3p.ok) {
      refined = Estimate();
      return;
    }
    refined = fromHomogeneous(pose.refinePose(cMo), cMo);
  } catch (const vpException &e) {
    std::cerr << "vpPoseGravity: " << e.getStringMessage() << "\n";
    p3p = Estimate();
    refined = Estimate();
  }
}

/*!
  Rotation world-to-sensor {}^sR_w that an attitude-and-heading sensor reports from its gravity and
  north readings (TRIAD): world z = measured gravity, world x = measured north made orthogonal to it.
*/
Eigen::Matrix3d triadSensorFromWorld(const Eigen::Vector3d &gravity, const Eigen::Vector3d &north)
{
  const Eigen::Vector3d z = gravity.normalized();
  const Eigen::Vector3d x = (north - north.dot(z) * z).normalized();
  Eigen::Matrix3d sRw;
  sRw.col(0) = x;
  sRw.col(1) = z.cross(x);
  sRw.col(2) = z;
  return sRw;
}

/*!
  P3P_NM baseline (the paper's [8]): the rotation comes entirely from the sensors, the image only gives
  the translation. Each device reports its attitude from its noisy gravity and a north direction. The
  compass error is one heading error of sigma_compass about the vertical, applied to the camera's north;
  the object's north is exact, so sigma_compass is the error on the relative heading (the only one that
  matters for cRo). Translation: eq. 14 (vpGravitySolvers::translationFromRotation on two points) for
  each pair (A,B), (B,C), (C,A), then the three vectors averaged.
*/
Estimate estimateNorthMagnetic(const Trial &trial)
{
  const Eigen::Vector3d northWorld = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d gravityCamTrue = trial.wRc.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d northCam =
      Eigen::AngleAxisd(trial.headingError, gravityCamTrue) * (trial.wRc.transpose() * northWorld);
  const Eigen::Vector3d northObj = trial.wRo.transpose() * northWorld;
  const Eigen::Matrix3d cRw = triadSensorFromWorld(trial.gCam, northCam);
  const Eigen::Matrix3d oRw = triadSensorFromWorld(trial.gObj, northObj);

  Estimate e;
  e.R = cRw * oRw.transpose();
  const std::array<std::array<int, 2>, 3> pairs = {{{0, 1}, {1, 2}, {2, 0}}};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto &pair : pairs) {
    const Eigen::Vector3d x[2] = {measuredBearing(trial, pair[0]), measuredBearing(trial, pair[1])};
    const Eigen::Vector3d X[2] = {kFeature[pair[0]], kFeature[pair[1]]};
    Eigen::Vector3d t;
    if (vpGravitySolvers::translationFromRotation(e.R, x, X, 2, t)) {
      sum += t;
      ++count;
    }
  }
  e.ok = count > 0;
  if (e.ok)
    e.t = sum / count;
  return e;
}

/*!
  P4P from the image only: OpenCV IPPE, the method designed for a planar target. IPPE returns the two
  poses a plane admits, sorted by reprojection error; cv::solvePnP() keeps the first one even when it puts
  the target behind the camera (its mirror image reprojects identically, which happens here on about 5 %
  of the trials, seen nearly edge-on). A user would reject such a pose, so we keep the best candidate
  with all points in front of the camera.
*/
Estimate estimateP4POpenCV(const Trial &trial)
{
  std::vector<cv::Point3d> objectPoints;
  std::vector<cv::Point2d> imagePoints;
  for (int q = 0; q < kNumFeaturePoints; ++q) {
    objectPoints.emplace_back(kFeature[q].x(), kFeature[q].y(), kFeature[q].z());
    imagePoints.emplace_back(trial.uvMeasured[q].x(), trial.uvMeasured[q].y());
  }
  const CameraModel &c = trial.camera;
  const cv::Matx33d K(c.focal, 0.0, c.u0(), 0.0, c.focal, c.v0(), 0.0, 0.0, 1.0);
  std::vector<cv::Mat> rvecs, tvecs;
  try {
    cv::solvePnPGeneric(objectPoints, imagePoints, K, cv::noArray(), rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
  } catch (const cv::Exception &ex) {
    std::cerr << "cv::solvePnPGeneric: " << ex.what() << "\n";
    return Estimate();
  }
  for (std::size_t k = 0; k < rvecs.size() && k < tvecs.size(); ++k) {
    cv::Matx33d R;
    cv::Rodrigues(rvecs[k], R);
    Estimate e;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        e.R(i, j) = R(i, j);
      e.t[i] = tvecs[k].at<double>(i);
    }
    bool inFront = true;
    for (int q = 0; q < kNumFeaturePoints; ++q)
      inFront = inFront && (e.R * kFeature[q] + e.t).z() > 0.0;
    if (inFront) {
      e.ok = true;
      return e;
    }
  }
  return Estimate();
}

//! Extra row: ViSP's classical pose on the same four points (Dementhon initialisation + virtual visual servoing).
Estimate estimateP4PViSP(const Trial &trial)
{
  try {
    vpPose pose;
    for (int q = 0; q < kNumFeaturePoints; ++q)
      pose.addPoint(measuredPoint(trial, q));
    vpHomogeneousMatrix cMo;
    return fromHomogeneous(pose.computePose(vpPose::DEMENTHON_VIRTUAL_VS, cMo), cMo);
  } catch (const vpException &) {
    return Estimate(); // vpPose throws on its own degenerate cases: counted as a failure.
  }
}

// ---- Error index and statistics ---------------------------------------------------------------

/*!
  The paper's eq. 17: mean over A, B, C, D of ||p_q - p*_q|| / ||p_q||, with p*_q the pixel reprojected
  by the estimated pose and p_q the reference pixel, both measured from the image corner (+ x_CI in the
  paper). +inf when the method failed or its pose puts a feature point behind the camera.
*/
double relativeReprojectionError(const Trial &trial, const Estimate &e, bool referenceMeasured)
{
  if (!e.ok || !e.R.allFinite() || !e.t.allFinite())
    return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (int q = 0; q < kNumFeaturePoints; ++q) {
    Eigen::Vector2d uvEstimated;
    if (!projectToPixel(trial.camera, e.R * kFeature[q] + e.t, uvEstimated))
      return std::numeric_limits<double>::infinity();
    const Eigen::Vector2d &uvReference = referenceMeasured ? trial.uvMeasured[q] : trial.uvTrue[q];
    sum += (uvReference - uvEstimated).norm() / uvReference.norm();
  }
  return sum / kNumFeaturePoints;
}

//! Accumulated results of one method over all trials.
struct MethodStats
{
  std::string name;
  std::array<int, 4> below{}; // trials under each threshold
  int trials = 0;
  int failures = 0;       // no pose, or a pose with a point behind the camera (eps = inf)
  double sumFinite = 0.0; // sum of the finite errors

  void add(double eps)
  {
    ++trials;
    if (!std::isfinite(eps)) {
      ++failures;
      return;
    }
    sumFinite += eps;
    for (std::size_t k = 0; k < kThresholds.size(); ++k)
      if (eps < kThresholds[k])
        ++below[k];
  }
  double percentBelow(std::size_t k) const { return trials > 0 ? 100.0 * below[k] / trials : 0.0; }
  //! Mean over the trials where the method gave a pose (failures are reported apart).
  double meanFinite() const
  {
    const int n = trials - failures;
    return n > 0 ? sumFinite / n : std::numeric_limits<double>::quiet_NaN();
  }
};

enum MethodIndex { kP3PIMU, kP3PIMURefined, kP3PNM, kP4P, kP4PViSP, kNumMethods };

void printTable(const std::array<MethodStats, kNumMethods> &stats)
{
  std::cout << "| Method | eps < 0.02 | eps < 0.05 | eps < 0.15 | eps < 0.3 | mean eps |\n"
            << "|---|---|---|---|---|---|\n";
  for (const MethodStats &s : stats) {
    std::cout << "| " << s.name << " |";
    for (std::size_t k = 0; k < kThresholds.size(); ++k)
      std::cout << " " << std::fixed << std::setprecision(1) << s.percentBelow(k) << " % |";
    std::cout << " " << std::fixed << std::setprecision(4) << s.meanFinite() << " |\n";
  }
}

/*!
  Assertions used by ctest (--check), meant for about 2000 trials:
  - P3P_IMU fails on at most 1 % of the trials: with exact data it always has a solution, but 2 px of
    noise on a target ~20 px wide can make the image of every pair inconsistent with the two gravity
    readings (no yaw solves the P2P equation within the solver's tolerance), which the solver reports
    instead of guessing (about 0.1 % of the trials here); more than 1 % means a broken solver;
  - mean eps of P3P_IMU < 0.02: with sigma_px = 2 px the reprojection error of a pose estimated from the
    same noisy pixels is a few pixels and the pixel norm in the denominator a few hundred pixels (0.0115
    measured over 8000 trials, the paper reports 0.008); 0.02 leaves room for the near-corner points whose
    small denominator inflates eps, yet picking the P2P candidate at random instead of by the third point
    gives 0.027 and fails;
  - P3P_IMU is not worse than P4P on the eps < 0.02 column (the paper's claim, 93 % vs 56 %; here about
    90 % vs 89 %, the P4P losing mostly its failures; the random candidate choice above gives 78 %).
*/
bool checkResults(const std::array<MethodStats, kNumMethods> &stats)
{
  bool ok = true;
  const MethodStats &imu = stats[kP3PIMU], &p4p = stats[kP4P];
  if (imu.failures > imu.trials / 100) {
    std::cout << "CHECK FAILED: P3P_IMU failed on " << imu.failures << " of " << imu.trials
              << " trials (at most 1 % expected)\n";
    ok = false;
  }
  if (!(imu.meanFinite() < 0.02)) {
    std::cout << "CHECK FAILED: P3P_IMU mean eps " << std::setprecision(4) << imu.meanFinite()
              << " is not below 0.02\n";
    ok = false;
  }
  if (!(imu.percentBelow(0) >= p4p.percentBelow(0))) {
    std::cout << "CHECK FAILED: P3P_IMU has " << std::setprecision(1) << imu.percentBelow(0) << " % under 0.02, P4P "
              << p4p.percentBelow(0) << " %\n";
    ok = false;
  }
  if (ok)
    std::cout << "CHECK PASSED\n";
  return ok;
}
} // namespace

int main(int argc, char **argv)
{
  Options opt;
  vpCommandLine cli = commandLine(opt);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  const CameraModel camera = opt.camera == "uxga" ? kCameraUxga : kCameraVga;
  const bool referenceMeasured = opt.reference == "measured";

  std::array<MethodStats, kNumMethods> stats;
  stats[kP3PIMU].name = "P3P_IMU";
  stats[kP3PIMURefined].name = "P3P_IMU_REFINED";
  stats[kP3PNM].name = "P3P_NM";
  stats[kP4P].name = "P4P";
  stats[kP4PViSP].name = "P4P_VISP";

  std::mt19937 rng(opt.seed);
  const auto start = std::chrono::steady_clock::now();
  vpProgress progress("table1-gravity-p3p: trials", static_cast<std::size_t>(opt.trials));
  for (int i = 0; i < opt.trials; ++i) {
    progress.update(static_cast<std::size_t>(i));
    const Trial trial = drawTrial(camera, rng);
    std::array<Estimate, kNumMethods> estimates;
    estimateGravityP3P(trial, estimates[kP3PIMU], estimates[kP3PIMURefined]);
    estimates[kP3PNM] = estimateNorthMagnetic(trial);
    estimates[kP4P] = estimateP4POpenCV(trial);
    estimates[kP4PViSP] = estimateP4PViSP(trial);
    for (int m = 0; m < kNumMethods; ++m)
      stats[m].add(relativeReprojectionError(trial, estimates[m], referenceMeasured));
  }
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::cout << "Table I of D'Alfonso et al. (MED 2013), relative reprojection error eps (eq. 17) against the "
            << (referenceMeasured ? "measured (noisy)" : "noise-free") << " pixels.\n"
            << "Camera " << camera.width << "x" << camera.height << " px, f = " << camera.focal
            << " px; object in x,y in [-2.5, 2.5] m, z in [" << kCubeNearDepth << ", " << kCubeNearDepth + kCubeSide
            << "] m; sigma_g = " << kSigmaGravity << ", sigma_px = " << kSigmaPixel
            << " px, sigma_compass = 4 deg.\n\n";
  printTable(stats);
  std::cout << "\nTrials: " << opt.trials << ", seed: " << opt.seed << ", failures (counted as eps = inf; mean eps"
            << " over the other trials):";
  for (const MethodStats &s : stats)
    std::cout << " " << s.name << " " << s.failures << (&s == &stats.back() ? "" : ",");
  std::cout << ". Time " << std::setprecision(2) << seconds << " s.\n";
  std::cout << "Published (paper, 8000 trials):";
  for (const PublishedRow &row : kPublished)
    std::cout << " " << row.name << " " << row.values << (&row == &kPublished.back() ? "" : ";");
  std::cout << ".\n";

  if (opt.check && !checkResults(stats))
    return EXIT_FAILURE;
  return EXIT_SUCCESS;
}
