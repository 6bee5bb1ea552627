/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpImuGravity against the physics it encodes: an accelerometer at rest reads the specific force
  -g (pointing up), the IMU-to-sensor rotation is applied, the stream is interpolated at the
  requested (offset) times, readings under acceleration are flagged, and the CSV layouts of EuRoC /
  Kalibr are read (bad files give badFileError with the line).
*/
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/pose_gravity/vpImuGravity.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_test_scene.h"

using namespace gravity_test;

namespace
{
const double kG = vpImuGravity::standardGravity();

vpColVector vec(double a, double b, double c)
{
  vpColVector v(3);
  v[0] = a;
  v[1] = b;
  v[2] = c;
  return v;
}

// The specific force read at rest by an IMU whose frame has rotation imuRw from the world (z up).
vpColVector restReading(const vpRotationMatrix &imuRw) { return imuRw * vec(0, 0, kG); }

std::string tempFile(const std::string &name, const std::string &content)
{
  std::string path = ::testing::TempDir() + name;
  std::ofstream out(path.c_str());
  out << content;
  return path;
}
} // namespace

TEST(PoseGravityImu, SpecificForceBecomesDownGravity)
{
  // Level IMU, z up: reads +9.81 on z; gravity points down: -z.
  const vpColVector g = vpImuGravity::gravityFromSpecificForce(vec(0, 0, kG));
  EXPECT_NEAR(g[2], -1.0, 1e-15);
  // The IMU-to-camera rotation is applied: a camera whose z axis is the IMU's x axis.
  const vpRotationMatrix cRi(vpThetaUVector(0, -M_PI / 2, 0));
  const vpColVector gc = vpImuGravity::gravityFromSpecificForce(vec(kG, 0, 0), cRi);
  const vpColVector expected = -(cRi * vec(1, 0, 0));
  for (unsigned int i = 0; i < 3; ++i)
    EXPECT_NEAR(gc[i], expected[i], 1e-15);
  EXPECT_TRUE(vpImuGravity::isAtRest(vec(0.1, 0.2, 9.79)));
  EXPECT_FALSE(vpImuGravity::isAtRest(vec(0.0, 4.0, 9.81))); // norm 10.59: 0.79 m/s^2 over g
  EXPECT_THROW(vpImuGravity::gravityFromSpecificForce(vec(0, 0, 0)), vpPoseGravityException);
  EXPECT_THROW(vpImuGravity::gravityFromSpecificForce(vec(NAN, 0, 1)), vpPoseGravityException);
}

