/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  The P2P / P3P fast path solves the yaw equation for (cos, sin) directly and selects the P3P root
  through linear forms in (cos, sin). These tests hold it to the plain definitions on seeded scenes:
  the yaw order of the P2P candidates (angle read back from the rotation), both points in front of
  the camera, the P3P pose equal to the P2P candidate chosen by each pair rule (best third-point
  error over the observing pairs; the widest image pair), computed directly with noise so that the
  choice matters, and invariance to the scale of the bearings.
*/
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpGravitySolvers.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
// Yaw of a rotation cRo in (-pi, pi]: Rz = wRc cRo wRo^T (file description of vpGravitySolvers.h).
double yawOf(const Eigen::Matrix3d &R, const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj)
{
  const Eigen::Matrix3d Rz =
      vpGravitySolvers::uprightRotation(gCam) * R * vpGravitySolvers::uprightRotation(gObj).transpose();
  return std::atan2(Rz(1, 0), Rz(0, 0));
}

// Squared reprojection error of X through the pose against the bearing x; infinity behind the camera.
double reprojection2(const vpGravitySolvers::Pose &pose, const Eigen::Vector3d &x, const Eigen::Vector3d &X)
{
  const Eigen::Vector3d P = pose.R * X + pose.t;
  if (!(P.z() > 0.0))
    return std::numeric_limits<double>::infinity();
  const double ex = P.x() / P.z() - x.x() / x.z(), ey = P.y() / P.z() - x.y() / x.z();
  return ex * ex + ey * ey;
}

// How much the pair (i, j) constrains the yaw: |n_h| |d_h| / (|n| |d|) in the upright frames, with
// n the normal of the plane of the two rays and d the object segment.
double observability(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d &xi,
                     const Eigen::Vector3d &xj, const Eigen::Vector3d &Xi, const Eigen::Vector3d &Xj)
{
  const Eigen::Vector3d n = vpGravitySolvers::uprightRotation(gCam) * xi.cross(xj);
  const Eigen::Vector3d d = vpGravitySolvers::uprightRotation(gObj) * (Xi - Xj);
  return n.head<2>().norm() * d.head<2>().norm() / (n.norm() * d.norm());
}

// P3P with the default rule by its definition: over the pairs that observe the yaw (observability >=
// 0.05; the others only if none does), the P2P candidate with the smallest third-point error.
bool referenceBestThirdPoint(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj,
                             const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X,
                             vpGravitySolvers::Pose &pose)
{
  double best[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  vpGravitySolvers::Pose bestPose[2];
  for (int p = 0; p < 3; ++p) {
    const int i = p, j = (p + 1) % 3, k = (p + 2) % 3;
    const Eigen::Vector3d xp[2] = {x[i], x[j]}, Xp[2] = {X[i], X[j]};
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    const int count = vpGravitySolvers::p2p(gCam, gObj, xp, Xp, poses, &p2pCase);
    if (p2pCase != vpGravitySolvers::P2PCase::TwoSolutions)
      continue;
    const int weak = observability(gCam, gObj, x[i], x[j], X[i], X[j]) < 0.05 ? 1 : 0;
    for (int m = 0; m < count; ++m) {
      const double e = reprojection2(poses[m], x[k], X[k]);
      if (e < best[weak]) {
        best[weak] = e;
        bestPose[weak] = poses[m];
      }
    }
  }
  for (int w = 0; w < 2; ++w)
    if (best[w] < std::numeric_limits<double>::infinity()) {
      pose = bestPose[w];
      return true;
    }
  return false;
}

// P3P with the paper's rule by its definition: pairs by decreasing image distance, first pair with
// admissible P2P candidates, the candidate with the smallest reprojection error of the third point.
bool referenceWidestPair(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj,
                         const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X,
                         vpGravitySolvers::Pose &pose)
{
  int order[3] = {0, 1, 2};
  auto dist = [&](int p) { return (x[p] / x[p].z() - x[(p + 1) % 3] / x[(p + 1) % 3].z()).squaredNorm(); };
  std::stable_sort(order, order + 3, [&](int a, int b) { return dist(a) > dist(b); });
  for (int p : order) {
    const int i = p, j = (p + 1) % 3, k = (p + 2) % 3;
    const Eigen::Vector3d xp[2] = {x[i], x[j]}, Xp[2] = {X[i], X[j]};
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    const int count = vpGravitySolvers::p2p(gCam, gObj, xp, Xp, poses, &p2pCase);
    double best = std::numeric_limits<double>::infinity();
    for (int m = 0; m < count; ++m) {
      const double e = reprojection2(poses[m], x[k], X[k]);
      if (e < best) {
        best = e;
        pose = poses[m];
      }
    }
    if (p2pCase == vpGravitySolvers::P2PCase::TwoSolutions && best < std::numeric_limits<double>::infinity())
      return true;
  }
  return false;
}
} // namespace

