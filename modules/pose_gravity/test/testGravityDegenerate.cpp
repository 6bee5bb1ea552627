/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Special geometry, exact data: gravity along the camera / object axes (singular in the paper's
  formulas), image points with equal x or equal y (the paper's special cases 1 and 2), and the
  three cases of Lemma 1 (coincident image points on a general, horizontal or vertical ray).
  Exact data leave only rounding: pose errors are required below 1e-9.
*/
#include <algorithm>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
const double kExact = 1e-9;

// Best P2P candidate error (facade), infinity if none.
double bestCandidateError(const Scene &s, vpPoseGravity::vpPoseGravityStatus *status = nullptr)
{
  vpPoseGravity pose = estimatorFor(s, true, true, false);
  pose.addPoint(s.points[0]);
  pose.addPoint(s.points[1]);
  double best = std::numeric_limits<double>::infinity();
  for (const vpHomogeneousMatrix &cMo : pose.computePoseCandidates())
    best = std::min(best, poseError(cMo, s.cMo));
  if (status)
    *status = pose.getStatus();
  return best;
}

double methodError(const Scene &s, vpPoseGravity::vpPoseGravityMethod method)
{
  vpPoseGravity pose = estimatorFor(s);
  vpHomogeneousMatrix cMo;
  if (!pose.computePose(method, cMo)) {
    std::cout << "no pose: " << vpPoseGravity::getStatusMessage(pose.getStatus()) << std::endl;
    return std::numeric_limits<double>::infinity();
  }
  return poseError(cMo, s.cMo);
}

Eigen::Vector3d axis(int i, double sign)
{
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[i] = sign;
  return e;
}

// Scene whose pose maps the object gravity gObj onto the camera gravity gCam exactly.
Scene sceneWithGravities(SceneGenerator &gen, const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, int n)
{
  const std::vector<Eigen::Vector3d> X = gen.objectPoints(n);
  Scene s;
  s.cMo = gen.poseLookingAt(X, rotationMapping(gObj, gCam, gen.uniform(-M_PI, M_PI)));
  s.gObj = toVisp(gObj);
  s.gCam = SceneGenerator::cameraGravity(s.cMo, s.gObj);
  s.points = SceneGenerator::project(X, s.cMo);
  return s;
}

// Object point whose camera coordinates are cP under pose cMo.
Eigen::Vector3d objectPointAt(const vpHomogeneousMatrix &cMo, const Eigen::Vector3d &cP)
{
  return rotationOf(cMo).transpose() * (cP - translationOf(cMo));
}
} // namespace

TEST(PoseGravityDegenerate, GravityAlongAxes)
{
  // Every pair of signed axes (camera, object), including Y (the paper's singular direction) for
  // both, and a random direction on the other side.
  SceneGenerator gen(21);
  std::vector<Eigen::Vector3d> directions;
  for (int i = 0; i < 3; ++i)
    for (double sign : {-1.0, 1.0})
      directions.push_back(axis(i, sign));
  directions.push_back(gen.unitVector());
  for (const Eigen::Vector3d &gCam : directions)
    for (const Eigen::Vector3d &gObj : directions)
      for (int trial = 0; trial < 20; ++trial) {
        const Scene s = sceneWithGravities(gen, gCam, gObj, 5);
        // The gravity built from the truth must be exactly the requested axis.
        EXPECT_LT((toEigen(s.gCam) - gCam).norm(), 1e-15);
        EXPECT_LT(bestCandidateError(s), kExact) << "gCam " << gCam.transpose() << " gObj " << gObj.transpose();
        EXPECT_LT(methodError(s, vpPoseGravity::P3P), kExact);
        EXPECT_LT(methodError(s, vpPoseGravity::LEAST_SQUARES), kExact);
      }
}

