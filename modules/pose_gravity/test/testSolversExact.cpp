/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Exact data over 1e5 random scenes simulated with ViSP's camera: P3P and LEAST_SQUARES return
  the true pose and the truth is among the P2P candidates. With exact data only rounding remains:
  the required bounds are a median error <= 1e-10 and a maximum <= 1e-6 (the maximum is governed by
  the rare ill-conditioned draws, e.g. near a double root of the P2P equation).
*/
#include <algorithm>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpGravitySolvers.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
// 100000 scenes; 10000 under the sanitizers (gravity_test::trials).
const int kTrials = trials(100000, 10000);

void reportAndCheck(const char *what, const std::vector<double> &errors)
{
  const double med = median(errors);
  const double worst = *std::max_element(errors.begin(), errors.end());
  std::cout << what << ": " << errors.size() << " poses, median error " << med << ", max " << worst << std::endl;
  EXPECT_LE(med, 1e-10) << what;
  EXPECT_LE(worst, 1e-6) << what;
}

/*!
  On kTrials exact scenes from \e seed (scene k has \e nPoints(k) points), \e solve(scene, x, X, pose)
  must return a pose, and the errors must meet the exact-data bounds of reportAndCheck().
*/
template <typename Count, typename Solve>
void checkExactPoses(const char *what, unsigned int seed, Count nPoints, Solve solve)
{
  SceneGenerator gen(seed);
  std::vector<double> errors;
  std::vector<Eigen::Vector3d> x, X;
  for (int k = 0; k < kTrials; ++k) {
    const Scene s = gen.scene(nPoints(k));
    toSolverInput(s.points, x, X);
    vpGravitySolvers::Pose pose;
    ASSERT_TRUE(solve(s, x, X, pose)) << what << ", scene " << k;
    errors.push_back(poseError(pose, s.cMo));
  }
  reportAndCheck(what, errors);
}
} // namespace

TEST(PoseGravitySolversExact, P2PTruthAmongCandidates)
{
  SceneGenerator gen(11);
  std::vector<double> errors;
  std::vector<Eigen::Vector3d> x, X;
  int twoCandidates = 0;
  for (int k = 0; k < kTrials; ++k) {
    const Scene s = gen.scene(2);
    toSolverInput(s.points, x, X);
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    const int count = vpGravitySolvers::p2p(toEigen(s.gCam), toEigen(s.gObj), x.data(), X.data(), poses, &p2pCase);
    ASSERT_EQ(p2pCase, vpGravitySolvers::P2PCase::TwoSolutions);
    ASSERT_GE(count, 1);
    twoCandidates += (count == 2);
    double best = std::numeric_limits<double>::infinity();
    for (int m = 0; m < count; ++m)
      best = std::min(best, poseError(poses[m], s.cMo));
    errors.push_back(best);
  }
  std::cout << "P2P: two admissible candidates in " << twoCandidates << " of " << kTrials << " scenes" << std::endl;
  reportAndCheck("P2P (best candidate)", errors);
}

TEST(PoseGravitySolversExact, P3PGivesTruth)
{
  checkExactPoses(
      "P3P", 12, [](int) { return 3; },
      [](const Scene &s, const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X,
         vpGravitySolvers::Pose &pose) {
        return vpGravitySolvers::p3p(toEigen(s.gCam), toEigen(s.gObj), x.data(), X.data(), pose);
      });
}

TEST(PoseGravitySolversExact, LeastSquaresGivesTruth)
{
  checkExactPoses(
      "LEAST_SQUARES", 13, [](int k) { return 3 + k % 8; }, // 3 to 10 points
      [](const Scene &s, const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X,
         vpGravitySolvers::Pose &pose) {
        return vpGravitySolvers::leastSquares(toEigen(s.gCam), toEigen(s.gObj), x.data(), X.data(),
                                              static_cast<int>(x.size()), pose);
      });
}

TEST(PoseGravitySolversExact, TranslationFromTrueRotation)
{
  SceneGenerator gen(14);
  std::vector<Eigen::Vector3d> x, X;
  for (int k = 0; k < 1000; ++k) {
    const Scene s = gen.scene(2 + k % 5);
    toSolverInput(s.points, x, X);
    Eigen::Vector3d t;
    ASSERT_TRUE(vpGravitySolvers::translationFromRotation(rotationOf(s.cMo), x.data(), X.data(),
                                                          static_cast<int>(x.size()), t));
    EXPECT_LT((t - translationOf(s.cMo)).norm() / translationOf(s.cMo).norm(), 1e-10);
  }
  // All rays parallel: the translation is not observable.
  const Eigen::Vector3d xs[2] = {Eigen::Vector3d(0.1, 0.2, 1.0), Eigen::Vector3d(0.2, 0.4, 2.0)};
  const Eigen::Vector3d Xs[2] = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  Eigen::Vector3d t;
  EXPECT_FALSE(vpGravitySolvers::translationFromRotation(Eigen::Matrix3d::Identity(), xs, Xs, 2, t));
}