TEST(PoseGravityImu, RawReadingsGiveTheTruePose)
{
  // Two IMUs at rest, each rotated with respect to its sensor: the converted readings fed to
  // vpPoseGravity give the true pose, the raw readings (sign mix-up) are refused.
  SceneGenerator gen(81);
  for (int k = 0; k < 50; ++k) {
    Scene s = gen.scene(6);
    const vpRotationMatrix cRi = gen.rotation(), oRj = gen.rotation();
    // Specific force in each IMU frame: -g rotated into it.
    const vpColVector fCam = -(cRi.t() * s.gCam) * kG, fObj = -(oRj.t() * s.gObj) * kG;
    vpPoseGravity pose;
    pose.setCameraGravity(vpImuGravity::gravityFromSpecificForce(fCam, cRi));
    pose.setObjectGravity(vpImuGravity::gravityFromSpecificForce(fObj, oRj));
    pose.addPoints(s.points);
    vpHomogeneousMatrix cMo;
    ASSERT_TRUE(pose.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
    EXPECT_LT(poseError(cMo, s.cMo), 1e-9);
    vpPoseGravity raw;
    raw.setCameraGravity(cRi * fCam); // specific force in the camera frame: points up
    raw.setObjectGravity(vpImuGravity::gravityFromSpecificForce(fObj, oRj));
    raw.addPoints(s.points);
    EXPECT_FALSE(raw.computePose(vpPoseGravity::LEAST_SQUARES, cMo));
    EXPECT_EQ(raw.getStatus(), vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED);
  }
}

TEST(PoseGravityImu, StreamInterpolationAndMotionFlag)
{
  // 200 Hz stream of an IMU tilting slowly about x (0.2 rad/s), with an acceleration burst of
  // 2 m/s^2 between t = 1.0 and 1.1 s. The camera clock runs 5 ms behind the IMU's.
  vpImuGravity imu;
  const double rate = 0.2, offset = 0.005;
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.005 * k;
    const vpRotationMatrix imuRw(vpThetaUVector(rate * t, 0, 0));
    vpColVector f = restReading(imuRw.t());
    if (t >= 1.0 && t <= 1.1)
      f += vec(0, 0, 2.0);
    imu.addSample(t, vec(rate, 0, 0), f);
  }
  imu.setTimeOffset(offset);
  vpColVector g;
  bool moving = true;
  // Between two samples: the direction at the interpolated time, within the linearisation error
  // (angle step 1e-3 rad: chord error 1e-7).
  const double tCam = 0.4321;
  ASSERT_TRUE(imu.gravityAt(tCam, g, moving));
  EXPECT_FALSE(moving);
  const vpRotationMatrix imuRw(vpThetaUVector(rate * (tCam + offset), 0, 0));
  const vpColVector expected = imuRw.t() * vec(0, 0, -1);
  for (unsigned int i = 0; i < 3; ++i)
    EXPECT_NEAR(g[i], expected[i], 1e-6);
  // In the burst: flagged.
  ASSERT_TRUE(imu.gravityAt(1.05, g, moving));
  EXPECT_TRUE(moving);
  // Just before the burst: not flagged unless the motion window reaches it.
  ASSERT_TRUE(imu.gravityAt(0.98, g, moving));
  EXPECT_FALSE(moving);
  imu.setMotionWindow(0.03);
  ASSERT_TRUE(imu.gravityAt(0.98, g, moving));
  EXPECT_TRUE(moving);
  // Outside the stream: no gravity.
  EXPECT_FALSE(imu.gravityAt(-0.1, g, moving));
  EXPECT_FALSE(imu.gravityAt(2.5, g, moving));
  // Gyro tolerance: 0.2 rad/s is motion at 0.1 rad/s.
  imu.setMotionWindow(0.0);
  imu.setGyroTolerance(0.1);
  ASSERT_TRUE(imu.gravityAt(0.4, g, moving));
  EXPECT_TRUE(moving);
  EXPECT_THROW(imu.addSample(0.5, vec(0, 0, 0), vec(0, 0, kG)), vpPoseGravityException); // time going back
}

TEST(PoseGravityImu, EurocCsvAndRotationFiles)
{
  const std::string csv = tempFile("imu_euroc.csv",
                                   "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                                   "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n"
                                   "1403636579758555392,0.0,0.0,0.0,0.0,0.0,9.81\n"
                                   "1403636579763555584,0.0,0.0,0.0,0.0,9.81,0.0\n");
  vpImuGravity imu;
  imu.loadCsv(csv);
  ASSERT_EQ(imu.size(), 2u);
  vpColVector g;
  bool moving = true;
  // Half-way (2.5 ms after the first sample): interpolated (0, 4.905, 4.905) -> down (0, -1, -1)/sqrt 2.
  ASSERT_TRUE(imu.gravityAt(1403636579758555392 * 1e-9 + 2.500096e-3, g, moving));
  EXPECT_NEAR(g[1], -std::sqrt(0.5), 1e-3);
  EXPECT_NEAR(g[2], -std::sqrt(0.5), 1e-3);
  EXPECT_FALSE(moving); // both samples read |f| = 9.81
}