TEST(PoseGravityDegenerate, EqualImageXOrY)
{
  // Second point placed in camera coordinates so that x_B == x_A (resp. y_B == y_A) exactly up to
  // rounding: the paper needs dedicated formulas for these cases, the plane formulation does not.
  SceneGenerator gen(22);
  for (int coordinate = 0; coordinate < 2; ++coordinate)
    for (int trial = 0; trial < 500; ++trial) {
      Scene s = gen.scene(3);
      vpPoint &A = s.points[0];
      const double zB = gen.uniform(1.0, 8.0);
      const double free = gen.uniform(-0.4, 0.4) * zB;
      const Eigen::Vector3d cB = (coordinate == 0) ? Eigen::Vector3d(A.get_x() * zB, free, zB)
                                                   : Eigen::Vector3d(free, A.get_y() * zB, zB);
      const Eigen::Vector3d XB = objectPointAt(s.cMo, cB);
      s.points[1] = SceneGenerator::project({XB}, s.cMo)[0];
      if (coordinate == 0)
        ASSERT_NEAR(s.points[1].get_x(), A.get_x(), 1e-14);
      else
        ASSERT_NEAR(s.points[1].get_y(), A.get_y(), 1e-14);
      vpPoseGravity::vpPoseGravityStatus status;
      EXPECT_LT(bestCandidateError(s, &status), kExact);
      EXPECT_EQ(status, vpPoseGravity::STATUS_OK);
      EXPECT_LT(methodError(s, vpPoseGravity::P3P), kExact);
    }
}

TEST(PoseGravityDegenerate, CoincidentImagePointsGeneralRay)
{
  // Lemma 1, second case: A, B and the optical centre aligned, ray not parallel to gravity. The
  // rotation is unique, the translation known up to the ray; the facade reports the status and no
  // candidate, the solver returns the rotation and a translation on the right ray.
  SceneGenerator gen(23);
  int tested = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Scene s = gen.scene(2);
    const Eigen::Vector3d cA = rotationOf(s.cMo) * toEigen(s.points[0].oP) + translationOf(s.cMo);
    const double k = (trial % 2) ? gen.uniform(1.1, 2.0) : gen.uniform(0.3, 0.9); // B behind or in front of A
    const Eigen::Vector3d XB = objectPointAt(s.cMo, k * cA);
    s.points[1] = SceneGenerator::project({XB}, s.cMo)[0];

    vpPoseGravity::vpPoseGravityStatus status;
    EXPECT_EQ(bestCandidateError(s, &status), std::numeric_limits<double>::infinity());
    EXPECT_EQ(status, vpPoseGravity::STATUS_COINCIDENT_IMAGE_POINTS);

    std::vector<Eigen::Vector3d> x, X;
    toSolverInput(s.points, x, X);
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    ASSERT_EQ(vpGravitySolvers::p2p(toEigen(s.gCam), toEigen(s.gObj), x.data(), X.data(), poses, &p2pCase), 1);
    ASSERT_EQ(p2pCase, vpGravitySolvers::P2PCase::UniqueRotation);
    // A generic ray has a vertical component, which fixes which point is nearer: exact rotation.
    EXPECT_LT((poses[0].R - rotationOf(s.cMo)).norm(), kExact);
    // Translation: differs from the truth only along the ray, and puts both points in front.
    const Eigen::Vector3d ray = x[0].normalized();
    EXPECT_LT((poses[0].t - translationOf(s.cMo)).cross(ray).norm(), kExact * translationOf(s.cMo).norm());
    for (int i = 0; i < 2; ++i)
      EXPECT_GT((poses[0].R * X[i] + poses[0].t).z(), 0.0);
    const double nearest = std::min((poses[0].R * X[0] + poses[0].t).z(), (poses[0].R * X[1] + poses[0].t).z());
    EXPECT_NEAR(nearest, 1.0, 1e-12);
    ++tested;
  }
  EXPECT_EQ(tested, 2000);
}

