/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \example gravity-robustness.cpp

  Evaluation of the checks that keep vpPoseGravity from returning confident wrong poses, on seeded
  simulated scenes (a 1 m object 2 to 8 m in front of a 640 x 480, f = 800 px camera; image noise in
  pixels / 800):

  - ransac_pure_outliers: random image points in the 640 x 480 image, random object points and
    gravities (no true pose): share of runs where computePose(RANSAC) claims success, n = 40 and
    200, default threshold and 5e-3.
  - ransac_inlier_recall: share of the true inliers (1 px noise) kept at the default threshold.
  - sign_mixup: the camera gravity passed with the wrong sign (the raw accelerometer reading): share
    of runs returning success with a pose more than 10 degrees off, P3P and LEAST_SQUARES (8 points),
    exact and 1 px image noise.
  (That LEAST_SQUARES returns the best minimum of its cost is checked against a dense scan of the yaw
  by the test PoseGravityChecks.LeastSquaresIsTheBestMinimum.)
  - lsq_near_points: 3D error of the near points (1 to 2 m) of scenes that mix them with far points
    (8 m, 40 m), LEAST_SQUARES (0 and 2 reweighting passes) over the maximum-likelihood pose.
  - p3p_noisy_gravity: P3P median rotation error over the median relative tilt error of the two
    IMUs (sigma_g = 0.01 per component), both pair rules.
  - p3p_exact_gravity: P3P p90 rotation error (first 3 of 4 points) against OpenCV SQPnP on the 4
    points, 1 px noise.

  Usage: gravity-robustness [--trials N] [--seed S] [--check]   (N = 1000 by default: about 10 s)
*/
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpQuaternionVector.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "vpCommandLine.h"

namespace
{
const double kFocal = 800.0;
const double kHalfWidth = 320.0 / kFocal, kHalfHeight = 240.0 / kFocal;
const double kPi = 3.14159265358979323846;

struct Scene
{
  vpHomogeneousMatrix cMo;
  std::vector<vpPoint> points;
  vpColVector gCam, gObj;
};

class Generator
{
public:
  explicit Generator(unsigned int seed) : m_rng(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }
  double gaussian(double s) { return std::normal_distribution<double>(0.0, s)(m_rng); }
  Eigen::Vector3d unit()
  {
    Eigen::Vector3d v(gaussian(1), gaussian(1), gaussian(1));
    return v.normalized();
  }
  Eigen::Matrix3d rotation()
  {
    Eigen::Quaterniond q(gaussian(1), gaussian(1), gaussian(1), gaussian(1));
    return q.normalized().toRotationMatrix();
  }
  //! Points at the given depths (one range per point), in the field of view, random rotation.
  Scene scene(const std::vector<std::pair<double, double> > &depths, double size = 1.0)
  {
    Scene s;
    const Eigen::Matrix3d R = rotation();
    std::vector<Eigen::Vector3d> Pc;
    for (const auto &d : depths) {
      const double z = uniform(d.first, d.second);
      Pc.emplace_back(uniform(-0.8, 0.8) * kHalfWidth * z, uniform(-0.8, 0.8) * kHalfHeight * z, z);
    }
    // A compact object: pull the points of the same depth range towards their mean (size metres).
    if (size > 0.0 && !depths.empty()) {
      const double z0 = uniform(depths[0].first, depths[0].second);
      Eigen::Vector3d c(uniform(-0.3, 0.3) * z0, uniform(-0.2, 0.2) * z0, z0);
      for (size_t i = 0; i < Pc.size(); ++i)
        if (depths[i] == depths[0])
          Pc[i] = c + size * Eigen::Vector3d(uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5));
    }
    const Eigen::Vector3d t(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    // Object frame: X = R^T (Pc - t) so that Pc = R X + t.
    vpRotationMatrix cRo;
    for (unsigned int r = 0; r < 3; ++r)
      for (unsigned int c = 0; c < 3; ++c)
        cRo[r][c] = R(r, c);
    s.cMo = vpHomogeneousMatrix(vpTranslationVector(t.x(), t.y(), t.z()), cRo);
    for (const Eigen::Vector3d &p : Pc) {
      const Eigen::Vector3d X = R.transpose() * (p - t);
      vpPoint P(X.x(), X.y(), X.z());
      P.set_x(p.x() / p.z());
      P.set_y(p.y() / p.z());
      s.points.push_back(P);
    }
    const Eigen::Vector3d go = unit();
    const Eigen::Vector3d gc = R * go;
    s.gObj = vpColVector(3);
    s.gCam = vpColVector(3);
    for (unsigned int i = 0; i < 3; ++i) {
      s.gObj[i] = go[i];
      s.gCam[i] = gc[i];
    }
    return s;
  }
  Scene compact(int n) { return scene(std::vector<std::pair<double, double> >(n, {2.0, 8.0})); }
  void noise(Scene &s, double px)
  {
    for (vpPoint &P : s.points) {
      P.set_x(P.get_x() + gaussian(px / kFocal));
      P.set_y(P.get_y() + gaussian(px / kFocal));
    }
  }
  vpColVector noisyGravity(const vpColVector &g, double sigma)
  {
    Eigen::Vector3d v(g[0] + gaussian(sigma), g[1] + gaussian(sigma), g[2] + gaussian(sigma));
    v.normalize();
    vpColVector r(3);
    for (unsigned int i = 0; i < 3; ++i)
      r[i] = v[i];
    return r;
  }

private:
  std::mt19937 m_rng;
};

Eigen::Matrix3d rotationOf(const vpHomogeneousMatrix &M)
{
  Eigen::Matrix3d R;
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c)
      R(r, c) = M[r][c];
  return R;
}

