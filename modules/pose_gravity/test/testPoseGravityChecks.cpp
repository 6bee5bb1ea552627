/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  The checks that keep vpPoseGravity from returning confident wrong poses, against ground truth:
  RANSAC consensus against chance, inlier recall of the default threshold, repeated points, the
  gravity sign mix-up, a wrong IMU-to-camera rotation, the P3P pair choice on a vertical pole, the
  global minimum of LEAST_SQUARES and its reweighting, the robust refinement and the covariance
  (Monte-Carlo NEES). Scenes: gravity_test_scene.h (1 m object 2 to 8 m away), noise in px at f = 800.

  Bounds: measured values are printed; the bounds sit at the targets of the module's documentation
  (success on pure outliers <= 1 %, sign mix-up accepted >10 deg off <= 1 %, mean NEES within 20 % of
  its dimension, ...), the measured values being well inside them.
*/
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpImage.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
const double kPixel = 1.0 / 800.0;
const double kHalfWidth = 320.0 * kPixel, kHalfHeight = 240.0 * kPixel;

double degrees(double rad) { return rad * 180.0 / 3.14159265358979323846; }

// Rotation angle between two poses (rad).
double rotationAngle(const vpHomogeneousMatrix &A, const vpHomogeneousMatrix &B)
{
  const Eigen::AngleAxisd aa(rotationOf(A) * rotationOf(B).transpose());
  return std::abs(aa.angle());
}

vpColVector randomVector(SceneGenerator &gen) { return toVisp(gen.unitVector()); }

// n random points in the image with random object points and gravities: no pose explains them.
vpPoseGravity pureOutliers(SceneGenerator &gen, int n)
{
  vpPoseGravity pose;
  pose.setCameraGravity(randomVector(gen));
  pose.setObjectGravity(randomVector(gen));
  for (int i = 0; i < n; ++i) {
    vpPoint P(gen.uniform(-1, 1), gen.uniform(-1, 1), gen.uniform(-1, 1));
    P.set_x(gen.uniform(-kHalfWidth, kHalfWidth));
    P.set_y(gen.uniform(-kHalfHeight, kHalfHeight));
    pose.addPoint(P);
  }
  return pose;
}
} // namespace

TEST(PoseGravityChecks, RansacOnPureOutliersFindsNoConsensus)
{
  SceneGenerator gen(61);
  // 300 runs per case; 100 under the sanitizers (gravity_test::trials), where the same bounds hold.
  const int runs = trials(300, 100);
  for (int n : {40, 200})
    for (double threshold : {-1.0, 5e-3}) { // -1: the default
      int success = 0;
      for (int k = 0; k < runs; ++k) {
        vpPoseGravity pose = pureOutliers(gen, n);
        if (threshold > 0)
          pose.setRansacThreshold(threshold);
        pose.setRansacSeed(static_cast<unsigned int>(k));
        vpHomogeneousMatrix cMo;
        const bool ok = pose.computePose(vpPoseGravity::RANSAC, cMo);
        success += ok;
        if (!ok) {
          EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_NO_CONSENSUS);
        }
      }
      std::cout << "pure outliers, n = " << n << ", threshold " << (threshold > 0 ? threshold : 4e-3) << ": " << success
                << " / " << runs << " successes" << std::endl;
      EXPECT_LE(success, runs / 100) << "n = " << n;
    }
  // The significance test is what rejects them: without it a loose threshold finds "consensus".
  int withoutTest = 0;
  const int runsWithoutTest = trials(100, 30);
  for (int k = 0; k < runsWithoutTest; ++k) {
    vpPoseGravity pose = pureOutliers(gen, 200);
    pose.setRansacThreshold(1e-2);
    pose.setRansacSignificance(1.0);
    pose.setRansacNbInliersToReachConsensus(3);
    vpHomogeneousMatrix cMo;
    withoutTest += pose.computePose(vpPoseGravity::RANSAC, cMo);
  }
  std::cout << "pure outliers, n = 200, threshold 1e-2, no significance test, consensus 3: " << withoutTest << " / "
            << runsWithoutTest << " successes" << std::endl;
  EXPECT_GT(withoutTest, runsWithoutTest / 2);
}

