/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchGravityPeers.cpp
  \brief Gravity-aided P2P / P3P / least squares / RANSAC against OpenCV, ViSP vpPose and OpenGV.

  Every method of a group runs on the same seeded instances (pose, object points, bearings and, for
  ours, the two gravity vectors). Without the pose_gravity library (VSP_HAVE_POSE_GRAVITY undefined)
  only the peers are timed.
*/
#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <opengv/absolute_pose/CentralAbsoluteAdapter.hpp>
#include <opengv/absolute_pose/methods.hpp>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/vision/vpPose.h>

#ifdef VSP_HAVE_POSE_GRAVITY
#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>
#endif

#include "benchTable.h"
#include "vspBenchUtils.h"

namespace
{
//! One seeded pose problem: the true pose, the points in both frames and gravity in both frames.
struct PoseInstance
{
  Eigen::Matrix3d R;              // cRo
  Eigen::Vector3d t;              // cto
  Eigen::Vector3d gCam, gObj;     // unit gravity in camera / object frames
  std::vector<Eigen::Vector3d> X; // object points
  std::vector<Eigen::Vector3d> x; // bearings (x, y, 1), noisy when requested
  std::vector<bool> outlier;

  // The same data in each peer's types, built once so that only the solvers are timed.
  std::vector<cv::Point3d> cvObject;
  std::vector<cv::Point2d> cvImage;
  std::vector<vpPoint> vpPoints;
  opengv::bearingVectors_t gvBearings;
  opengv::points_t gvPoints;
};

/*!
  \e n object points in a 1 m cube (or its plane Z = 0 when \e coplanar) seen from 3 to 5 m, a
  uniformly random rotation, a random gravity direction, image noise \e sigma (normalized units)
  and a fraction \e outlierRatio of bearings replaced by random ones in the field of view.
*/
PoseInstance makeInstance(std::mt19937 &rng, int n, bool coplanar, double sigma, double outlierRatio)
{
  std::uniform_real_distribution<double> unit(-0.5, 0.5), depth(3.0, 5.0), fov(-0.4, 0.4), coin(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  PoseInstance p;
  p.R = vspBench::randomRotation(rng);
  p.t = Eigen::Vector3d(unit(rng), unit(rng), depth(rng));
  p.gObj = vspBench::randomUnitVector(rng);
  p.gCam = p.R * p.gObj;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d X(unit(rng), unit(rng), coplanar ? 0.0 : unit(rng));
    const Eigen::Vector3d Xc = p.R * X + p.t;
    Eigen::Vector3d x = Xc / Xc.z();
    const bool isOutlier = coin(rng) < outlierRatio;
    if (isOutlier) {
      x = Eigen::Vector3d(fov(rng), fov(rng), 1.0);
    } else if (sigma > 0.0) {
      x.x() += noise(rng);
      x.y() += noise(rng);
    }
    p.X.push_back(X);
    p.x.push_back(x);
    p.outlier.push_back(isOutlier);
    p.cvObject.emplace_back(X.x(), X.y(), X.z());
    p.cvImage.emplace_back(x.x(), x.y());
    vpPoint P(X.x(), X.y(), X.z());
    P.set_x(x.x());
    P.set_y(x.y());
    p.vpPoints.push_back(P);
    p.gvBearings.push_back(x.normalized());
    p.gvPoints.push_back(X);
  }
  return p;
}

std::vector<PoseInstance> makeInstances(unsigned int seed, int count, int n, bool coplanar, double sigma,
                                        double outlierRatio)
{
  std::mt19937 rng(seed);
  std::vector<PoseInstance> instances;
  instances.reserve(count);
  for (int i = 0; i < count; ++i) {
    instances.push_back(makeInstance(rng, n, coplanar, sigma, outlierRatio));
  }
  return instances;
}

// ---- Peers -----------------------------------------------------------------------------------

double timeCvSolveP3P(const std::vector<PoseInstance> &in, int flags)
{
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  return vspBench::medianNsPerCall(
      [&](int i) {
        std::vector<cv::Mat> rvecs, tvecs;
        const int n = cv::solveP3P(in[i].cvObject, in[i].cvImage, K, cv::noArray(), rvecs, tvecs, flags);
        vspBench::consume(n > 0 ? tvecs[0].at<double>(2) : 0.0);
      },
      static_cast<int>(in.size()));
}

double timeCvSolvePnP(const std::vector<PoseInstance> &in, int flags)
{
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  return vspBench::medianNsPerCall(
      [&](int i) {
        cv::Mat rvec, tvec;
        const bool ok = cv::solvePnP(in[i].cvObject, in[i].cvImage, K, cv::noArray(), rvec, tvec, false, flags);
        vspBench::consume(ok ? tvec.at<double>(2) : 0.0);
      },
      static_cast<int>(in.size()));
}

double timeVpPose(const std::vector<PoseInstance> &in, vpPose::vpPoseMethodType method)
{
  // vpPose is filled in the timed call: its API takes the points through addPoint() for each pose.
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpPose pose;
        pose.addPoints(in[i].vpPoints);
        vpHomogeneousMatrix cMo;
        try {
          pose.computePose(method, cMo);
        } catch (const vpException &) {
        }
        vspBench::consume(cMo[2][3]);
      },
      static_cast<int>(in.size()));
}