TEST(PoseGravityImu, BadFilesAreReported)
{
  auto expectFileError = [](const std::string &path, const std::string &where) {
    vpImuGravity imu;
    try {
      imu.loadCsv(path);
      ADD_FAILURE() << path << ": no exception";
    } catch (const vpPoseGravityException &e) {
      EXPECT_EQ(e.getCode(), vpPoseGravityException::badFileError);
      EXPECT_NE(e.getStringMessage().find(where), std::string::npos) << e.getStringMessage();
    }
  };
  expectFileError(tempFile("imu_columns.csv", "timestamp,wx,wy,wz,ax,ay,az\n1,0,0,0,0,0,9.8\n2,0,0,0,0,9.8\n"),
                  "imu_columns.csv:3");
  expectFileError(tempFile("imu_nan.csv", "1,0,0,0,0,0,9.8\n2,0,0,0,0,x,9.8\n"), "imu_nan.csv:2");
  expectFileError(tempFile("imu_order.csv", "2,0,0,0,0,0,9.8\n1,0,0,0,0,0,9.8\n"), "imu_order.csv:2");
  expectFileError(::testing::TempDir() + "does_not_exist.csv", "cannot open");

  // Rotation files: 3x3, 4x4 homogeneous (Kalibr's T_cam_imu rows), not a rotation.
  const vpRotationMatrix R(vpThetaUVector(0.1, -0.2, 0.3));
  std::ostringstream r3, r4;
  r3.precision(17);
  r4.precision(17);
  r3 << "# cam_R_imu\n";
  for (unsigned int i = 0; i < 3; ++i) {
    r3 << R[i][0] << " " << R[i][1] << " " << R[i][2] << "\n";
    r4 << "- [" << R[i][0] << ", " << R[i][1] << ", " << R[i][2] << ", 0.05]\n";
  }
  r4 << "- [0.0, 0.0, 0.0, 1.0]\n";
  for (const std::string &content : {r3.str(), r4.str()}) {
    const vpRotationMatrix read = vpImuGravity::loadRotation(tempFile("rotation.txt", content));
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        EXPECT_NEAR(read[i][j], R[i][j], 1e-12);
  }
  EXPECT_THROW(vpImuGravity::loadRotation(tempFile("bad_rotation.txt", "1 0 0\n0 2 0\n0 0 1\n")),
               vpPoseGravityException);
  EXPECT_THROW(vpImuGravity::loadRotation(tempFile("short_rotation.txt", "1 0 0\n0 1 0\n")), vpPoseGravityException);
}

// A rotation near a half turn (an IMU mounted upside down) from a file rounded to 4 decimals: the nearest
// rotation is within the rounding of the truth. Through the theta-u vector, whose axis comes from the
// antisymmetric part (of size sin theta, 0.0125 here), it loaded 7.9e-3 rad off, gravity 0.45 degree off.
TEST(PoseGravityImu, ARotationNearAHalfTurnLoadsWithinItsRounding)
{
  const vpRotationMatrix truth(vpThetaUVector(3.129099 * -0.393447, 3.129099 * -0.405048, 3.129099 * 0.825309));
  std::ostringstream rounded;
  rounded.setf(std::ios::fixed);
  rounded.precision(4);
  for (unsigned int i = 0; i < 3; ++i)
    rounded << truth[i][0] << " " << truth[i][1] << " " << truth[i][2] << "\n";
  const vpRotationMatrix read = vpImuGravity::loadRotation(tempFile("half_turn.txt", rounded.str()));
  const double off = vpThetaUVector(read * truth.inverse()).getTheta();
  const vpColVector g = vpImuGravity::gravityFromSpecificForce(vec(0, 0, kG), read),
                    expected = vpImuGravity::gravityFromSpecificForce(vec(0, 0, kG), truth);
  const double gravityOff = std::acos(std::min(1.0, vpColVector::dotProd(g, expected)));
  std::cout << "half turn from 4 decimals: " << off << " rad off, gravity " << vpMath::deg(gravityOff) << " deg off"
            << std::endl;
  EXPECT_LT(off, 1e-4); // rounding of 5e-5 per coefficient
  EXPECT_LT(vpMath::deg(gravityOff), 0.01);
}