TEST(PoseGravityChecks, RansacDefaultThresholdKeepsTheInliers)
{
  // 40 inliers with 1 px noise + 20 outliers: the default threshold (3.2 px) keeps >= 95 % of the
  // true inliers (a 1 px inlier's error is Rayleigh: P(r > 3.2 px) = 0.6 %, plus the model error).
  SceneGenerator gen(62);
  double kept = 0.0, total = 0.0;
  int falseInliers = 0;
  for (int k = 0; k < 100; ++k) {
    Scene s = gen.scene(60);
    gen.addImageNoise(s.points, kPixel);
    for (int i = 40; i < 60; ++i) {
      s.points[static_cast<size_t>(i)].set_x(gen.uniform(-kHalfWidth, kHalfWidth));
      s.points[static_cast<size_t>(i)].set_y(gen.uniform(-kHalfHeight, kHalfHeight));
    }
    vpPoseGravity pose = estimatorFor(s);
    pose.setRansacSeed(static_cast<unsigned int>(k));
    vpHomogeneousMatrix cMo;
    ASSERT_TRUE(pose.computePose(vpPoseGravity::RANSAC, cMo)) << vpPoseGravity::getStatusMessage(pose.getStatus());
    EXPECT_EQ(pose.getRansacNbInliers(), pose.getRansacInlierIndex().size());
    EXPECT_LT(rotationAngle(cMo, s.cMo), 0.02);
    total += 40;
    for (unsigned int i : pose.getRansacInlierIndex()) {
      kept += (i < 40);
      falseInliers += (i >= 40);
    }
  }
  std::cout << "default threshold: " << 100.0 * kept / total << " % of the true inliers kept, " << falseInliers
            << " outliers taken in 100 trials" << std::endl;
  EXPECT_GE(kept / total, 0.95);
  EXPECT_LE(falseInliers, 10);
}

TEST(PoseGravityChecks, RansacMinimumConsensus)
{
  // 6 exact inliers among 30 outliers: found with the default minimum (4), refused with 7.
  SceneGenerator gen(63);
  Scene s = gen.scene(36);
  for (int i = 6; i < 36; ++i) {
    s.points[static_cast<size_t>(i)].set_x(gen.uniform(-kHalfWidth, kHalfWidth));
    s.points[static_cast<size_t>(i)].set_y(gen.uniform(-kHalfHeight, kHalfHeight));
  }
  vpPoseGravity pose = estimatorFor(s);
  EXPECT_EQ(pose.getRansacNbInliersToReachConsensus(), 4u);
  pose.setRansacMaxTrials(5000);
  vpHomogeneousMatrix cMo;
  ASSERT_TRUE(pose.computePose(vpPoseGravity::RANSAC, cMo));
  EXPECT_EQ(pose.getRansacNbInliers(), 6u);
  EXPECT_LT(poseError(cMo, s.cMo), 1e-6);
  pose.setRansacNbInliersToReachConsensus(7);
  EXPECT_FALSE(pose.computePose(vpPoseGravity::RANSAC, cMo));
  EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_NO_CONSENSUS);
  EXPECT_EQ(pose.getRansacNbInliers(), 0u);
}

TEST(PoseGravityChecks, RansacFiltersRepeatedPoints)
{
  // Real matches repeat points: 20 true points, then 10 of them again with a wrong image point and
  // 5 exact copies. RANSAC must not throw and must return the true points as inliers, once each.
  SceneGenerator gen(64);
  for (int trial = 0; trial < 20; ++trial) {
    Scene s = gen.scene(20);
    gen.addImageNoise(s.points, kPixel);
    std::vector<vpPoint> points = s.points;
    for (int i = 0; i < 10; ++i) {
      vpPoint P = s.points[static_cast<size_t>(i)];
      P.set_x(gen.uniform(-kHalfWidth, kHalfWidth));
      P.set_y(gen.uniform(-kHalfHeight, kHalfHeight));
      points.push_back(P);
    }
    for (int i = 10; i < 15; ++i)
      points.push_back(s.points[static_cast<size_t>(i)]);
    for (vpPoseGravity::RANSAC_FILTER_FLAGS flag :
         {vpPoseGravity::PREFILTER_DEGENERATE_POINTS, vpPoseGravity::NO_FILTER}) {
      vpPoseGravity pose;
      pose.setCameraGravity(s.gCam);
      pose.setObjectGravity(s.gObj);
      pose.addPoints(points);
      pose.setRansacFilterFlag(flag);
      pose.setRansacSeed(static_cast<unsigned int>(trial));
      vpHomogeneousMatrix cMo;
      ASSERT_NO_THROW(ASSERT_TRUE(pose.computePose(vpPoseGravity::RANSAC, cMo)));
      EXPECT_LT(rotationAngle(cMo, s.cMo), 0.02);
      std::vector<unsigned int> inliers = pose.getRansacInlierIndex();
      if (flag == vpPoseGravity::PREFILTER_DEGENERATE_POINTS) {
        // Each object point once: the copies (indices >= 20) are filtered out.
        for (unsigned int i : inliers)
          EXPECT_LT(i, 20u);
        EXPECT_GE(inliers.size(), 19u);
      }
    }
  }
}