template <typename Solver> double timeOpenGv(const std::vector<PoseInstance> &in, Solver solver)
{
  std::vector<opengv::absolute_pose::CentralAbsoluteAdapter> adapters;
  adapters.reserve(in.size());
  for (const PoseInstance &p : in) {
    adapters.emplace_back(p.gvBearings, p.gvPoints, opengv::rotation_t(p.R.transpose()));
  }
  return vspBench::medianNsPerCall([&](int i) { vspBench::consume(solver(adapters[i])); }, static_cast<int>(in.size()));
}

double timeCvSolvePnPRansac(const std::vector<PoseInstance> &in, int flags)
{
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  return vspBench::medianNsPerCall(
      [&](int i) {
        cv::Mat rvec, tvec;
        const bool ok = cv::solvePnPRansac(in[i].cvObject, in[i].cvImage, K, cv::noArray(), rvec, tvec, false, 1000,
                                           1e-3f, 0.99, cv::noArray(), flags);
        vspBench::consume(ok ? tvec.at<double>(2) : 0.0);
      },
      static_cast<int>(in.size()), 5, 0.3);
}

//! Rotation error below 1 deg and translation error below 1 % of the distance.
bool closeEnough(const Eigen::Matrix3d &R, const Eigen::Vector3d &t, const PoseInstance &p)
{
  return vspBench::rotationAngleBetween(R, p.R) < 1.0 * M_PI / 180.0 && (t - p.t).norm() < 0.01 * p.t.norm();
}

double successCvSolvePnPRansac(const std::vector<PoseInstance> &in, int flags)
{
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  int ok = 0;
  for (const PoseInstance &p : in) {
    cv::Mat rvec, tvec, Rcv;
    if (cv::solvePnPRansac(p.cvObject, p.cvImage, K, cv::noArray(), rvec, tvec, false, 1000, 1e-3f, 0.99, cv::noArray(),
                           flags)) {
      cv::Rodrigues(rvec, Rcv);
      Eigen::Matrix3d R;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          R(r, c) = Rcv.at<double>(r, c);
      ok += closeEnough(R, Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)), p) ? 1 : 0;
    }
  }
  return static_cast<double>(ok) / in.size();
}

// ---- Ours ------------------------------------------------------------------------------------
#ifdef VSP_HAVE_POSE_GRAVITY
double timeOursP2P(const std::vector<PoseInstance> &in)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        std::array<vpGravitySolvers::Pose, 2> poses;
        const int n = vpGravitySolvers::p2p(in[i].gCam, in[i].gObj, in[i].x.data(), in[i].X.data(), poses);
        vspBench::consume(n > 0 ? poses[0].t.z() : 0.0);
      },
      static_cast<int>(in.size()));
}

double timeOursP3P(const std::vector<PoseInstance> &in)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpGravitySolvers::Pose pose;
        const bool ok = vpGravitySolvers::p3p(in[i].gCam, in[i].gObj, in[i].x.data(), in[i].X.data(), pose);
        vspBench::consume(ok ? pose.t.z() : 0.0);
      },
      static_cast<int>(in.size()));
}