TEST(PoseGravityDegenerate, CoincidentImagePointsHorizontalRay)
{
  // Horizontal ray: which point is nearer is not observable; the solver takes the first point as
  // the nearer (visible) one, which recovers the truth when that holds.
  SceneGenerator gen(24);
  for (int trial = 0; trial < 500; ++trial) {
    const std::vector<Eigen::Vector3d> X0 = gen.objectPoints(1);
    const vpRotationMatrix cRo = gen.rotation();
    const vpHomogeneousMatrix cMo = gen.poseLookingAt(X0, cRo);
    const Eigen::Vector3d cA = rotationOf(cMo) * X0[0] + translationOf(cMo);
    // Gravity orthogonal to the ray of A in the camera frame.
    const Eigen::Vector3d gCam = cA.cross(gen.unitVector()).normalized();
    const Eigen::Vector3d gObj = rotationOf(cMo).transpose() * gCam;
    const Eigen::Vector3d XB = objectPointAt(cMo, gen.uniform(1.1, 3.0) * cA);
    Scene s;
    s.cMo = cMo;
    s.gCam = toVisp(gCam);
    s.gObj = toVisp(gObj);
    s.points = SceneGenerator::project({X0[0], XB}, cMo);
    std::vector<Eigen::Vector3d> x, X;
    toSolverInput(s.points, x, X);
    std::array<vpGravitySolvers::Pose, 2> poses;
    vpGravitySolvers::P2PCase p2pCase;
    ASSERT_EQ(vpGravitySolvers::p2p(gCam, gObj, x.data(), X.data(), poses, &p2pCase), 1);
    ASSERT_EQ(p2pCase, vpGravitySolvers::P2PCase::UniqueRotation);
    EXPECT_LT((poses[0].R - rotationOf(cMo)).norm(), kExact);
  }
}

TEST(PoseGravityDegenerate, CoincidentImagePointsVerticalRay)
{
  // Lemma 1, third case: the common ray is parallel to gravity: infinitely many poses.
  SceneGenerator gen(25);
  for (int trial = 0; trial < 500; ++trial) {
    const std::vector<Eigen::Vector3d> X0 = gen.objectPoints(1);
    const vpHomogeneousMatrix cMo = gen.poseLookingAt(X0, gen.rotation());
    const Eigen::Vector3d cA = rotationOf(cMo) * X0[0] + translationOf(cMo);
    const Eigen::Vector3d gCam = (trial % 2 ? 1.0 : -1.0) * cA.normalized();
    Scene s;
    s.cMo = cMo;
    s.gCam = toVisp(gCam);
    s.gObj = toVisp(rotationOf(cMo).transpose() * gCam);
    s.points = SceneGenerator::project({X0[0], objectPointAt(cMo, gen.uniform(0.3, 3.0) * cA)}, cMo);
    vpPoseGravity::vpPoseGravityStatus status;
    EXPECT_EQ(bestCandidateError(s, &status), std::numeric_limits<double>::infinity());
    EXPECT_EQ(status, vpPoseGravity::STATUS_VERTICAL_RAY);
  }
}

TEST(PoseGravityDegenerate, P3PWithTwoPointsOnOneRay)
{
  // Two of the three points share an image point (general ray or vertical ray): P3P works through
  // the pairs that involve the third point.
  SceneGenerator gen(26);
  for (int trial = 0; trial < 1000; ++trial) {
    Scene s = gen.scene(3);
    const Eigen::Vector3d cA = rotationOf(s.cMo) * toEigen(s.points[0].oP) + translationOf(s.cMo);
    const int shared = 1 + trial % 2; // the point moved onto A's ray
    s.points[shared] = SceneGenerator::project({objectPointAt(s.cMo, gen.uniform(0.5, 2.0) * cA)}, s.cMo)[0];
    if (trial % 4 >= 2) {
      // Make the common ray vertical.
      s.gCam = toVisp(cA.normalized());
      s.gObj = toVisp(rotationOf(s.cMo).transpose() * cA.normalized());
    }
    EXPECT_LT(methodError(s, vpPoseGravity::P3P), kExact) << "trial " << trial;
    EXPECT_LT(methodError(s, vpPoseGravity::LEAST_SQUARES), kExact) << "trial " << trial;
  }
}