TEST(PoseGravityChecks, DuplicateSearchScalesToLargeSets)
{
  // 20000 points on a planar grid (many equal coordinates, the hard case of a sorted search), one
  // duplicate far apart in the list: found, named in the message, quickly (O(n log n)).
  vpPoseGravity pose;
  pose.setCameraGravity(toVisp(Eigen::Vector3d(0, 1, 0)));
  pose.setObjectGravity(toVisp(Eigen::Vector3d(0, 1, 0)));
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 100; ++j) {
      vpPoint P(0.01 * i, 0.01 * j, 0.0);
      P.set_x(0.001 * i);
      P.set_y(0.001 * j);
      pose.addPoint(P);
    }
  vpPoint copy = pose.getPoints()[123];
  pose.addPoint(copy);
  vpHomogeneousMatrix cMo;
  try {
    pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo);
    ADD_FAILURE() << "no exception";
  } catch (const vpPoseGravityException &e) {
    EXPECT_EQ(e.getCode(), vpPoseGravityException::degeneratePointsError);
    EXPECT_NE(e.getStringMessage().find("123 and 20000"), std::string::npos) << e.getStringMessage();
  }
}

TEST(PoseGravityChecks, GravitySignMixUpIsRefused)
{
  // The camera gravity passed as the raw accelerometer reading (specific force, pointing up).
  SceneGenerator gen(65);
  const int runs = 500;
  for (vpPoseGravity::vpPoseGravityMethod method : {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES})
    for (double noise : {0.0, kPixel}) {
      int wrongAccepted = 0, diagnosed = 0;
      for (int k = 0; k < runs; ++k) {
        Scene s = gen.scene(method == vpPoseGravity::P3P ? 3 : 8);
        gen.addImageNoise(s.points, noise);
        s.gCam = -s.gCam;
        vpPoseGravity pose = estimatorFor(s);
        vpHomogeneousMatrix cMo;
        const bool ok = pose.computePose(method, cMo);
        wrongAccepted += ok && degrees(rotationAngle(cMo, s.cMo)) > 10.0;
        diagnosed += pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED;
      }
      std::cout << (method == vpPoseGravity::P3P ? "P3P" : "LEAST_SQUARES 8 points") << ", noise " << noise / kPixel
                << " px: wrong pose accepted " << wrongAccepted << " / " << runs << ", sign reversal diagnosed "
                << diagnosed << " / " << runs << std::endl;
      EXPECT_LE(wrongAccepted, runs / 100);
      EXPECT_GE(diagnosed, runs * 95 / 100);
    }
  EXPECT_FALSE(vpPoseGravity::getStatusMessage(vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED).find("specific force") ==
               std::string::npos);
}

TEST(PoseGravityChecks, RightSignIsAccepted)
{
  // The same check must not refuse correct data: 1 px and two IMUs of 0.01 per component.
  SceneGenerator gen(66);
  int refused = 0;
  const int runs = 1000;
  for (int k = 0; k < runs; ++k) {
    Scene s = gen.scene(3);
    gen.addImageNoise(s.points, kPixel);
    s.gCam = gen.noisyGravity(s.gCam, 0.01);
    s.gObj = gen.noisyGravity(s.gObj, 0.01);
    vpPoseGravity pose = estimatorFor(s);
    vpHomogeneousMatrix cMo;
    refused += !pose.computePose(vpPoseGravity::P3P, cMo);
  }
  std::cout << "right sign, 1 px, sigma_g 0.01: " << refused << " / " << runs << " refused" << std::endl;
  EXPECT_LE(refused, runs / 100);
}

