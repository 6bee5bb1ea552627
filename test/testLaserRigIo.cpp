/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of the laser calibration files of vpLaserRigIo: the YAML format (a vpPoseVector that ViSP reads
// back), the older laser.txt, and the messages on malformed files.
#include "vpLaserRigIo.h"

#include <gtest/gtest.h>

#include <fstream>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpPoseVector.h>

namespace
{
std::string workFile(const std::string &name) { return std::string(VSP_WORK_DIR) + "/" + name; }

void writeText(const std::string &file, const std::string &text) { std::ofstream(file.c_str()) << text; }

vpLaserCalibrationData sampleCalibration()
{
  vpLaserCalibrationData c;
  c.openingAngle = vpMath::rad(33.987654321);
  c.cMl = vpHomogeneousMatrix(0.1012345, 0.0201234, -0.0098765, vpMath::rad(3.1), vpMath::rad(-5.2), 0.0);
  c.hasStdDeviations = true;
  c.stdDeviations = vpColVector(6);
  const double s[6] = {5.7e-5, 5.8e-5, 4.4e-5, 4.5e-5, 1.0e-4, 8.1e-5};
  for (unsigned int k = 0; k < 6; ++k)
    c.stdDeviations[k] = s[k];
  c.rms = 2.98e-4;
  c.nbViews = 9;
  return c;
}

// The error message of reading a file made of \e text.
std::string readError(const std::string &text)
{
  const std::string file = workFile("malformed_laser.yaml");
  writeText(file, text);
  vpLaserCalibrationData c;
  std::string error;
  EXPECT_FALSE(vpLaserRigIo::readLaserCalibration(file, c, error));
  return error;
}

const char *const kValidYaml = "opening_angle_deg: 34\nrows: 6\ncols: 1\ndata:\n  - [0.1]\n  - [0]\n  - [0]\n"
                               "  - [0]\n  - [0]\n  - [0]\n";
} // namespace

TEST(LaserRigIo, YamlRoundTripKeepsThePoseTheAngleAndTheStandardDeviations)
{
  const vpLaserCalibrationData written = sampleCalibration();
  const std::string file = workFile("laser_roundtrip.yaml");
  std::string error;
  ASSERT_TRUE(vpLaserRigIo::writeLaserCalibrationYaml(file, written, error)) << error;
  vpLaserCalibrationData read;
  ASSERT_TRUE(vpLaserRigIo::readLaserCalibration(file, read, error)) << error;
  EXPECT_NEAR(read.openingAngle, written.openingAngle, 1e-15);
  // vpPoseVector::saveYAML() writes 6 significant digits: 1e-7 m and 1e-7 rad here.
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      EXPECT_NEAR(read.cMl[i][j], written.cMl[i][j], 1e-6);
  EXPECT_TRUE(read.hasStdDeviations);
  for (unsigned int k = 0; k < 6; ++k)
    EXPECT_NEAR(read.stdDeviations[k], written.stdDeviations[k],
                1e-5 * written.stdDeviations[k]); // 6 digits, in degrees for the angles
  EXPECT_NEAR(read.rms, written.rms, 1e-9);
  EXPECT_EQ(read.nbViews, 9u);

  // A ViSP user reads the pose with ViSP alone.
  vpPoseVector pose;
  ASSERT_TRUE(vpPoseVector::loadYAML(file, pose));
  const vpHomogeneousMatrix cMl(pose);
  for (unsigned int i = 0; i < 3; ++i)
    EXPECT_NEAR(cMl[i][3], written.cMl[i][3], 1e-6);

  // The two-output overload reads the same file.
  double angle = 0.0;
  vpHomogeneousMatrix M;
  ASSERT_TRUE(vpLaserRigIo::readLaserCalibration(file, angle, M, error)) << error;
  EXPECT_NEAR(angle, written.openingAngle, 1e-15);

  // Without standard deviations.
  vpLaserCalibrationData bare = written;
  bare.hasStdDeviations = false;
  bare.rms = -1.0;
  bare.nbViews = 0;
  ASSERT_TRUE(vpLaserRigIo::writeLaserCalibrationYaml(file, bare, error));
  ASSERT_TRUE(vpLaserRigIo::readLaserCalibration(file, read, error)) << error;
  EXPECT_FALSE(read.hasStdDeviations);
  EXPECT_LT(read.rms, 0.0);
}

TEST(LaserRigIo, TheOlderTextFormatIsStillRead)
{
  vpLaserCalibrationData read;
  std::string error;
  ASSERT_TRUE(
      vpLaserRigIo::readLaserCalibration(std::string(VSP_DATA_DIR) + "/laser_sequence/laser_true.txt", read, error))
      << error;
  EXPECT_NEAR(vpMath::deg(read.openingAngle), 34.0, 1e-9);
  EXPECT_FALSE(read.hasStdDeviations);
  const std::string file = workFile("laser_old.txt");
  const vpLaserCalibrationData c = sampleCalibration();
  ASSERT_TRUE(vpLaserRigIo::writeLaserCalibration(file, c.openingAngle, c.cMl, error));
  ASSERT_TRUE(vpLaserRigIo::readLaserCalibration(file, read, error)) << error;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      EXPECT_NEAR(read.cMl[i][j], c.cMl[i][j], 1e-15);
}

TEST(LaserRigIo, MalformedYamlFilesAreRefusedWithTheLine)
{
  std::string error;
  vpLaserCalibrationData c;
  EXPECT_FALSE(vpLaserRigIo::readLaserCalibration(workFile("no_such_laser.yaml"), c, error));
  EXPECT_NE(error.find("cannot open"), std::string::npos);
  writeText(workFile("valid_laser.yaml"), kValidYaml); // the reference the malformed files are made from
  EXPECT_TRUE(vpLaserRigIo::readLaserCalibration(workFile("valid_laser.yaml"), c, error)) << error;
  EXPECT_NE(
      readError(std::string(kValidYaml).replace(0, 17, "opening_angle_deg: 190")).find("line 1: opening_angle_deg"),
      std::string::npos);
  EXPECT_NE(readError(std::string("colour: red\n") + kValidYaml).find("line 1: unknown key 'colour'"),
            std::string::npos);
  EXPECT_NE(readError(std::string(kValidYaml).replace(std::string(kValidYaml).find("[0.1]"), 5, "[0.1x]"))
                .find("line 5: expected a pose row"),
            std::string::npos);
  EXPECT_NE(readError(std::string(kValidYaml).substr(std::string(kValidYaml).find("rows:")))
                .find("missing 'opening_angle_deg"),
            std::string::npos);
  EXPECT_NE(
      readError(std::string("std_dev_apex_m: [1e-5, 1e-5]\n") + kValidYaml).find("std_dev_apex_m expects a list of 3"),
      std::string::npos);
  EXPECT_NE(readError(std::string("std_dev_apex_m: [1e-5, 1e-5, 1e-5]\n") + kValidYaml).find("or none"),
            std::string::npos);
  EXPECT_NE(readError("opening_angle_deg: 34\nrows: 4\ncols: 4\ndata:\n  - [1, 0, 0, 0]\n")
                .find("line 5: expected a pose row"),
            std::string::npos);
  EXPECT_NE(readError(std::string(kValidYaml).replace(std::string(kValidYaml).find("rows: 6"), 7, "rows: 5"))
                .find("vpPoseVector"),
            std::string::npos);
}

TEST(LaserRigIo, CameraWithDistortionIsRead)
{
  const std::string file = workFile("camera_distortion.xml");
  const vpCameraParameters cam(1500, 1490, 800, 600, -0.12, 0.13);
  std::string error;
  ASSERT_TRUE(vpLaserRigIo::writeCamera(file, cam, 1600, 1200, error));
  vpCameraParameters read;
  unsigned int w = 0, h = 0;
  ASSERT_TRUE(vpLaserRigIo::readCamera(file, "Camera", read, w, h, error)) << error;
  EXPECT_EQ(read.get_projModel(), vpCameraParameters::perspectiveProjWithDistortion);
  EXPECT_NEAR(read.get_kdu(), 0.13, 1e-12);
  EXPECT_NEAR(read.get_kud(), -0.12, 1e-12);
  EXPECT_EQ(w, 1600u);
}