TEST(PoseGravityDegenerate, VerticalLineOfPointsHasNoYaw)
{
  // Every object point on one line along gravity: the image only repeats the IMUs, the yaw is free.
  SceneGenerator gen(27);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d gObj = gen.unitVector();
    const Eigen::Vector3d origin(gen.uniform(-1, 1), gen.uniform(-1, 1), gen.uniform(-1, 1));
    std::vector<Eigen::Vector3d> X;
    X.reserve(5);
    for (int i = 0; i < 5; ++i)
      X.push_back(origin + gen.uniform(-0.5, 0.5) * gObj);
    Scene s;
    s.cMo = gen.poseLookingAt(X, gen.rotation());
    s.gObj = toVisp(gObj);
    s.gCam = SceneGenerator::cameraGravity(s.cMo, s.gObj);
    s.points = SceneGenerator::project(X, s.cMo);
    vpPoseGravity pose = estimatorFor(s);
    vpHomogeneousMatrix cMo;
    EXPECT_FALSE(pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
    EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_NO_SOLUTION);
    EXPECT_TRUE(pose.computePoseCandidates().empty());
    EXPECT_EQ(pose.getStatus(), vpPoseGravity::STATUS_VERTICAL_RAY);
  }
}

TEST(PoseGravityDegenerate, ObjectFarFromItsOrigin)
{
  // A 0.2 m object whose coordinates are around 1 km (e.g. georeferenced): the closed forms must
  // not lose the yaw in the large common offset. Exact data: rounding of 1e3 m coordinates is
  // ~1e-13 m, amplified by the 0.2 m extent: 1e-9 is a safe bound.
  SceneGenerator gen(28);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Eigen::Vector3d> X = gen.objectPoints(6, 0.2);
    const Eigen::Vector3d offset = 1000.0 * gen.unitVector();
    for (Eigen::Vector3d &p : X)
      p += offset;
    Scene s;
    s.cMo = gen.poseLookingAt(X, gen.rotation());
    s.gObj = toVisp(gen.unitVector());
    s.gCam = SceneGenerator::cameraGravity(s.cMo, s.gObj);
    s.points = SceneGenerator::project(X, s.cMo);
    EXPECT_LT(methodError(s, vpPoseGravity::LEAST_SQUARES), 1e-9);
    EXPECT_LT(methodError(s, vpPoseGravity::P3P), 1e-9);
  }
}

// The solvers take unit gravity vectors (vpPoseGravity normalises them): one of another norm is refused,
// with no pose, rather than turned into a matrix that is not a rotation (twice the unit vector gave
// |R R^T - I| = 3 and a pose returned as found). Within 1e-6 of unit norm is taken.
TEST(PoseGravityDegenerate, SolversRefuseGravityThatIsNotUnit)
{
  SceneGenerator gen(28);
  std::vector<Eigen::Vector3d> x, X;
  for (int trial = 0; trial < 100; ++trial) {
    const Scene s = gen.scene(5);
    toSolverInput(s.points, x, X);
    const Eigen::Vector3d gCam = toEigen(s.gCam), gObj = toEigen(s.gObj);
    for (double scale : {2.0, 0.5, 1.0 + 1e-4}) {
      vpGravitySolvers::Pose pose;
      std::array<vpGravitySolvers::Pose, 2> poses;
      vpGravitySolvers::P2PCase p2pCase = vpGravitySolvers::P2PCase::TwoSolutions;
      EXPECT_FALSE(vpGravitySolvers::p3p(scale * gCam, gObj, x.data(), X.data(), pose)) << scale;
      EXPECT_FALSE(vpGravitySolvers::p3p(gCam, scale * gObj, x.data(), X.data(), pose)) << scale;
      EXPECT_FALSE(vpGravitySolvers::leastSquares(scale * gCam, gObj, x.data(), X.data(), 5, pose)) << scale;
      EXPECT_EQ(vpGravitySolvers::p2p(gCam, scale * gObj, x.data(), X.data(), poses, &p2pCase), 0) << scale;
      EXPECT_EQ(p2pCase, vpGravitySolvers::P2PCase::NoSolution);
    }
    vpGravitySolvers::Pose pose;
    const double nearlyUnit = 1.0 + 1e-7;
    ASSERT_TRUE(vpGravitySolvers::p3p(nearlyUnit * gCam, gObj, x.data(), X.data(), pose));
    EXPECT_LT(poseError(pose, s.cMo), 1e-5);
  }
}