TEST(PoseGravityChecks, WrongImuToCameraRotationIsRefused)
{
  // The camera IMU's reading left in the IMU frame, 30 degrees off the camera frame (about a random
  // axis, so about 20 degrees of tilt on average). Whether the points can reveal it depends on how
  // much of the field of view and of depth they span: a small object far away looks the same tilted
  // by a few tens of degrees once yaw and translation adapt. Here: 12 points spread over a 3 m
  // object 2 to 8 m away, 1 px.
  SceneGenerator gen(67);
  int accepted = 0, calledSwapped = 0;
  const int runs = 300;
  for (int k = 0; k < runs; ++k) {
    Scene s = gen.scene(12, 3.0);
    gen.addImageNoise(s.points, kPixel);
    const Eigen::Vector3d axis = gen.unitVector();
    s.gCam = toVisp(Eigen::AngleAxisd(30.0 * 3.14159265358979323846 / 180.0, axis) * toEigen(s.gCam));
    vpPoseGravity pose = estimatorFor(s);
    vpHomogeneousMatrix cMo;
    if (pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo))
      ++accepted;
    else if (pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SWAPPED)
      ++calledSwapped; // the exchanged vectors absorb the tilt within twice the noise: a wrong diagnosis
    else
      EXPECT_TRUE(pose.getStatus() == vpPoseGravity::STATUS_INCONSISTENT_GRAVITY ||
                  pose.getStatus() == vpPoseGravity::STATUS_BEHIND_CAMERA ||
                  pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED)
          << vpPoseGravity::getStatusMessage(pose.getStatus());
  }
  std::cout << "IMU-to-camera rotation off by 30 deg, LEAST_SQUARES 12 points on 3 m: " << accepted << " / " << runs
            << " accepted, " << calledSwapped << " called an exchange of the gravity vectors" << std::endl;
  EXPECT_LE(accepted, runs / 4);
  EXPECT_LE(calledSwapped, runs / 100); // measured: 1 of 300
}

TEST(PoseGravityChecks, P3PAvoidsTheVerticalPair)
{
  // A pole (A, B along gravity, 2 m) and a point C 0.3 m aside: the widest image pair is the pole,
  // which carries no yaw information; the default rule uses the pairs with C.
  SceneGenerator gen(68);
  std::vector<double> best, widest;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d g = gen.unitVector();
    const Eigen::Vector3d h = g.unitOrthogonal();
    const std::vector<Eigen::Vector3d> X = {Eigen::Vector3d::Zero(), 2.0 * g, 0.3 * h + 1.0 * g};
    Scene s;
    s.cMo = gen.poseLookingAt(X, gen.rotation());
    s.gObj = toVisp(g);
    s.gCam = SceneGenerator::cameraGravity(s.cMo, s.gObj);
    s.points = SceneGenerator::project(X, s.cMo);
    gen.addImageNoise(s.points, kPixel);
    for (int rule = 0; rule < 2; ++rule) {
      vpPoseGravity pose = estimatorFor(s);
      pose.setP3PPairRule(rule == 0 ? vpPoseGravity::P3P_BEST_THIRD_POINT : vpPoseGravity::P3P_WIDEST_PAIR);
      vpHomogeneousMatrix cMo;
      const double e = pose.computePose(vpPoseGravity::P3P, cMo) ? rotationAngle(cMo, s.cMo) : 3.14;
      (rule == 0 ? best : widest).push_back(e);
    }
  }
  std::sort(best.begin(), best.end());
  std::sort(widest.begin(), widest.end());
  std::cout << "pole + point, 1 px: median rotation error " << degrees(best[250]) << " deg (widest pair "
            << degrees(widest[250]) << "), p90 " << degrees(best[450]) << " deg (widest pair " << degrees(widest[450])
            << ")" << std::endl;
  EXPECT_LT(degrees(best[450]), 5.0);
  EXPECT_LT(best[450], widest[450]);
}

