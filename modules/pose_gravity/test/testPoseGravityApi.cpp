/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpPoseGravity facade: input validation (every bad input throws vpPoseGravityException with the
  documented code), statuses, computeResidual() against a hand computation, candidate ordering.
*/
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
vpColVector vec(std::initializer_list<double> values)
{
  vpColVector v(static_cast<unsigned int>(values.size()));
  unsigned int i = 0;
  for (double x : values)
    v[i++] = x;
  return v;
}

// Runs f and checks that it throws vpPoseGravityException with the given code.
void expectThrowCode(const std::function<void()> &f, int code, const char *what)
{
  try {
    f();
    ADD_FAILURE() << what << ": no exception";
  } catch (const vpPoseGravityException &e) {
    EXPECT_EQ(e.getCode(), code) << what << ": " << e.getStringMessage();
    EXPECT_FALSE(e.getStringMessage().empty());
  } catch (...) {
    ADD_FAILURE() << what << ": wrong exception type";
  }
}
} // namespace

TEST(PoseGravityApi, BadGravityThrows)
{
  vpPoseGravity pose;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const int code = vpPoseGravityException::badGravityError;
  for (const vpColVector &g : {vec({0, 0, 0}), vec({nan, 0, 1}), vec({0, inf, 1}), vec({0, 1}), vec({0, 0, 1, 0})}) {
    expectThrowCode([&] { pose.setCameraGravity(g); }, code, "setCameraGravity");
    expectThrowCode([&] { pose.setObjectGravity(g); }, code, "setObjectGravity");
  }
  // Any positive norm is accepted and normalised.
  pose.setCameraGravity(vec({0, 9.81, 0}));
  EXPECT_NEAR(pose.getCameraGravity()[1], 1.0, 1e-15);
  pose.setObjectGravity(vec({1e-200, 0, 0}));
  EXPECT_NEAR(pose.getObjectGravity()[0], 1.0, 1e-15);
  pose.setObjectGravity(vec({1e300, -1e300, 0}));
  EXPECT_NEAR(pose.getObjectGravity()[1], -std::sqrt(0.5), 1e-15);
}

TEST(PoseGravityApi, UnsetGravityThrows)
{
  SceneGenerator gen(31);
  const Scene s = gen.scene(4);
  vpHomogeneousMatrix cMo;
  const int code = vpPoseGravityException::badGravityError;
  vpPoseGravity noCamera = estimatorFor(s, false, true);
  expectThrowCode([&] { noCamera.computePose(vpPoseGravity::P3P, cMo); }, code, "camera gravity unset");
  vpPoseGravity noObject = estimatorFor(s, true, false);
  expectThrowCode([&] { noObject.computePose(vpPoseGravity::LEAST_SQUARES, cMo); }, code, "object gravity unset");
  expectThrowCode([&] { noObject.computePoseCandidates(); }, code, "object gravity unset (candidates)");
  expectThrowCode([&] { noObject.refinePose(cMo); }, code, "object gravity unset (refine)");
}

TEST(PoseGravityApi, TooFewPointsThrows)
{
  SceneGenerator gen(32);
  const Scene s = gen.scene(3);
  vpHomogeneousMatrix cMo;
  const int code = vpPoseGravityException::notEnoughPointError;
  vpPoseGravity pose = estimatorFor(s, true, true, false);
  expectThrowCode([&] { pose.computePoseCandidates(); }, code, "candidates, 0 points");
  pose.addPoint(s.points[0]);
  expectThrowCode([&] { pose.computePoseCandidates(); }, code, "candidates, 1 point");
  pose.addPoint(s.points[1]);
  EXPECT_NO_THROW(pose.computePoseCandidates());
  for (vpPoseGravity::vpPoseGravityMethod method :
       {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES, vpPoseGravity::RANSAC})
    expectThrowCode([&] { pose.computePose(method, cMo); }, code, "2 points");
  pose.addPoint(s.points[2]);
  for (vpPoseGravity::vpPoseGravityMethod method :
       {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES, vpPoseGravity::RANSAC})
    EXPECT_NO_THROW(pose.computePose(method, cMo));
  pose.clearPoint();
  EXPECT_TRUE(pose.getPoints().empty());
  expectThrowCode([&] { pose.computePose(vpPoseGravity::P3P, cMo); }, code, "after clearPoint");
}

