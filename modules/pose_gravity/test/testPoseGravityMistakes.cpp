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
      int wrongAccepted = 0, withinNoise = 0, named = 0, distinct = 0;
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
        if (ok && rotationDegrees(cMo, s.cMo) > 10.0) {
          // The stated vectors fit the points within the noise the estimator assumes (3 sigma,
          // setImageStdDev(), 1e-3 by default), as the exchanged ones do: three points cannot tell them.
          const double rms = std::sqrt(pose.computeResidual(cMo) / 3.0);
          std::cout << "  scene " << k << ": " << rotationDegrees(cMo, s.cMo) << " deg off, accepted at "
                    << rms / kPixel << " px rms" << std::endl;
          (rms <= 3.0 * 1e-3 ? withinNoise : wrongAccepted) += 1; // the default setImageStdDev()
        }
        named += pose.getStatus() == vpPoseGravity::STATUS_GRAVITY_SWAPPED &&
                 pose.getSuspectedMistake() == vpPoseGravity::GRAVITY_MISTAKE_SWAPPED;
      }
      std::cout << (method == vpPoseGravity::P3P ? "P3P" : "LEAST_SQUARES 8 points") << ", noise " << noise / kPixel
                << " px, gravity swapped: wrong pose accepted " << wrongAccepted << " / " << distinct
                << ", accepted within the noise " << withinNoise << ", named " << named << std::endl;
      // Measured: P3P accepts 3 of 300 poses 10 to 146 deg off, at 0 and at 1 px; each fits its three
      // points within 3 sigma, as the exchanged vectors do (two redundant equations): both hypotheses
      // fit, and one frame cannot tell them apart (1 % of the exchanged-vector scenes). Comparing the
      // two hypotheses from one sigma on would keep none at 0 px, but refuses 13 of 2000 right P3P
      // estimates at 1 px (0.65 %, PoseGravityNoise), beyond the 0.5 % allowed. None is accepted beyond
      // the noise; 8 points never accept one.
      EXPECT_EQ(wrongAccepted, 0);
      EXPECT_LE(withinNoise, distinct * 3 / 200);
      EXPECT_GE(named, distinct * 9 / 10);
    }
}