TEST(PoseGravityChecks, LeastSquaresIsTheBestMinimum)
{
  // 8 points, one gross outlier. The unweighted solve must return, among the local minima of its
  // algebraic cost (found by a dense scan of the yaw, translation solved linearly at each yaw), the
  // one whose pose has the lowest reprojection error: never a maximum nor another minimum.
  SceneGenerator gen(69);
  std::vector<Eigen::Vector3d> x, X;
  const int steps = 7200;
  const double step = 2.0 * 3.14159265358979323846 / steps;
  int secondMinima = 0;
  // 200 scenes; 50 under the sanitizers (gravity_test::trials), with the same share of two-minima scenes.
  const int scenes = trials(200, 50);
  for (int k = 0; k < scenes; ++k) {
    Scene s = gen.scene(8);
    gen.addImageNoise(s.points, kPixel);
    s.points[3].set_x(gen.uniform(-kHalfWidth, kHalfWidth));
    s.points[3].set_y(gen.uniform(-kHalfHeight, kHalfHeight));
    toSolverInput(s.points, x, X);
    const Eigen::Vector3d gc = toEigen(s.gCam), go = toEigen(s.gObj);
    vpGravitySolvers::Pose pose;
    ASSERT_TRUE(vpGravitySolvers::leastSquares(gc, go, x.data(), X.data(), 8, pose, 0));
    const Eigen::Matrix3d wRc = vpGravitySolvers::uprightRotation(gc), wRo = vpGravitySolvers::uprightRotation(go);
    // (algebraic cost, reprojection error) at a yaw.
    auto costs = [&](double alpha) {
      const Eigen::Matrix3d R = wRc.transpose() * Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitZ()) * wRo;
      Eigen::MatrixXd A(16, 3);
      Eigen::VectorXd b(16);
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d u1(-1, 0, x[i].x()), u2(0, -1, x[i].y()), RX = R * X[i];
        A.row(2 * i) = u1.transpose();
        A.row(2 * i + 1) = u2.transpose();
        b(2 * i) = -u1.dot(RX);
        b(2 * i + 1) = -u2.dot(RX);
      }
      const Eigen::Vector3d t = A.colPivHouseholderQr().solve(b);
      double reprojection = 0.0;
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d P = R * X[i] + t;
        reprojection += P.z() > 0.0 ? (P.head<2>() / P.z() - x[i].head<2>()).squaredNorm()
                                    : std::numeric_limits<double>::infinity();
      }
      return std::make_pair((A * t - b).squaredNorm(), reprojection);
    };
    std::vector<std::pair<double, double> > c(steps);
    for (int a = 0; a < steps; ++a)
      c[a] = costs(-3.14159265358979323846 + a * step);
    double bestAlpha = 0.0, bestReprojection = std::numeric_limits<double>::infinity();
    double lowestAlpha = 0.0, lowest = std::numeric_limits<double>::infinity();
    int minima = 0;
    for (int a = 0; a < steps; ++a) {
      if (!(c[a].first < c[(a + steps - 1) % steps].first && c[a].first <= c[(a + 1) % steps].first))
        continue;
      ++minima;
      const double alpha = -3.14159265358979323846 + a * step;
      if (c[a].second < bestReprojection) {
        bestReprojection = c[a].second;
        bestAlpha = alpha;
      }
      if (c[a].first < lowest) {
        lowest = c[a].first;
        lowestAlpha = alpha;
      }
    }
    if (!(bestReprojection < std::numeric_limits<double>::infinity()))
      bestAlpha = lowestAlpha;
    secondMinima += minima > 1;
    // At the best minimum of the scan, or (two minima of nearly equal reprojection error, which the
    // grid evaluates 1e-3 rad off) at a minimum as good to 1 %; a minimum in any case.
    const Eigen::Matrix3d W = wRc * pose.R * wRo.transpose();
    const double found = std::atan2(W(1, 0), W(0, 0));
    const bool atBest = std::abs(std::remainder(found - bestAlpha, 2.0 * 3.14159265358979323846)) <= 2.0 * step;
    EXPECT_TRUE(atBest || costs(found).second <= 1.01 * bestReprojection) << "trial " << k;
    EXPECT_LE(costs(found).first, std::min(costs(found - 1e-4).first, costs(found + 1e-4).first)) << "trial " << k;
  }
  std::cout << secondMinima << " / " << scenes << " scenes have two minima" << std::endl;
  EXPECT_GT(secondMinima, scenes / 20); // the choice between minima was exercised
}