TEST(PoseGravityApi, NonFiniteCoordinatesThrow)
{
  SceneGenerator gen(33);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vpHomogeneousMatrix cMo;
  for (int which = 0; which < 5; ++which)
    for (double bad : {nan, inf, -inf}) {
      Scene s = gen.scene(4);
      vpPoint &P = s.points[which % 3];
      double oX = P.get_oX(), oY = P.get_oY(), oZ = P.get_oZ();
      if (which == 0)
        oX = bad;
      if (which == 1)
        oY = bad;
      if (which == 2)
        oZ = bad;
      P.setWorldCoordinates(oX, oY, oZ);
      if (which == 3)
        P.set_x(bad);
      if (which == 4)
        P.set_y(bad);
      vpPoseGravity pose = estimatorFor(s);
      const int code = vpPoseGravityException::badPointError;
      for (vpPoseGravity::vpPoseGravityMethod method :
           {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES, vpPoseGravity::RANSAC})
        expectThrowCode([&] { pose.computePose(method, cMo); }, code, "non-finite coordinate");
      if (which % 3 < 2)
        expectThrowCode([&] { pose.computePoseCandidates(); }, code, "non-finite coordinate (candidates)");
    }
}

TEST(PoseGravityApi, DuplicateObjectPointsThrow)
{
  SceneGenerator gen(34);
  vpHomogeneousMatrix cMo;
  const int code = vpPoseGravityException::degeneratePointsError;
  Scene s = gen.scene(4);
  // Same object point, different image point (a wrong match): within 1e-12 relative -> duplicate.
  const vpPoint &A = s.points[0];
  const double scale = std::max({std::abs(A.get_oX()), std::abs(A.get_oY()), std::abs(A.get_oZ())});
  s.points[1].setWorldCoordinates(A.get_oX() + 0.5e-12 * scale, A.get_oY(), A.get_oZ());
  vpPoseGravity pose = estimatorFor(s);
  for (vpPoseGravity::vpPoseGravityMethod method : {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES})
    expectThrowCode([&] { pose.computePose(method, cMo); }, code, "duplicate points");
  // RANSAC filters repeated points (a wrong match repeating a point is common) instead of throwing.
  EXPECT_NO_THROW(pose.computePose(vpPoseGravity::RANSAC, cMo));
  expectThrowCode([&] { pose.computePoseCandidates(); }, code, "duplicate points (candidates)");
  // Duplicate among later points only matters for the methods that use them.
  Scene s2 = gen.scene(5);
  s2.points[4].setWorldCoordinates(s2.points[3].get_oX(), s2.points[3].get_oY(), s2.points[3].get_oZ());
  vpPoseGravity pose2 = estimatorFor(s2);
  EXPECT_NO_THROW(pose2.computePose(vpPoseGravity::P3P, cMo));
  expectThrowCode([&] { pose2.computePose(vpPoseGravity::LEAST_SQUARES, cMo); }, code, "late duplicate");
  // Distinct but close points (1e-9 relative) are legal.
  Scene s3 = gen.scene(4);
  const vpPoint &B = s3.points[0];
  s3.points[1].setWorldCoordinates(B.get_oX() + 1e-9, B.get_oY(), B.get_oZ());
  s3.points[1].track(s3.cMo);
  vpPoseGravity pose3 = estimatorFor(s3);
  EXPECT_NO_THROW(pose3.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
}

TEST(PoseGravityApi, CollinearPointsThrowForP3P)
{
  SceneGenerator gen(35);
  Scene s = gen.scene(4);
  const Eigen::Vector3d A = toEigen(s.points[0].oP), B = toEigen(s.points[1].oP);
  const Eigen::Vector3d C = A + 2.5 * (B - A);
  s.points[2] = SceneGenerator::project({C}, s.cMo)[0];
  vpPoseGravity pose = estimatorFor(s);
  vpHomogeneousMatrix cMo;
  expectThrowCode([&] { pose.computePose(vpPoseGravity::P3P, cMo); }, vpPoseGravityException::degeneratePointsError,
                  "collinear P3P");
  // Least squares uses the fourth point too and does not need non-collinear points.
  EXPECT_TRUE(pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
  EXPECT_LT(poseError(cMo, s.cMo), 1e-9);
}

TEST(PoseGravityApi, BadSettingsThrow)
{
  vpPoseGravity pose;
  const int code = vpPoseGravityException::badParameterError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectThrowCode([&] { pose.setRansacThreshold(0.0); }, code, "threshold 0");
  expectThrowCode([&] { pose.setRansacThreshold(nan); }, code, "threshold NaN");
  expectThrowCode([&] { pose.setRansacMaxTrials(0); }, code, "max trials 0");
  expectThrowCode([&] { pose.setRansacProbability(1.0); }, code, "probability 1");
  expectThrowCode([&] { pose.setImageStdDev(0.0); }, code, "image sigma 0");
  expectThrowCode([&] { pose.setGravityStdDev(-1.0); }, code, "gravity sigma < 0");
  EXPECT_NO_THROW(pose.setGravityStdDev(0.0));
}

TEST(PoseGravityApi, ComputeResidualMatchesHandComputation)
{
  // Identity rotation, camera 2 m behind the object origin: point (X, Y, Z) projects to
  // (X / (Z + 2), Y / (Z + 2)). Image points offset by known amounts.
  vpHomogeneousMatrix cMo(0.0, 0.0, 2.0, 0.0, 0.0, 0.0);
  std::vector<vpPoint> points;
  const double coords[3][3] = {{0.0, 0.0, 0.0}, {0.2, -0.1, 0.0}, {0.1, 0.3, 2.0}};
  const double offsets[3][2] = {{0.01, 0.0}, {0.0, -0.02}, {0.003, 0.004}};
  for (int i = 0; i < 3; ++i) {
    vpPoint P(coords[i][0], coords[i][1], coords[i][2]);
    P.set_x(coords[i][0] / (coords[i][2] + 2.0) + offsets[i][0]);
    P.set_y(coords[i][1] / (coords[i][2] + 2.0) + offsets[i][1]);
    points.push_back(P);
  }
  vpPoseGravity pose;
  pose.addPoints(points);
  // 0.01^2 + 0.02^2 + 0.003^2 + 0.004^2 = 1e-4 + 4e-4 + 9e-6 + 1.6e-5 = 5.25e-4
  EXPECT_NEAR(pose.computeResidual(cMo), 5.25e-4, 1e-15);
}

TEST(PoseGravityApi, StatusesAndCandidateOrder)
{
  SceneGenerator gen(36);
  vpPoseGravity pose;
  EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_NOT_COMPUTED);
  EXPECT_FALSE(vpPoseGravity::getStatusMessage(vpPoseGravity::STATUS_VERTICAL_RAY).empty());
  int twoCandidates = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Scene s = gen.scene(2);
    vpPoseGravity p = estimatorFor(s);
    const std::vector<vpHomogeneousMatrix> candidates = p.computePoseCandidates();
    ASSERT_EQ(p.getStatus(), vpPoseGravity::STATUS_OK);
    ASSERT_FALSE(candidates.empty());
    if (candidates.size() == 2) {
      // Both are turns about gravity of each other, ordered by increasing yaw: cRo = wRc^T Rz(yaw) wRo
      // with the upright frames of vpGravitySolvers::uprightRotation().
      ++twoCandidates;
      const Eigen::Matrix3d wRc = vpGravitySolvers::uprightRotation(toEigen(s.gCam));
      const Eigen::Matrix3d wRo = vpGravitySolvers::uprightRotation(toEigen(s.gObj));
      double yaw[2];
      for (int k = 0; k < 2; ++k) {
        const Eigen::Matrix3d Rz = wRc * rotationOf(candidates[k]) * wRo.transpose();
        EXPECT_LT((Rz.col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
        yaw[k] = std::atan2(Rz(1, 0), Rz(0, 0));
      }
      EXPECT_LT(yaw[0], yaw[1]);
    }
    double best = std::numeric_limits<double>::infinity();
    for (const vpHomogeneousMatrix &c : candidates)
      best = std::min(best, poseError(c, s.cMo));
    EXPECT_LT(best, 1e-9);
  }
  EXPECT_GT(twoCandidates, 0);
}

// An initial pose that is not finite, or not rigid (its rotation block scaled by 1.5), is refused with
// STATUS_REFINEMENT_FAILED and left as given, on the 4-DOF path and on the 6-DOF one (a gravity standard
// deviation set), which returned the scaled pose refined but still scaled, as a success.
TEST(PoseGravityApi, RefineKeepsPoseOnFailure)
{
  SceneGenerator gen(37);
  const Scene s = gen.scene(5);
  vpHomogeneousMatrix notFinite = s.cMo, scaled = s.cMo;
  notFinite[0][3] = std::numeric_limits<double>::quiet_NaN();
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c)
      scaled[r][c] *= 1.5;
  for (double gravitySigma : {0.0, 0.01}) {
    vpPoseGravity pose = estimatorFor(s);
    pose.setCameraGravityStdDev(gravitySigma);
    for (const vpHomogeneousMatrix &before : {notFinite, scaled}) {
      vpHomogeneousMatrix cMo = before;
      EXPECT_FALSE(pose.refinePose(cMo)) << "gravity sigma " << gravitySigma;
      EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_REFINEMENT_FAILED);
      for (unsigned int r = 0; r < 4; ++r)
        for (unsigned int c = 0; c < 4; ++c)
          EXPECT_TRUE(cMo[r][c] == before[r][c] || (std::isnan(cMo[r][c]) && std::isnan(before[r][c])));
    }
    // Exact data: the refinement of the true pose stays on it.
    vpHomogeneousMatrix truth = s.cMo;
    EXPECT_TRUE(pose.refinePose(truth));
    EXPECT_LT(poseError(truth, s.cMo), 1e-9);
  }
}