// RANSAC with the camera gravity reversed or the vectors exchanged: no pose, and the mistake is named
// (STATUS_NO_CONSENSUS naming the alternative under which a consensus exists, or STATUS_GRAVITY_SWAPPED
// when a consensus exists under the exchanged vectors too but they fit it markedly better).
TEST(PoseGravityMistakes, RansacNamesTheMistake)
{
  SceneGenerator gen(302);
  const int runs = 100;
  for (vpPoseGravity::vpGravityMistake mistake :
       {vpPoseGravity::GRAVITY_MISTAKE_SIGN_REVERSED, vpPoseGravity::GRAVITY_MISTAKE_SWAPPED}) {
    int refused = 0, named = 0, distinct = 0, wrongAccepted = 0, withinNoise = 0;
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
      // The tilt the exchange makes to the true pose (deg): cRo applied to the exchanged object vector.
      const double tilt =
          std::acos(std::max(-1.0, std::min(1.0, (rotationOf(s.cMo) * toEigen(s.gObj)).dot(toEigen(s.gCam))))) * 180.0 /
          M_PI;
      if (pose.computePose(vpPoseGravity::RANSAC, cMo)) {
        // 20 points at 1 px leave about 0.1 deg (PoseGravityNoise): 1 deg is beyond the noise, unless the
        // exchange itself tilts the truth by less than 1 deg (about 1 px on a 1 m object at 2 to 8 m):
        // then both hypotheses fit within the noise.
        if (rotationDegrees(cMo, s.cMo) > 1.0) {
          (tilt > 1.0 ? wrongAccepted : withinNoise) += 1;
          std::cout << "  scene " << k << ": a pose " << rotationDegrees(cMo, s.cMo)
                    << " deg off accepted, exchange tilt " << tilt << " deg" << std::endl;
        }
        continue;
      }
      ++refused;
      named += pose.getSuspectedMistake() == mistake;
    }
    std::cout << "RANSAC 20 points, 1 px, " << vpPoseGravity::getMistakeMessage(mistake) << ": refused " << refused
              << " / " << distinct << ", named " << named << ", wrong pose accepted " << wrongAccepted
              << ", within the noise " << withinNoise << std::endl;
    // Measured: the reversed sign never reaches a consensus (100/100). The exchanged vectors reach one
    // in 20 of these 100 scenes (a 1 m object whose yaw and translation absorb the wrong tilt within
    // 3.2 px); the comparison with the exchanged hypothesis on that consensus (STATUS_GRAVITY_SWAPPED)
    // refuses 18 of them; of the 2 accepted, one is 0.8 deg off, one 1.2 deg off where the exchange
    // tilts the truth by 0.9 deg (both hypotheses fit within the noise).
    EXPECT_EQ(wrongAccepted, 0);
    EXPECT_LE(withinNoise, 1);
    EXPECT_GE(refused, distinct * 95 / 100);
    EXPECT_GE(named, refused * 9 / 10);
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

/*!
  Statuses of vpPoseGravity on \e runs scenes of a planar target 0.2-0.4 m wide (the plane z = 0 of its frame)
  seen by a camera at \e distance (metres, uniform in [first, second]) along its optical axis, turned by
  \e turn (from the generator, per scene): the rotation cRo. Each IMU has 0.16 deg of tilt noise (0.002 per
  component) that the estimator is not told of, the image 0.5 px. For P3P (3 points), LEAST_SQUARES (4) and
  RANSAC (20): how many found a pose, and how many named a mistake in the gravity (getSuspectedMistake()).
*/
template <typename Turn>
void countStatus(SceneGenerator &gen, int runs, const Eigen::Vector3d &gObjTrue, std::pair<double, double> distance,
                 Turn turn, int found[3], int mistaken[3])
{
  const vpPoseGravity::vpPoseGravityMethod methods[3] = {vpPoseGravity::P3P, vpPoseGravity::LEAST_SQUARES,
                                                         vpPoseGravity::RANSAC};
  for (int k = 0; k < runs; ++k)
    for (int m = 0; m < 3; ++m) {
      const int n = m == 0 ? 3 : (m == 1 ? 4 : 20);
      const double width = gen.uniform(0.2, 0.4), depth = gen.uniform(distance.first, distance.second);
      std::vector<Eigen::Vector3d> X(static_cast<size_t>(n));
      for (Eigen::Vector3d &P : X)
        P = Eigen::Vector3d(gen.uniform(-0.5, 0.5) * width, gen.uniform(-0.5, 0.5) * width, 0.0);
      const vpRotationMatrix cRo = turn(gen);
      const Eigen::Vector3d t = Eigen::Vector3d(gen.uniform(-0.2, 0.2), gen.uniform(-0.2, 0.2), 1.0) * depth;
      Scene s;
      s.cMo = vpHomogeneousMatrix(vpTranslationVector(t.x(), t.y(), t.z()), cRo);
      s.points = SceneGenerator::project(X, s.cMo);
      gen.addImageNoise(s.points, 0.5 * kPixel);
      s.gObj = gen.noisyGravity(toVisp(gObjTrue), 0.002);
      s.gCam = gen.noisyGravity(toVisp(rotationOf(s.cMo) * gObjTrue), 0.002);
      vpPoseGravity pose = estimatorFor(s);
      pose.setRansacSeed(static_cast<unsigned int>(k));
      vpHomogeneousMatrix cMo;
      found[m] += pose.computePose(methods[m], cMo);
      mistaken[m] += pose.getSuspectedMistake() != vpPoseGravity::GRAVITY_MISTAKE_NONE;
    }
}

const char *const kMethodNames[3] = {"P3P", "LEAST_SQUARES 4 points", "RANSAC 20 points"};

// A camera that shares the object's vertical: an upright camera facing a target on a wall (a robot's or a
// drone's forward camera, a marker) at 0.5-1.5 m, turned by up to 40 deg about the vertical. The exchanged
// vectors are the stated ones up to the IMUs' noise, so naming an exchange is always wrong there
// (tutorial-servo-gravity lost 1-3 of its 150 estimates to it on 12 of its noise seeds 1-30). Nor is the
// gravity's sign.
TEST(PoseGravityMistakes, ASharedVerticalIsNeverCalledMistaken)
{
  SceneGenerator gen(304);
  const int runs = 1000;
  const Eigen::Vector3d down(0.0, 1.0, 0.0); // the wall's vertical in the target frame, and the camera's y
  int found[3] = {0, 0, 0}, mistaken[3] = {0, 0, 0};
  countStatus(
      gen, runs, down, {0.5, 1.5},
      [&down](SceneGenerator &g) { return rotationMapping(down, down, g.uniform(-1.0, 1.0) * 40.0 * M_PI / 180.0); },
      found, mistaken);
  for (int m = 0; m < 3; ++m) {
    std::cout << kMethodNames[m] << ", target on a wall, upright camera: " << found[m] << " / " << runs << " found, "
              << mistaken[m] << " called mistaken" << std::endl;
    // Measured before the vectors' difference was compared with their noise: 15 of the P3P estimates and 1
    // of RANSAC's called swapped, none reversed. Now none; found 999, 1000, 1000 (the P3P refused has two of its three
    // points 1.5 px apart on a vertical line: no yaw to see, STATUS_INCONSISTENT_GRAVITY).
    EXPECT_EQ(mistaken[m], 0);
    EXPECT_GE(found[m] * 100, runs * 99);
  }
}

// A camera looking down at a marker on the floor (a drone landing on a pad), within 10 deg of the vertical,
// turned freely about it, 0.5-3 m above. The mirror pose of a plane seen from above fits its points nearly
// as well as the true one; with the camera gravity reversed it would be a camera looking up from under the
// floor. The two vectors are equal there too. No estimate may be refused as a mistake (measured: none of
// 1000 with each method, all found).
TEST(PoseGravityMistakes, ADownwardCameraOverAFloorMarkerIsNeverCalledMistaken)
{
  SceneGenerator gen(305);
  const int runs = 1000;
  const Eigen::Vector3d down(0.0, 0.0, 1.0); // the floor's vertical in the marker frame (z into the floor)
  int found[3] = {0, 0, 0}, mistaken[3] = {0, 0, 0};
  countStatus(
      gen, runs, down, {0.5, 3.0},
      [&down](SceneGenerator &g) {
        const double tilt = g.uniform(0.0, 10.0) * M_PI / 180.0, heading = g.uniform(-M_PI, M_PI);
        const Eigen::Vector3d tilted(std::sin(tilt) * std::cos(heading), std::sin(tilt) * std::sin(heading),
                                     std::cos(tilt));
        return rotationMapping(down, tilted, g.uniform(-M_PI, M_PI));
      },
      found, mistaken);
  for (int m = 0; m < 3; ++m) {
    std::cout << kMethodNames[m] << ", marker on the floor, downward camera: " << found[m] << " / " << runs
              << " found, " << mistaken[m] << " called mistaken" << std::endl;
    EXPECT_EQ(mistaken[m], 0);
    EXPECT_GE(found[m] * 100, runs * 99);
  }
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