TEST(PoseGravityChecks, LeastSquaresReweightingApproachesMaximumLikelihood)
{
  // 5 points at 1 to 2 m and 5 at 40 m: the algebraic cost weighs the far ones by depth^2; two
  // inverse-depth passes must bring the 3D error of the near points within 1.2x of the ML pose's.
  SceneGenerator gen(70);
  double err[2] = {0.0, 0.0}, ml = 0.0;
  std::vector<Eigen::Vector3d> x, X;
  for (int k = 0; k < 300; ++k) {
    const vpRotationMatrix cRo = gen.rotation();
    std::vector<Eigen::Vector3d> Pc;
    for (int i = 0; i < 10; ++i) {
      const double z = i < 5 ? gen.uniform(1.0, 2.0) : gen.uniform(38.0, 42.0);
      Pc.emplace_back(gen.uniform(-0.3, 0.3) * z, gen.uniform(-0.25, 0.25) * z, z);
    }
    Scene s;
    const Eigen::Vector3d t(gen.uniform(-1, 1), gen.uniform(-1, 1), gen.uniform(-1, 1));
    s.cMo = vpHomogeneousMatrix(vpTranslationVector(t.x(), t.y(), t.z()), cRo);
    std::vector<Eigen::Vector3d> Xo;
    Xo.reserve(Pc.size());
    for (const Eigen::Vector3d &p : Pc)
      Xo.push_back(rotationOf(s.cMo).transpose() * (p - t));
    s.points = SceneGenerator::project(Xo, s.cMo);
    s.gObj = toVisp(gen.unitVector());
    s.gCam = SceneGenerator::cameraGravity(s.cMo, s.gObj);
    gen.addImageNoise(s.points, kPixel);
    toSolverInput(s.points, x, X);
    auto nearError = [&](const Eigen::Matrix3d &R, const Eigen::Vector3d &tt) {
      double e = 0.0;
      for (int i = 0; i < 5; ++i)
        e += ((R * Xo[i] + tt) - Pc[i]).norm() / 5.0;
      return e;
    };
    for (int passes : {0, 2}) {
      vpGravitySolvers::Pose p;
      ASSERT_TRUE(vpGravitySolvers::leastSquares(toEigen(s.gCam), toEigen(s.gObj), x.data(), X.data(), 10, p, passes));
      err[passes / 2] += nearError(p.R, p.t);
    }
    vpPoseGravity pose = estimatorFor(s);
    pose.setImageStdDev(kPixel);
    vpHomogeneousMatrix M = s.cMo;
    ASSERT_TRUE(pose.refinePose(M));
    ml += nearError(rotationOf(M), translationOf(M));
  }
  std::cout << "near-point 3D error over the ML pose's: " << err[0] / ml << " (algebraic), " << err[1] / ml
            << " (2 reweighting passes)" << std::endl;
  EXPECT_GT(err[0] / ml, 3.0); // the defect is there without reweighting
  EXPECT_LE(err[1] / ml, 1.2);
}

TEST(PoseGravityChecks, RobustRefinementResistsAnOutlier)
{
  // 20 points at 1 px and one of them 40 px off: the squared loss follows the outlier, Huber and
  // Cauchy (scale 3 px) do not.
  SceneGenerator gen(71);
  std::vector<double> clean, none, huber, cauchy;
  for (int k = 0; k < 200; ++k) {
    Scene s = gen.scene(20);
    gen.addImageNoise(s.points, kPixel);
    vpPoseGravity ref = estimatorFor(s);
    ref.setImageStdDev(kPixel);
    vpHomogeneousMatrix M = s.cMo;
    ASSERT_TRUE(ref.refinePose(M));
    clean.push_back(rotationAngle(M, s.cMo));
    const double angle = gen.uniform(0, 6.283);
    s.points[7].set_x(s.points[7].get_x() + 40 * kPixel * std::cos(angle));
    s.points[7].set_y(s.points[7].get_y() + 40 * kPixel * std::sin(angle));
    for (vpPoseGravity::vpRobustLoss loss :
         {vpPoseGravity::LOSS_NONE, vpPoseGravity::LOSS_HUBER, vpPoseGravity::LOSS_CAUCHY}) {
      vpPoseGravity pose = estimatorFor(s);
      pose.setImageStdDev(kPixel);
      pose.setRefineLoss(loss, 3 * kPixel);
      vpHomogeneousMatrix cMo = s.cMo;
      ASSERT_TRUE(pose.refinePose(cMo));
      (loss == vpPoseGravity::LOSS_NONE    ? none
       : loss == vpPoseGravity::LOSS_HUBER ? huber
                                           : cauchy)
          .push_back(rotationAngle(cMo, s.cMo));
    }
  }
  const double c = median(clean), n = median(none), h = median(huber), y = median(cauchy);
  std::cout << "median rotation error (deg): no outlier " << degrees(c) << ", with the outlier: squared " << degrees(n)
            << ", Huber " << degrees(h) << ", Cauchy " << degrees(y) << std::endl;
  EXPECT_GT(n, 3.0 * c);
  EXPECT_LT(h, 2.0 * c);
  EXPECT_LT(y, 1.3 * c);
}