double rotationErrorDeg(const vpHomogeneousMatrix &A, const vpHomogeneousMatrix &B)
{
  const Eigen::AngleAxisd aa(rotationOf(A) * rotationOf(B).transpose());
  return std::abs(aa.angle()) * 180.0 / kPi;
}

double quantile(std::vector<double> v, double q)
{
  if (v.empty())
    return std::nan("");
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * v.size()));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

int g_failedTargets = 0;

//! Prints a measured value; \e target is "" or a description, \e pass false when a target is missed.
void row(const std::string &name, const std::string &what, double value, const std::string &target, bool pass = true)
{
  std::cout << std::left << std::setw(22) << name << std::setw(58) << what << std::right << std::setw(10)
            << std::setprecision(4) << value << "   " << target << (pass ? "" : "   MISSED") << "\n";
  g_failedTargets += !pass;
}

// --- RANSAC on pure outliers ---------------------------------------------------------------------
void ransacPureOutliers(Generator &gen, int trials)
{
  for (int n : {40, 200})
    for (double thr : {4e-3, 5e-3}) {
      int success = 0;
      for (int k = 0; k < trials; ++k) {
        vpPoseGravity pose;
        pose.setCameraGravity(vpColVector(std::vector<double>{gen.gaussian(1), gen.gaussian(1), gen.gaussian(1)}));
        pose.setObjectGravity(vpColVector(std::vector<double>{gen.gaussian(1), gen.gaussian(1), gen.gaussian(1)}));
        for (int i = 0; i < n; ++i) {
          vpPoint P(gen.uniform(-1, 1), gen.uniform(-1, 1), gen.uniform(-1, 1));
          P.set_x(gen.uniform(-kHalfWidth, kHalfWidth));
          P.set_y(gen.uniform(-kHalfHeight, kHalfHeight));
          pose.addPoint(P);
        }
        pose.setRansacThreshold(thr);
        pose.setRansacSeed(static_cast<unsigned int>(k));
        vpHomogeneousMatrix cMo;
        success += pose.computePose(vpPoseGravity::RANSAC, cMo);
      }
      row("ransac_pure_outliers",
          "n = " + std::to_string(n) + ", threshold " + std::to_string(thr).substr(0, 6) + ": % success claimed",
          100.0 * success / trials, "target <= 1 %", success <= trials / 100);
    }
}