double timeOursLeastSquares(const std::vector<PoseInstance> &in)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpGravitySolvers::Pose pose;
        const bool ok = vpGravitySolvers::leastSquares(in[i].gCam, in[i].gObj, in[i].x.data(), in[i].X.data(),
                                                       static_cast<int>(in[i].x.size()), pose);
        vspBench::consume(ok ? pose.t.z() : 0.0);
      },
      static_cast<int>(in.size()));
}

vpColVector toVp(const Eigen::Vector3d &v)
{
  vpColVector g(3);
  g[0] = v.x();
  g[1] = v.y();
  g[2] = v.z();
  return g;
}

//! The estimator of one instance, filled through its API (gravity vectors and vpPoint copies).
void prepareFacade(const PoseInstance &p, vpPoseGravity &pose)
{
  pose.setCameraGravity(toVp(p.gCam));
  pose.setObjectGravity(toVp(p.gObj));
  pose.addPoints(p.vpPoints);
}

bool runFacade(const PoseInstance &p, vpPoseGravity::vpPoseGravityMethod method, vpHomogeneousMatrix &cMo)
{
  vpPoseGravity pose;
  prepareFacade(p, pose);
  return pose.computePose(method, cMo);
}

/*!
  computePose() alone on estimators filled beforehand: the validation and the solver, without the
  vpPoint copies and gravity vectors of the API calls that precede it (timed in timeOursFacade()).
*/
double timeOursFacadeComputeOnly(const std::vector<PoseInstance> &in, vpPoseGravity::vpPoseGravityMethod method)
{
  std::vector<vpPoseGravity> estimators(in.size());
  for (size_t i = 0; i < in.size(); ++i)
    prepareFacade(in[i], estimators[i]);
  vpHomogeneousMatrix cMo;
  return vspBench::medianNsPerCall(
      [&](int i) {
        try {
          estimators[i].computePose(method, cMo);
        } catch (const vpException &) {
        }
        vspBench::consume(cMo[2][3]);
      },
      static_cast<int>(in.size()));
}

double timeOursFacade(const std::vector<PoseInstance> &in, vpPoseGravity::vpPoseGravityMethod method, int reps)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpHomogeneousMatrix cMo;
        try {
          runFacade(in[i], method, cMo);
        } catch (const vpException &) {
        }
        vspBench::consume(cMo[2][3]);
      },
      static_cast<int>(in.size()), reps, 0.3);
}

double successOursFacade(const std::vector<PoseInstance> &in, vpPoseGravity::vpPoseGravityMethod method)
{
  int ok = 0;
  for (const PoseInstance &p : in) {
    vpHomogeneousMatrix cMo;
    try {
      if (runFacade(p, method, cMo)) {
        Eigen::Matrix3d R;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            R(r, c) = cMo[r][c];
        ok += closeEnough(R, Eigen::Vector3d(cMo[0][3], cMo[1][3], cMo[2][3]), p) ? 1 : 0;
      }
    } catch (const vpException &) {
    }
  }
  return static_cast<double>(ok) / in.size();
}
#endif

} // namespace

int runGravityProfileLoop(const std::string &method, int instances, unsigned int seed)
{
#ifdef VSP_HAVE_POSE_GRAVITY
  const int points = method == "p2p" ? 2 : (method == "lsq" ? 10 : 3);
  const std::vector<PoseInstance> in = makeInstances(seed, instances, points, false, method == "lsq" ? 1e-4 : 0.0, 0.0);
  double ns = 0.0;
  if (method == "p2p")
    ns = timeOursP2P(in);
  else if (method == "p3p")
    ns = timeOursP3P(in);
  else if (method == "lsq")
    ns = timeOursLeastSquares(in);
  else if (method == "facade")
    ns = timeOursFacade(in, vpPoseGravity::P3P, 15);
  else if (method == "compute")
    ns = timeOursFacadeComputeOnly(in, vpPoseGravity::P3P);
  else {
    std::fprintf(stderr, "unknown gravity method %s (p2p, p3p, lsq, facade, compute)\n", method.c_str());
    return 1;
  }
  std::printf("%s: %.1f ns per call (median over batches of %d instances)\n", method.c_str(), ns, instances);
  return 0;
#else
  std::fprintf(stderr, "bench-peers was built without the pose_gravity module (%s, %d, %u)\n", method.c_str(),
               instances, seed);
  return 1;
#endif
}

void runGravityBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick)
{
  const int count = quick ? 200 : 1000;
  const std::vector<PoseInstance> two = makeInstances(seed, count, 2, false, 0.0, 0.0);
  const std::vector<PoseInstance> three = makeInstances(seed + 1, count, 3, false, 0.0, 0.0);
  const std::vector<PoseInstance> four = makeInstances(seed + 2, count, 4, true, 0.0, 0.0);
  const std::vector<PoseInstance> ten = makeInstances(seed + 3, count, 10, false, 1e-4, 0.0);
  const std::vector<PoseInstance> hundred = makeInstances(seed + 4, count / 4, 100, false, 1e-4, 0.0);
  const std::vector<PoseInstance> ransac = makeInstances(seed + 5, quick ? 20 : 100, 100, false, 1e-4, 0.3);

  BenchTable table;
  table.title = "Gravity-aided pose: median time per call";
  table.note = "Exact data for P2P/P3P/4 points, 1e-4 (normalized) image noise for 10/100 points, 30 % outliers "
               "for RANSAC (100 points, 1e-3 threshold; success = rotation < 1 deg and translation < 1 %). "
               "Ratio = time / time of our solver of the same problem. vpPose includes addPoints(), its API.";
  std::vector<BenchRow> &rows = table.rows;

  double oursP2P = 0.0, oursP3P = 0.0, oursP3P4 = 0.0, oursLs10 = 0.0, oursLs100 = 0.0, oursRansac = 0.0;
#ifdef VSP_HAVE_POSE_GRAVITY
  oursP2P = timeOursP2P(two);
  oursP3P = timeOursP3P(three);
  oursP3P4 = timeOursP3P(four);
  oursLs10 = timeOursLeastSquares(ten);
  oursLs100 = timeOursLeastSquares(hundred);
  oursRansac = timeOursFacade(ransac, vpPoseGravity::RANSAC, 7);
  targets.oursP3P = oursP3P;
#endif

  // P2P: ours solves the yaw and the translation; OpenGV's p2p is given the full rotation.
  rows.push_back(benchRow("P2P (2 points)", "ours vpGravitySolvers::p2p (gravity)", oursP2P, oursP2P, true));
  rows.push_back(benchRow("P2P (2 points)", "OpenGV absolute_pose::p2p (rotation known)",
                          timeOpenGv(two,
                                     [](const opengv::absolute_pose::CentralAbsoluteAdapter &a) {
                                       return opengv::absolute_pose::p2p(a, 0, 1).z();
                                     }),
                          oursP2P));

  rows.push_back(benchRow("P3P (3 points)", "ours vpGravitySolvers::p3p (gravity)", oursP3P, oursP3P, true));
#ifdef VSP_HAVE_POSE_GRAVITY
  rows.push_back(benchRow("P3P (3 points)", "ours vpPoseGravity API: set gravity, addPoints, computePose(P3P)",
                          timeOursFacade(three, vpPoseGravity::P3P, 15), oursP3P, true));
  rows.push_back(benchRow("P3P (3 points)", "ours vpPoseGravity::computePose(P3P) alone (points added before)",
                          timeOursFacadeComputeOnly(three, vpPoseGravity::P3P), oursP3P, true));
#endif
  const double cvP3P = timeCvSolveP3P(three, cv::SOLVEPNP_P3P);
  const double cvAP3P = timeCvSolveP3P(three, cv::SOLVEPNP_AP3P);
  targets.cvAp3p = cvAP3P;
  rows.push_back(benchRow("P3P (3 points)", "OpenCV solveP3P SOLVEPNP_P3P", cvP3P, oursP3P));
  rows.push_back(benchRow("P3P (3 points)", "OpenCV solveP3P SOLVEPNP_AP3P", cvAP3P, oursP3P));
  rows.push_back(benchRow("P3P (3 points)", "OpenGV p3p_kneip",
                          timeOpenGv(three,
                                     [](const opengv::absolute_pose::CentralAbsoluteAdapter &a) {
                                       const opengv::transformations_t T = opengv::absolute_pose::p3p_kneip(a, 0, 1, 2);
                                       return T.empty() ? 0.0 : T[0](2, 3);
                                     }),
                          oursP3P));
  rows.push_back(benchRow("P3P (3 points)", "OpenGV p3p_gao",
                          timeOpenGv(three,
                                     [](const opengv::absolute_pose::CentralAbsoluteAdapter &a) {
                                       const opengv::transformations_t T = opengv::absolute_pose::p3p_gao(a, 0, 1, 2);
                                       return T.empty() ? 0.0 : T[0](2, 3);
                                     }),
                          oursP3P));

  const std::string four4 = "4 coplanar points";
  rows.push_back(benchRow(four4, "ours vpGravitySolvers::p3p (first 3 points)", oursP3P4, oursP3P4, true));
#ifdef VSP_HAVE_POSE_GRAVITY
  rows.push_back(
      benchRow(four4, "ours vpGravitySolvers::leastSquares (4 points)", timeOursLeastSquares(four), oursP3P4, true));
#endif
  rows.push_back(benchRow(four4, "OpenCV solvePnP SOLVEPNP_SQPNP", timeCvSolvePnP(four, cv::SOLVEPNP_SQPNP), oursP3P4));
  rows.push_back(benchRow(four4, "OpenCV solvePnP SOLVEPNP_IPPE", timeCvSolvePnP(four, cv::SOLVEPNP_IPPE), oursP3P4));
  const double lagrange4 = timeVpPose(four, vpPose::LAGRANGE);
  targets.vpPoseLagrange4 = lagrange4;
  rows.push_back(benchRow(four4, "ViSP vpPose LAGRANGE", lagrange4, oursP3P4));
  rows.push_back(benchRow(four4, "ViSP vpPose DEMENTHON", timeVpPose(four, vpPose::DEMENTHON), oursP3P4));
  rows.push_back(
      benchRow(four4, "ViSP vpPose LAGRANGE_VIRTUAL_VS", timeVpPose(four, vpPose::LAGRANGE_VIRTUAL_VS), oursP3P4));
  rows.push_back(
      benchRow(four4, "ViSP vpPose DEMENTHON_VIRTUAL_VS", timeVpPose(four, vpPose::DEMENTHON_VIRTUAL_VS), oursP3P4));

  for (int n : {10, 100}) {
    const std::vector<PoseInstance> &in = n == 10 ? ten : hundred;
    const double ours = n == 10 ? oursLs10 : oursLs100;
    const std::string problem = std::to_string(n) + " points";
    rows.push_back(benchRow(problem, "ours vpGravitySolvers::leastSquares", ours, ours, true));
    rows.push_back(benchRow(problem, "OpenCV solvePnP SOLVEPNP_SQPNP", timeCvSolvePnP(in, cv::SOLVEPNP_SQPNP), ours));
    rows.push_back(benchRow(problem, "OpenCV solvePnP SOLVEPNP_EPNP", timeCvSolvePnP(in, cv::SOLVEPNP_EPNP), ours));
    rows.push_back(benchRow(problem, "OpenGV epnp",
                            timeOpenGv(in,
                                       [](const opengv::absolute_pose::CentralAbsoluteAdapter &a) {
                                         return opengv::absolute_pose::epnp(a)(2, 3);
                                       }),
                            ours));
    rows.push_back(
        benchRow(problem, "ViSP vpPose LAGRANGE_VIRTUAL_VS", timeVpPose(in, vpPose::LAGRANGE_VIRTUAL_VS), ours));
  }

  const std::string rs = "RANSAC, 100 points, 30 % outliers";
#ifdef VSP_HAVE_POSE_GRAVITY
  rows.push_back(benchRow(rs, "ours vpPoseGravity RANSAC (2-point)", oursRansac, oursRansac, true,
                          successOursFacade(ransac, vpPoseGravity::RANSAC)));
#endif
  rows.push_back(benchRow(rs, "OpenCV solvePnPRansac SOLVEPNP_AP3P", timeCvSolvePnPRansac(ransac, cv::SOLVEPNP_AP3P),
                          oursRansac, false, successCvSolvePnPRansac(ransac, cv::SOLVEPNP_AP3P)));
  rows.push_back(benchRow(rs, "OpenCV solvePnPRansac SOLVEPNP_EPNP", timeCvSolvePnPRansac(ransac, cv::SOLVEPNP_EPNP),
                          oursRansac, false, successCvSolvePnPRansac(ransac, cv::SOLVEPNP_EPNP)));
  tables.push_back(table);
}