namespace
{
// e^T C^+ e with the pseudo-inverse of a rank-deficient covariance.
double nees(const vpMatrix &C, const vpColVector &e)
{
  const vpMatrix Cinv = C.pseudoInverse(1e-9);
  return e.t() * (Cinv * e);
}

// Error of cMo against the truth in the covariance's parameters (t, theta), theta on the left.
vpColVector poseError6(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &truth)
{
  const Eigen::AngleAxisd aa(rotationOf(cMo) * rotationOf(truth).transpose());
  const Eigen::Vector3d theta = aa.angle() * aa.axis();
  const Eigen::Vector3d dt = translationOf(cMo) - translationOf(truth);
  vpColVector e(6);
  for (unsigned int i = 0; i < 3; ++i) {
    e[i] = dt[static_cast<int>(i)];
    e[i + 3] = theta[static_cast<int>(i)];
  }
  return e;
}
} // namespace

TEST(PoseGravityChecks, CovarianceIsConsistent)
{
  // Monte-Carlo NEES: exact gravity (4 DOF, rank-4 covariance) and noisy gravity with both IMU
  // sigmas set (6 DOF); mean NEES within 20 % of the dimension over 1000 trials (its standard error
  // is sqrt(2 d / 1000), about 2 % of d).
  SceneGenerator gen(72);
  const double sigmaC = 0.01, sigmaO = 0.005;
  double sum4 = 0.0, sum6 = 0.0;
  const int runs = 1000;
  for (int k = 0; k < runs; ++k) {
    for (int model = 0; model < 2; ++model) {
      Scene s = gen.scene(10);
      gen.addImageNoise(s.points, kPixel);
      if (model == 1) {
        s.gCam = gen.noisyGravity(s.gCam, sigmaC);
        s.gObj = gen.noisyGravity(s.gObj, sigmaO);
      }
      vpPoseGravity pose = estimatorFor(s);
      pose.setImageStdDev(kPixel);
      pose.setCameraGravityStdDev(model == 1 ? sigmaC : 0.0);
      pose.setObjectGravityStdDev(model == 1 ? sigmaO : 0.0);
      pose.setCovarianceComputation(true);
      vpHomogeneousMatrix cMo;
      ASSERT_TRUE(pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
      ASSERT_TRUE(pose.refinePose(cMo));
      const vpMatrix C = pose.getCovarianceMatrix();
      ASSERT_EQ(C.getRows(), 6u);
      (model == 0 ? sum4 : sum6) += nees(C, poseError6(cMo, s.cMo));
    }
  }
  std::cout << "mean NEES: " << sum4 / runs << " (exact gravity, dimension 4), " << sum6 / runs
            << " (noisy gravity, dimension 6)" << std::endl;
  EXPECT_NEAR(sum4 / runs, 4.0, 0.8);
  EXPECT_NEAR(sum6 / runs, 6.0, 1.2);
  vpPoseGravity fresh;
  EXPECT_THROW(fresh.getCovarianceMatrix(), vpPoseGravityException);
}

// P3P solves the first three points: its covariance is theirs, whatever other points were added. With all of
// them it was 28 times too small in variance when 20 were added (a mean NEES of 182 for 4 expected). P3P's
// closed form is not the maximum-likelihood fit of its three points, so its error exceeds that covariance
// somewhat (the mean NEES printed); refinePose() on the three meets it.
TEST(PoseGravityChecks, P3PCovarianceIsThatOfItsThreePoints)
{
  SceneGenerator gen(73);
  double sum = 0.0;
  const int runs = trials(500, 50);
  for (int k = 0; k < runs; ++k) {
    Scene s = gen.scene(20);
    gen.addImageNoise(s.points, kPixel);
    vpPoseGravity all = estimatorFor(s), three = estimatorFor(s, true, true, false);
    three.addPoints(std::vector<vpPoint>(s.points.begin(), s.points.begin() + 3));
    for (vpPoseGravity *pose : {&all, &three}) {
      pose->setImageStdDev(kPixel);
      pose->setCovarianceComputation(true);
    }
    vpHomogeneousMatrix cMoAll, cMoThree;
    if (!all.computePose(vpPoseGravity::P3P, cMoAll))
      continue;
    ASSERT_TRUE(three.computePose(vpPoseGravity::P3P, cMoThree));
    const vpMatrix C = all.getCovarianceMatrix(), C3 = three.getCovarianceMatrix();
    for (unsigned int i = 0; i < 6; ++i)
      for (unsigned int j = 0; j < 6; ++j)
        ASSERT_NEAR(C[i][j], C3[i][j], 1e-9 * (std::fabs(C3[i][i]) + std::fabs(C3[j][j]))) << k;
    sum += nees(C, poseError6(cMoAll, s.cMo));
  }
  std::cout << "P3P, 20 points added: mean NEES " << sum / runs << " (dimension 4)" << std::endl;
  EXPECT_GT(sum / runs, 3.0);
  EXPECT_LT(sum / runs, 12.0);
}

// A pose whose covariance is singular is still a pose: four exact points on one vertical line (the yaw
// unobservable). refinePose() refused it (STATUS_REFINEMENT_FAILED) when the covariance was asked for, and
// returned it otherwise.
TEST(PoseGravityChecks, ARefinedPoseWithASingularCovarianceIsKept)
{
  SceneGenerator gen(74);
  const Scene s = gen.scene(4);
  const Eigen::Vector3d base(s.points[0].get_oX(), s.points[0].get_oY(), s.points[0].get_oZ());
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < 4; ++i)
    X.push_back(base + 0.2 * i * toEigen(s.gObj));
  for (bool covariance : {false, true}) {
    vpPoseGravity pose;
    pose.setCameraGravity(s.gCam);
    pose.setObjectGravity(s.gObj);
    pose.addPoints(SceneGenerator::project(X, s.cMo));
    pose.setImageStdDev(kPixel);
    pose.setCovarianceComputation(covariance);
    vpHomogeneousMatrix cMo = s.cMo;
    EXPECT_TRUE(pose.refinePose(cMo)) << covariance;
    EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_OK);
    EXPECT_LT(translationError(cMo, s.cMo), 1e-9);
    EXPECT_THROW(pose.getCovarianceMatrix(), vpPoseGravityException); // singular: none
  }
}

TEST(PoseGravityChecks, DrawPutsTheFrameIntoThePixels)
{
  vpImage<unsigned char> I(480, 640, 0);
  vpImage<vpRGBa> C(480, 640, vpRGBa(0, 0, 0));
  const vpCameraParameters cam(800, 800, 320, 240);
  const vpHomogeneousMatrix cMo(0.0, 0.0, 2.0, 0.3, 0.2, 0.1);
  vpPoseGravity::draw(I, cMo, cam, 0.2, 255, 2);
  vpPoseGravity::draw(C, cMo, cam, 0.2);
  // The origin projects at the principal point; the axes are 0.2 m long at 2 m: ~80 px.
  EXPECT_EQ(I[240][320], 255);
  unsigned int lit = 0, litColour = 0;
  for (unsigned int r = 0; r < 480; ++r)
    for (unsigned int c = 0; c < 640; ++c) {
      lit += I[r][c] > 0;
      litColour += (C[r][c].R + C[r][c].G + C[r][c].B) > 0;
    }
  EXPECT_GT(lit, 150u);
  EXPECT_GT(litColour, 150u);
}