// A file refused part way leaves the stream as it was: the rows before the bad one are not kept, so that
// the corrected file then loads (it was refused as "times must be strictly increasing" before).
TEST(PoseGravityImu, ARefusedFileLeavesTheStreamUnchanged)
{
  vpImuGravity imu;
  imu.addSample(0.5, vec(0, 0, 0), vec(0, 0, kG));
  const std::string bad = tempFile("imu_bad_row.csv", "1,0,0,0,0,0,9.8\n2,0,0,0,0,0,9.8\n3,0,0,0,0,x,9.8\n");
  EXPECT_THROW(imu.loadCsv(bad, 1.0), vpPoseGravityException);
  EXPECT_EQ(imu.size(), 1u);
  const std::string backwards = tempFile("imu_backwards.csv", "1,0,0,0,0,0,9.8\n2,0,0,0,0,0,9.8\n1.5,0,0,0,0,0,9.8\n");
  EXPECT_THROW(imu.loadCsv(backwards, 1.0), vpPoseGravityException);
  EXPECT_EQ(imu.size(), 1u);
  imu.loadCsv(tempFile("imu_good.csv", "1,0,0,0,0,0,9.8\n2,0,0,0,0,0,9.8\n3,0,0,0,0,0,9.8\n"), 1.0);
  EXPECT_EQ(imu.size(), 4u);
}

// An empty field was skipped (the line split on blanks too): in a file of 8 columns, "2,0,,0,0,0,9.8,25" read as
// the 7 numbers of a row, every column after the gap shifted, and the file was refused at the next line.
TEST(PoseGravityImu, AnEmptyFieldIsRefusedAtItsLine)
{
  vpImuGravity imu;
  const std::string gap = tempFile("imu_gap.csv", "1,0,0,0,0,0,9.8\n2,0,,0,0,0,9.8,25\n3,0,0,0,0,0,9.8,25\n");
  try {
    imu.loadCsv(gap, 1.0);
    ADD_FAILURE() << "an empty field was read";
  } catch (const vpPoseGravityException &e) {
    EXPECT_NE(e.getStringMessage().find("imu_gap.csv:2:"), std::string::npos) << e.getStringMessage();
  }
  EXPECT_EQ(imu.size(), 0u);
}

// A matrix that is not a rotation is refused where a rotation is taken, as loadRotation() refuses it in a file:
// a sheared matrix turned gravity by 27 deg without a word.
TEST(PoseGravityImu, ANonRotationIsRefused)
{
  vpRotationMatrix sheared;
  sheared[0][1] = 0.5;
  vpRotationMatrix reflection;
  reflection[2][2] = -1.0;
  vpRotationMatrix notFinite;
  notFinite[1][1] = std::numeric_limits<double>::quiet_NaN();
  for (const vpRotationMatrix &R : {sheared, reflection, notFinite}) {
    vpImuGravity imu;
    EXPECT_THROW(imu.setImuToSensorRotation(R), vpPoseGravityException);
    EXPECT_THROW(vpImuGravity::gravityFromSpecificForce(vec(0, 0, kG), R), vpPoseGravityException);
  }
  vpImuGravity imu;
  EXPECT_THROW(imu.setTimeOffset(std::numeric_limits<double>::quiet_NaN()), vpPoseGravityException);
  const vpRotationMatrix R(vpThetaUVector(0.1, -0.2, 0.3));
  EXPECT_NO_THROW(imu.setImuToSensorRotation(R));
  const vpColVector g = vpImuGravity::gravityFromSpecificForce(vec(0, 0, kG), R);
  const vpColVector expected = -(R * vec(0, 0, 1));
  for (unsigned int i = 0; i < 3; ++i)
    EXPECT_NEAR(g[i], expected[i], 1e-12);
}