void ransacInlierRecall(Generator &gen, int trials)
{
  double kept = 0.0, total = 0.0;
  for (int k = 0; k < trials / 4; ++k) {
    Scene s = gen.compact(60);
    gen.noise(s, 1.0);
    for (int i = 40; i < 60; ++i) { // a third of outliers
      s.points[static_cast<size_t>(i)].set_x(gen.uniform(-kHalfWidth, kHalfWidth));
      s.points[static_cast<size_t>(i)].set_y(gen.uniform(-kHalfHeight, kHalfHeight));
    }
    vpPoseGravity pose;
    pose.setCameraGravity(s.gCam);
    pose.setObjectGravity(s.gObj);
    pose.addPoints(s.points);
    pose.setRansacSeed(static_cast<unsigned int>(k));
    vpHomogeneousMatrix cMo;
    total += 40;
    if (pose.computePose(vpPoseGravity::RANSAC, cMo))
      for (unsigned int i : pose.getRansacInlierIndex())
        kept += (i < 40);
  }
  row("ransac_inlier_recall", "default threshold, 1 px noise: % of true inliers kept", 100.0 * kept / total,
      "target >= 95 %", kept >= 0.95 * total);
}

// --- Gravity sign mix-up ---------------------------------------------------------------------------
void signMixup(Generator &gen, int trials)
{
  for (vpPoseGravity::vpPoseGravityMethod method : {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES})
    for (double px : {0.0, 1.0}) {
      int wrong = 0, reversedStatus = 0;
      for (int k = 0; k < trials; ++k) {
        Scene s = gen.compact(method == vpPoseGravity::P3P ? 3 : 8);
        gen.noise(s, px);
        vpPoseGravity pose;
        pose.setCameraGravity(-s.gCam); // the specific force, pointing up
        pose.setObjectGravity(s.gObj);
        pose.addPoints(s.points);
        vpHomogeneousMatrix cMo;
        const bool ok = pose.computePose(method, cMo);
        wrong += ok && rotationErrorDeg(cMo, s.cMo) > 10.0;
        reversedStatus += pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED;
      }
      const std::string name = std::string(method == vpPoseGravity::P3P ? "P3P" : "LEAST_SQUARES (8 points)") + ", " +
                               (px > 0 ? "1 px" : "exact");
      row("sign_mixup", name + ": % success > 10 deg off", 100.0 * wrong / trials, "target <= 1 %",
          wrong <= trials / 100);
      row("sign_mixup", name + ": % STATUS_GRAVITY_SIGN_REVERSED", 100.0 * reversedStatus / trials, "(diagnosis)");
    }
  // The same scenes with the right sign must still succeed.
  int failures = 0;
  for (int k = 0; k < trials; ++k) {
    Scene s = gen.compact(3);
    gen.noise(s, 1.0);
    vpPoseGravity pose;
    pose.setCameraGravity(gen.noisyGravity(s.gCam, 0.01));
    pose.setObjectGravity(gen.noisyGravity(s.gObj, 0.01));
    pose.addPoints(s.points);
    vpHomogeneousMatrix cMo;
    failures += !pose.computePose(vpPoseGravity::P3P, cMo);
  }
  row("sign_mixup", "right sign, 1 px, sigma_g 0.01, P3P: % rejected", 100.0 * failures / trials, "(false alarms)");
}

// --- Least squares ---------------------------------------------------------------------------------
double nearPointsError(const vpHomogeneousMatrix &M, const Scene &s, int nearCount)
{
  double e = 0.0;
  for (int i = 0; i < nearCount; ++i) {
    const vpPoint &P = s.points[static_cast<size_t>(i)];
    const vpColVector X(std::vector<double>{P.get_oX(), P.get_oY(), P.get_oZ(), 1.0});
    e += std::sqrt((M * X - s.cMo * X).sumSquare());
  }
  return e / nearCount;
}

