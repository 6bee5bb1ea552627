/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  Standard mistakes in the gravity vectors: camera and object gravity exchanged (closed forms:
  STATUS_GRAVITY_SWAPPED), and RANSAC's STATUS_NO_CONSENSUS telling whether a consensus exists with
  the camera gravity reversed or with the two vectors exchanged (getSuspectedMistake()); right
  vectors are not diagnosed.
*/
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
const double kPixel = 1.0 / 800.0;

double rotationDegrees(const vpHomogeneousMatrix &A, const vpHomogeneousMatrix &B)
{
  const Eigen::AngleAxisd aa(rotationOf(A) * rotationOf(B).transpose());
  return std::abs(aa.angle()) * 180.0 / M_PI;
}
} // namespace

// Camera and object gravity exchanged (the two IMUs' vectors given to the wrong setter), exact data
// and 1 px: a P3P or least-squares pose that fits is tens of degrees off; it must be refused, named.
TEST(PoseGravityMistakes, SwappedGravityIsRefusedAndNamed)
{
  SceneGenerator gen(301);
  const int runs = 300;
  for (vpPoseGravity::vpPoseGravityMethod method : {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES})
    for (double noise : {0.0, kPixel}) {
      int wrongAccepted = 0, named = 0, distinct = 0;
      for (int k = 0; k < runs; ++k) {
        Scene s = gen.scene(method == vpPoseGravity::P3P ? 3 : 8);
        gen.addImageNoise(s.points, noise);
        // Swapping changes nothing when the two frames share their vertical (a few degrees apart).
        if ((toEigen(s.gCam) - toEigen(s.gObj)).norm() < 0.1)
          continue;
        ++distinct;
        std::swap(s.gCam, s.gObj);
        vpPoseGravity pose = estimatorFor(s);
        vpHomogeneousMatrix cMo;
        const bool ok = pose.computePose(method, cMo);
        wrongAccepted += ok && rotationDegrees(cMo, s.cMo) > 10.0;
        named += pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SWAPPED &&
                 pose.getSuspectedMistake() == vpPoseGravity::GRAVITY_MISTAKE_SWAPPED;
      }
      std::cout << (method == vpPoseGravity::P3P ? "P3P" : "LEAST_SQUARES 8 points") << ", noise " << noise / kPixel
                << " px, gravity swapped: wrong pose accepted " << wrongAccepted << " / " << distinct << ", named "
                << named << std::endl;
      // Measured: 0-3 wrong poses accepted of 300 (P3P: its two redundant equations cannot always tell).
      EXPECT_LE(wrongAccepted, distinct * 3 / 200);
      EXPECT_GE(named, distinct * 9 / 10);
    }
}

// RANSAC with the camera gravity reversed or the vectors exchanged: no consensus, and the mistake
// under which one exists is named. Right vectors: a pose, no mistake.
TEST(PoseGravityMistakes, RansacNoConsensusNamesTheMistake)
{
  SceneGenerator gen(302);
  const int runs = 100;
  for (vpPoseGravity::vpGravityMistake mistake :
       {vpPoseGravity::GRAVITY_MISTAKE_SIGN_REVERSED, vpPoseGravity::GRAVITY_MISTAKE_SWAPPED}) {
    int noConsensus = 0, named = 0, distinct = 0;
    for (int k = 0; k < runs; ++k) {
      Scene s = gen.scene(20);
      gen.addImageNoise(s.points, kPixel);
      if ((toEigen(s.gCam) - toEigen(s.gObj)).norm() < 0.1)
        continue;
      ++distinct;
      if (mistake == vpPoseGravity::GRAVITY_MISTAKE_SIGN_REVERSED)
        s.gCam = -s.gCam;
      else
        std::swap(s.gCam, s.gObj);
      vpPoseGravity pose = estimatorFor(s);
      pose.setRansacSeed(static_cast<unsigned int>(k));
      vpHomogeneousMatrix cMo;
      if (!pose.computePose(vpPoseGravity::RANSAC, cMo) && pose.getStatus() == vpPoseGravity::STATUS_NO_CONSENSUS) {
        ++noConsensus;
        named += pose.getSuspectedMistake() == mistake;
      }
    }
    std::cout << "RANSAC 20 points, 1 px, " << vpPoseGravity::getMistakeMessage(mistake) << ": no consensus "
              << noConsensus << " / " << distinct << ", named " << named << std::endl;
    // Measured: the reversed sign never reaches a consensus (100/100); the exchanged vectors do in 20 of
    // these 100 scenes (a 1 m object whose yaw and translation absorb the wrong tilt within 3.2 px):
    // there RANSAC returns a wrong pose, a limit of what the points can tell.
    EXPECT_GE(noConsensus, distinct * (mistake == vpPoseGravity::GRAVITY_MISTAKE_SWAPPED ? 75 : 95) / 100);
    EXPECT_GE(named, noConsensus * 9 / 10);
  }
  // Right vectors: every run finds its pose, none names a mistake.
  int diagnosed = 0, found = 0;
  for (int k = 0; k < runs; ++k) {
    Scene s = gen.scene(20);
    gen.addImageNoise(s.points, kPixel);
    vpPoseGravity pose = estimatorFor(s);
    vpHomogeneousMatrix cMo;
    found += pose.computePose(vpPoseGravity::RANSAC, cMo);
    diagnosed += pose.getSuspectedMistake() != vpPoseGravity::GRAVITY_MISTAKE_NONE;
  }
  EXPECT_EQ(found, runs);
  EXPECT_EQ(diagnosed, 0);
}

// Right vectors, 1 px: no closed-form estimate is refused as swapped (at most 0.5 %).
TEST(PoseGravityMistakes, RightGravityIsNotCalledSwapped)
{
  SceneGenerator gen(303);
  const int runs = 1000;
  int swapped = 0;
  for (int k = 0; k < runs; ++k) {
    Scene s = gen.scene(k % 2 ? 3 : 8);
    gen.addImageNoise(s.points, kPixel);
    vpPoseGravity pose = estimatorFor(s);
    vpHomogeneousMatrix cMo;
    pose.computePose(k % 2 ? vpPoseGravity::P3P : vpPoseGravity::LEAST_SQUARES, cMo);
    swapped += pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SWAPPED;
  }
  std::cout << "right gravity, 1 px: " << swapped << " / " << runs << " called swapped" << std::endl;
  EXPECT_LE(swapped * 200, runs);
}