TEST(PoseGravitySolversFastPath, P2PCandidatesOrderedAndInFront)
{
  SceneGenerator gen(21);
  std::vector<Eigen::Vector3d> x, X;
  int pairsWithTwo = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Scene s = gen.scene(2);
    toSolverInput(s.points, x, X);
    const Eigen::Vector3d gCam = toEigen(s.gCam), gObj = toEigen(s.gObj);
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    const int count = vpGravitySolvers::p2p(gCam, gObj, x.data(), X.data(), poses, &p2pCase);
    ASSERT_EQ(p2pCase, vpGravitySolvers::P2PCase::TwoSolutions);
    ASSERT_GE(count, 1);
    for (int m = 0; m < count; ++m) {
      // A rotation, gravity mapped exactly, both points in front and reprojected exactly.
      EXPECT_LT((poses[m].R * poses[m].R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
      EXPECT_LT((poses[m].R * gObj - gCam).norm(), 1e-12);
      for (int i = 0; i < 2; ++i)
        EXPECT_LT(reprojection2(poses[m], x[i], X[i]), 1e-18) << "trial " << trial << " candidate " << m;
    }
    if (count == 2) {
      ++pairsWithTwo;
      EXPECT_LT(yawOf(poses[0].R, gCam, gObj), yawOf(poses[1].R, gCam, gObj)) << "trial " << trial;
    }
  }
  EXPECT_GT(pairsWithTwo, 1000); // the order was checked on many pairs
}

TEST(PoseGravitySolversFastPath, P3PIsTheBestReprojectingCandidate)
{
  SceneGenerator gen(22);
  std::vector<Eigen::Vector3d> x, X;
  int compared = 0, pairsDiffer = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Scene s = gen.scene(3);
    gen.addImageNoise(s.points, 2e-3); // noise large enough for the wrong root to be close at times
    toSolverInput(s.points, x, X);
    const Eigen::Vector3d gCam = toEigen(s.gCam), gObj = toEigen(s.gObj);
    for (vpGravitySolvers::P3PPairRule rule :
         {vpGravitySolvers::P3PPairRule::BestThirdPoint, vpGravitySolvers::P3PPairRule::WidestPair}) {
      vpGravitySolvers::Pose fast, reference;
      const bool okFast = vpGravitySolvers::p3p(gCam, gObj, x.data(), X.data(), fast, rule);
      const bool okReference = (rule == vpGravitySolvers::P3PPairRule::WidestPair)
                                   ? referenceWidestPair(gCam, gObj, x, X, reference)
                                   : referenceBestThirdPoint(gCam, gObj, x, X, reference);
      ASSERT_EQ(okFast, okReference) << "trial " << trial;
      if (!okFast)
        continue;
      ++compared;
      EXPECT_LT((fast.R - reference.R).norm(), 1e-9) << "trial " << trial;
      EXPECT_LT((fast.t - reference.t).norm(), 1e-9 * (1.0 + reference.t.norm())) << "trial " << trial;
    }
    vpGravitySolvers::Pose best, widest;
    if (vpGravitySolvers::p3p(gCam, gObj, x.data(), X.data(), best) &&
        vpGravitySolvers::p3p(gCam, gObj, x.data(), X.data(), widest, vpGravitySolvers::P3PPairRule::WidestPair))
      pairsDiffer += (best.R - widest.R).norm() > 1e-12;
  }
  EXPECT_GT(compared, 2 * 19000);
  EXPECT_GT(pairsDiffer, 1000); // the two rules were both exercised
}

TEST(PoseGravitySolversFastPath, BearingScaleDoesNotMatter)
{
  SceneGenerator gen(23);
  std::vector<Eigen::Vector3d> x, X;
  const double scales[3] = {0.01, 3.0, 250.0};
  for (int trial = 0; trial < 5000; ++trial) {
    const Scene s = gen.scene(3);
    toSolverInput(s.points, x, X);
    const Eigen::Vector3d gCam = toEigen(s.gCam), gObj = toEigen(s.gObj);
    vpGravitySolvers::Pose plain, scaled;
    ASSERT_TRUE(vpGravitySolvers::p3p(gCam, gObj, x.data(), X.data(), plain));
    std::vector<Eigen::Vector3d> xs = x;
    for (int i = 0; i < 3; ++i)
      xs[i] *= scales[(trial + i) % 3];
    ASSERT_TRUE(vpGravitySolvers::p3p(gCam, gObj, xs.data(), X.data(), scaled));
    EXPECT_LT((plain.R - scaled.R).norm(), 1e-10) << "trial " << trial;
    EXPECT_LT((plain.t - scaled.t).norm(), 1e-10 * plain.t.norm()) << "trial " << trial;
  }
}