void lsqNearPoints(Generator &gen, int trials)
{
  for (double far : {8.0, 40.0}) {
    double err[2] = {0.0, 0.0}, ml = 0.0;
    for (int k = 0; k < trials; ++k) {
      std::vector<std::pair<double, double> > depths(5, {1.0, 2.0});
      depths.insert(depths.end(), 5, {far * 0.95, far * 1.05});
      Scene s = gen.scene(depths, 0.0);
      gen.noise(s, 1.0);
      std::vector<Eigen::Vector3d> x, X;
      for (const vpPoint &P : s.points) {
        x.emplace_back(P.get_x(), P.get_y(), 1.0);
        X.emplace_back(P.get_oX(), P.get_oY(), P.get_oZ());
      }
      const Eigen::Vector3d gc(s.gCam[0], s.gCam[1], s.gCam[2]), go(s.gObj[0], s.gObj[1], s.gObj[2]);
      for (int passes : {0, 2}) {
        vpGravitySolvers::Pose p;
        vpGravitySolvers::leastSquares(gc, go, x.data(), X.data(), 10, p, passes);
        vpHomogeneousMatrix M;
        for (unsigned int r = 0; r < 3; ++r) {
          for (unsigned int c = 0; c < 3; ++c)
            M[r][c] = p.R(r, c);
          M[r][3] = p.t(r);
        }
        err[passes / 2] += nearPointsError(M, s, 5);
      }
      vpPoseGravity pose;
      pose.setCameraGravity(s.gCam);
      pose.setObjectGravity(s.gObj);
      pose.addPoints(s.points);
      pose.setImageStdDev(1.0 / kFocal);
      vpHomogeneousMatrix M = s.cMo; // the maximum-likelihood pose, found from the truth
      pose.refinePose(M);
      ml += nearPointsError(M, s, 5);
    }
    const std::string f = std::to_string(static_cast<int>(far)) + " m";
    row("lsq_near_points", "far points at " + f + ": near 3D error / ML, no reweighting", err[0] / ml, "(before)");
    row("lsq_near_points", "far points at " + f + ": near 3D error / ML, 2 passes", err[1] / ml, "target <= 1.2",
        err[1] / ml <= 1.2);
  }
}

// --- P3P -------------------------------------------------------------------------------------------
void p3pNoisyGravity(Generator &gen, int trials)
{
  std::vector<double> tilt, err[2];
  for (int k = 0; k < trials; ++k) {
    Scene s = gen.compact(3);
    gen.noise(s, 1.0);
    const vpColVector gc = gen.noisyGravity(s.gCam, 0.01), go = gen.noisyGravity(s.gObj, 0.01);
    // The relative tilt error the IMUs leave: angle between the measured camera gravity and the
    // measured object gravity carried by the true rotation.
    const Eigen::Vector3d a = rotationOf(s.cMo) * Eigen::Vector3d(go[0], go[1], go[2]);
    tilt.push_back(std::acos(std::min(1.0, a.dot(Eigen::Vector3d(gc[0], gc[1], gc[2])))) * 180.0 / kPi);
    for (int rule = 0; rule < 2; ++rule) {
      vpPoseGravity pose;
      pose.setCameraGravity(gc);
      pose.setObjectGravity(go);
      pose.addPoints(s.points);
      pose.setP3PPairRule(rule == 0 ? vpPoseGravity::P3P_BEST_THIRD_POINT : vpPoseGravity::P3P_WIDEST_PAIR);
      vpHomogeneousMatrix cMo;
      err[rule].push_back(pose.computePose(vpPoseGravity::P3P, cMo) ? rotationErrorDeg(cMo, s.cMo) : 180.0);
    }
  }
  const double t = quantile(tilt, 0.5);
  row("p3p_noisy_gravity", "median relative IMU tilt error (deg)", t, "");
  row("p3p_noisy_gravity", "best third point: median rotation error / tilt error", quantile(err[0], 0.5) / t,
      "target <= 2", quantile(err[0], 0.5) <= 2.0 * t);
  row("p3p_noisy_gravity", "widest pair (paper): median rotation error / tilt error", quantile(err[1], 0.5) / t,
      "(before)");
}

void p3pExactGravity(Generator &gen, int trials)
{
  std::vector<double> ours, widest, sqpnp;
  for (int k = 0; k < trials; ++k) {
    Scene s = gen.compact(4);
    gen.noise(s, 1.0);
    for (int rule = 0; rule < 2; ++rule) {
      vpPoseGravity pose;
      pose.setCameraGravity(s.gCam);
      pose.setObjectGravity(s.gObj);
      pose.addPoints(s.points);
      pose.setP3PPairRule(rule == 0 ? vpPoseGravity::P3P_BEST_THIRD_POINT : vpPoseGravity::P3P_WIDEST_PAIR);
      vpHomogeneousMatrix cMo;
      (rule == 0 ? ours : widest)
          .push_back(pose.computePose(vpPoseGravity::P3P, cMo) ? rotationErrorDeg(cMo, s.cMo) : 180.0);
    }
    std::vector<cv::Point3d> obj;
    std::vector<cv::Point2d> img;
    for (const vpPoint &P : s.points) {
      obj.emplace_back(P.get_oX(), P.get_oY(), P.get_oZ());
      img.emplace_back(P.get_x(), P.get_y());
    }
    cv::Mat rvec, tvec;
    double e = 180.0;
    if (cv::solvePnP(obj, img, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec, false, cv::SOLVEPNP_SQPNP)) {
      cv::Mat R;
      cv::Rodrigues(rvec, R);
      vpHomogeneousMatrix M;
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int c = 0; c < 3; ++c)
          M[r][c] = R.at<double>(static_cast<int>(r), static_cast<int>(c));
      e = rotationErrorDeg(M, s.cMo);
    }
    sqpnp.push_back(e);
  }
  row("p3p_exact_gravity", "P3P best third point (3 of 4 points): p90 rotation error (deg)", quantile(ours, 0.9), "");
  row("p3p_exact_gravity", "P3P widest pair: p90 rotation error (deg)", quantile(widest, 0.9), "(before)");
  row("p3p_exact_gravity", "OpenCV SQPnP (4 points): p90 rotation error (deg)", quantile(sqpnp, 0.9), "");
  row("p3p_exact_gravity", "p90 ratio ours / SQPnP", quantile(ours, 0.9) / quantile(sqpnp, 0.9), "target <= 1",
      quantile(ours, 0.9) <= quantile(sqpnp, 0.9));
}
} // namespace

int main(int argc, char **argv)
{
  int trials = 1000;
  unsigned int seed = 1;
  bool check = false;
  vpCommandLine cli("[--trials N] [--seed S] [--check]", "Robustness of vpPoseGravity's checks on simulated scenes.");
  cli.addFlag("--check", check, "exit with status 1 when a target is missed");
  cli.addInt("--trials", trials, "N", "trials per experiment (default 1000)", 1);
  cli.addUnsigned("--seed", seed, "S", "seed (default 1)");
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  Generator gen(seed);
  std::cout << std::fixed;
  try {
    ransacPureOutliers(gen, trials);
    ransacInlierRecall(gen, trials);
    signMixup(gen, trials);
    lsqNearPoints(gen, trials);
    p3pNoisyGravity(gen, trials);
    p3pExactGravity(gen, trials);
  } catch (const std::exception &e) {
    std::cerr << "gravity-robustness: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << (g_failedTargets ? std::to_string(g_failedTargets) + " target(s) MISSED"
                                : std::string("All targets met"))
            << std::endl;
  return (check && g_failedTargets) ? EXIT_FAILURE : EXIT_SUCCESS;
}
