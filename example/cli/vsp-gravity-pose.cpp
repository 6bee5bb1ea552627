/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-gravity-pose.cpp
  Command-line gravity-aided pose estimation: reads per-frame 2D/3D points and the two gravity
  vectors (format in vpGravityPointsIo.h and doc/usage_cli.md) and writes one pose cMo per frame.

  \verbatim
  vsp-gravity-pose --input points.csv --output poses.csv [--method P3P|LEAST_SQUARES|RANSAC] [--refine]
                   [--threshold PX --focal PX] [--seed N]
                   [--camera-imu imu.csv] [--object-imu imu.csv] [--frame-times times.csv]
                   [--camera-R-imu R.txt] [--object-R-imu R.txt] [--time-scale S] [--time-offset DT]
                   [--norm-tolerance A] [--keep-moving]
  \endverbatim
  With IMU streams (EuRoC / Kalibr CSV layout, see vpImuGravity), the gravity of each frame is
  interpolated at its exposure time, converted from specific force to a down direction and rotated
  into the camera (object) frame; frames taken while the IMU moves get the status imu_in_motion.
  Thresholds are in pixels, as in the other programs: --threshold PX is converted with the camera's
  focal length --focal PX (the points are in normalized coordinates).
  Exit status: 0 when every frame was processed (frames without a pose get a status word in the
  output), 1 on a usage, file or format error or a failed write (nothing is written then: the output
  is written to a temporary file renamed when complete). When most frames fail the gravity checks,
  one line on stderr names the suspected mistake (gravity sign, camera and object gravity exchanged,
  IMU rotation missing or to be transposed).
*/
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <visp3/pose_gravity/vpImuGravity.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpGravityPointsIo.h"
#include "vpOutputFile.h"

namespace
{
struct Options
{
  std::string input, output;
  // RANSAC by default: real matches hold mismatches, which LEAST_SQUARES refuses (or is pulled by).
  std::string methodName = "RANSAC";
  bool refine = false;
  double threshold = 3.0, focal = 0.0; // pixels; the camera's focal length in pixels converts them
  unsigned int seed = 0;
  // Raw IMU input (optional).
  std::string cameraImu, objectImu, frameTimes, cameraRImu, objectRImu;
  double timeScale = 1e-9, timeOffset = 0.0, normTolerance = 0.5;
  bool keepMoving = false;
};

vpPoseGravity::vpPoseGravityMethod methodId(const std::string &name)
{
  if (name == "P3P")
    return vpPoseGravity::P3P;
  return name == "RANSAC" ? vpPoseGravity::RANSAC : vpPoseGravity::LEAST_SQUARES;
}

//! Declares the options of the program; \e options receives their values.
vpCommandLine commandLine(Options &options)
{
  vpCommandLine cli("--input points.csv --output poses.csv [--method P3P|LEAST_SQUARES|RANSAC] [--refine]\n"
                    "          [--threshold PX --focal PX] [--seed N] [--camera-imu FILE] [--object-imu FILE]\n"
                    "          [--frame-times FILE] [--camera-R-imu FILE] [--object-R-imu FILE] [--time-scale S]\n"
                    "          [--time-offset DT] [--norm-tolerance A] [--keep-moving]",
                    "Gravity-aided pose of each frame from its 2D/3D points and the two gravity vectors.");
  cli.addString("--input", options.input, "FILE",
                "per-frame gravity and 2D/3D points (rows 'frame,gravity,gcx,gcy,gcz,gox,goy,goz'\n"
                "and 'frame,point,oX,oY,oZ,x,y' with normalized image coordinates x, y)");
  cli.addString("--output", options.output, "FILE",
                "CSV 'frame,status,tx,ty,tz,tux,tuy,tuz' (cMo: translation in metres, theta-u in\n"
                "radians); never the input file");
  cli.addChoice("--method", options.methodName, {"P3P", "LEAST_SQUARES", "RANSAC"}, "METHOD",
                "P3P (first three points), LEAST_SQUARES (all points) or RANSAC (all points, default)");
  cli.addFlag("--refine", options.refine, "maximum-likelihood refinement of each pose on its points (RANSAC: inliers)");
  cli.addDouble("--threshold", options.threshold, "PX",
                "RANSAC inlier threshold in pixels, as in vsp-laser-altimeter (default 3); converted to the\n"
                "normalized coordinates of the input with --focal",
                vpCommandLine::POSITIVE);
  cli.addDouble("--focal", options.focal, "PX",
                "focal length of the camera in pixels ((px + py) / 2 of its intrinsics); needed by --threshold\n"
                "(without both, the library's default 4e-3 normalized, 3.2 px at 800 px)",
                vpCommandLine::POSITIVE);
  cli.addUnsigned("--seed", options.seed, "N", "RANSAC seed (default 0)");
  cli.addString("--camera-imu", options.cameraImu, "FILE",
                "camera IMU stream, CSV 'timestamp,wx,wy,wz,ax,ay,az' (EuRoC imu0/data.csv or Kalibr\n"
                "imu.csv layout: gyro rad/s, accelerometer m/s^2); replaces the camera gravity columns");
  cli.addString("--object-imu", options.objectImu, "FILE",
                "object IMU stream (same layout); replaces the object gravity columns");
  cli.addString("--frame-times", options.frameTimes, "FILE",
                "CSV 'frame,timestamp': exposure time of each frame, in the unit of the IMU timestamps");
  cli.addString("--camera-R-imu", options.cameraRImu, "FILE",
                "rotation camera_R_imu (maps IMU vectors into the camera frame): 3x3, or 4x4 as Kalibr's T_cam_imu");
  cli.addString("--object-R-imu", options.objectRImu, "FILE", "rotation object_R_imu, same format");
  cli.addDouble("--time-scale", options.timeScale, "S", "seconds per timestamp unit (default 1e-9: nanoseconds)",
                vpCommandLine::POSITIVE);
  cli.addDouble("--time-offset", options.timeOffset, "DT", "IMU clock minus camera clock, seconds (default 0)");
  cli.addDouble("--norm-tolerance", options.normTolerance, "A",
                "|accelerometer| farther than A m/s^2 from 9.81 flags the frame as in motion (default 0.5)",
                vpCommandLine::POSITIVE);
  cli.addFlag("--keep-moving", options.keepMoving,
              "estimate the frames flagged in motion too (default: status imu_in_motion)");
  cli.require({"--input", "--output"});
  return cli;
}

//! The word of \e key in \e table, \e fallback when it is not there.
template <typename Key>
std::string lookUp(Key key, const std::vector<std::pair<Key, const char *> > &table, const char *fallback)
{
  for (const auto &entry : table)
    if (entry.first == key)
      return entry.second;
  return fallback;
}

//! Short status word of a vpPoseGravity status, for the CSV.
std::string statusWord(vpPoseGravity::vpPoseGravityStatus status)
{
  return lookUp<vpPoseGravity::vpPoseGravityStatus>(
      status,
      {{vpPoseGravity::STATUS_OK, "ok"},
       {vpPoseGravity::STATUS_COINCIDENT_IMAGE_POINTS, "coincident_image_points"},
       {vpPoseGravity::STATUS_VERTICAL_RAY, "vertical_ray"},
       {vpPoseGravity::STATUS_NO_SOLUTION, "no_solution"},
       {vpPoseGravity::STATUS_NO_CONSENSUS, "no_consensus"},
       {vpPoseGravity::STATUS_REFINEMENT_FAILED, "refinement_failed"},
       {vpPoseGravity::STATUS_INCONSISTENT_GRAVITY, "inconsistent_gravity"},
       {vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED, "gravity_sign_reversed"},
       {vpPoseGravity::STATUS_BEHIND_CAMERA, "behind_camera"},
       {vpPoseGravity::STATUS_GRAVITY_SWAPPED, "gravity_swapped"}},
      "not_computed");
}

//! Status word of an input error reported by vpPoseGravity for one frame.
std::string errorWord(const vpException &e)
{
  return lookUp<int>(e.getCode(),
                     {{vpPoseGravityException::badGravityError, "bad_gravity"},
                      {vpPoseGravityException::notEnoughPointError, "not_enough_points"},
                      {vpPoseGravityException::badPointError, "bad_point"},
                      {vpPoseGravityException::degeneratePointsError, "degenerate_points"}},
                     "error");
}

//! The IMU streams of the options and the frame times (empty when not given).
struct ImuInput
{
  bool camera = false, object = false;
  vpImuGravity cameraImu, objectImu;
  std::map<unsigned int, double> frameTimes;
};

//! Loads the IMU input named by the options; false with \e error on a file error.
bool loadImuInput(const Options &options, ImuInput &imu, std::string &error)
{
  imu.camera = !options.cameraImu.empty();
  imu.object = !options.objectImu.empty();
  if (!imu.camera && !imu.object)
    return true;
  if (options.frameTimes.empty()) {
    error = "--camera-imu / --object-imu need --frame-times";
    return false;
  }
  if (!vpGravityPointsIo::readFrameTimes(options.frameTimes, imu.frameTimes, error))
    return false;
  try {
    const std::pair<bool, vpImuGravity *> streams[2] = {{imu.camera, &imu.cameraImu}, {imu.object, &imu.objectImu}};
    const std::string files[2] = {options.cameraImu, options.objectImu};
    const std::string rotations[2] = {options.cameraRImu, options.objectRImu};
    for (int k = 0; k < 2; ++k) {
      if (!streams[k].first)
        continue;
      vpImuGravity &stream = *streams[k].second;
      stream.loadCsv(files[k], options.timeScale);
      if (!rotations[k].empty())
        stream.setImuToSensorRotation(vpImuGravity::loadRotation(rotations[k]));
      stream.setNormTolerance(options.normTolerance);
      stream.setTimeOffset(options.timeOffset);
    }
  } catch (const vpException &e) {
    error = e.getStringMessage();
    return false;
  }
  return true;
}

/*!
  Replaces the gravity of \e frame by the IMU streams' at its exposure time. \return "" when done, or
  the status word of the frame: no_frame_time, no_imu_data (time outside a stream), imu_in_motion.
*/
std::string gravityFromImu(const ImuInput &imu, const Options &options, vpGravityFrame &frame)
{
  if (!imu.camera && !imu.object)
    return "";
  const auto time = imu.frameTimes.find(frame.frame);
  if (time == imu.frameTimes.end())
    return "no_frame_time";
  const double t = time->second * options.timeScale;
  const std::pair<bool, const vpImuGravity *> streams[2] = {{imu.camera, &imu.cameraImu}, {imu.object, &imu.objectImu}};
  vpColVector *targets[2] = {&frame.gCam, &frame.gObj};
  for (int k = 0; k < 2; ++k) {
    if (!streams[k].first)
      continue;
    bool moving = false;
    if (!streams[k].second->gravityAt(t, *targets[k], moving))
      return "no_imu_data";
    if (moving && !options.keepMoving)
      return "imu_in_motion";
  }
  return "";
}

vpPoseRow estimateFrame(const vpGravityFrame &frame, const Options &options, const std::string &where,
                        vpPoseGravity::vpGravityMistake &mistake)
{
  mistake = vpPoseGravity::GRAVITY_MISTAKE_NONE;
  vpPoseRow row;
  row.frame = frame.frame;
  vpPoseGravity pose;
  if (options.focal > 0.0)
    pose.setRansacThreshold(options.threshold / options.focal);
  pose.setRansacSeed(options.seed);
  try {
    pose.setCameraGravity(frame.gCam);
    pose.setObjectGravity(frame.gObj);
    pose.addPoints(frame.points);
    vpHomogeneousMatrix cMo;
    if (!pose.computePose(methodId(options.methodName), cMo)) {
      row.status = statusWord(pose.getStatus());
      mistake = pose.getSuspectedMistake();
      return row;
    }
    if (options.refine)
      pose.refinePose(cMo); // a failed refinement keeps the closed-form pose
    row.cMo = cMo;
    row.status = "ok";
  } catch (const vpException &e) {
    // Bad data in one frame does not stop the others: its row says why, stderr says where.
    std::cerr << where << ": frame " << frame.frame << ": " << e.getStringMessage() << std::endl;
    row.status = errorWord(e);
  }
  return row;
}
/*!
  One line naming the suspected mistake when most estimated frames fail a gravity check (a per-frame
  status word alone would leave the user to guess), nothing otherwise.
*/
void printSequenceDiagnosis(const std::vector<vpPoseRow> &poses,
                            const std::map<vpPoseGravity::vpGravityMistake, unsigned int> &mistakes,
                            const Options &options, const char *program)
{
  unsigned int estimated = 0, gravityFailures = 0;
  for (const vpPoseRow &row : poses) {
    if (row.status == "imu_in_motion" || row.status == "no_frame_time" || row.status == "no_imu_data")
      continue;
    ++estimated;
    gravityFailures += row.status == "inconsistent_gravity" || row.status == "gravity_sign_reversed" ||
                               row.status == "gravity_swapped" || row.status == "no_consensus" ||
                               row.status == "behind_camera" || row.status == "no_solution"
                           ? 1
                           : 0;
  }
  if (estimated == 0 || 2 * gravityFailures <= estimated)
    return;
  vpPoseGravity::vpGravityMistake likely = vpPoseGravity::GRAVITY_MISTAKE_NONE;
  unsigned int count = 0;
  for (const auto &m : mistakes)
    if (m.first != vpPoseGravity::GRAVITY_MISTAKE_NONE && m.second > count) {
      likely = m.first;
      count = m.second;
    }
  std::string advice;
  if (likely == vpPoseGravity::GRAVITY_MISTAKE_SIGN_REVERSED)
    advice = vpPoseGravity::getMistakeMessage(likely) + " (" + std::to_string(count) +
             " frames): the gravity columns must point down (negate the accelerometer reading)";
  else if (likely == vpPoseGravity::GRAVITY_MISTAKE_SWAPPED)
    advice = vpPoseGravity::getMistakeMessage(likely) + " (" + std::to_string(count) +
             " frames): exchange the camera and object gravity (or --camera-imu and --object-imu)";
  else if ((!options.cameraImu.empty() && options.cameraRImu.empty()) ||
           (!options.objectImu.empty() && options.objectRImu.empty()))
    advice = std::string("an IMU stream is used without its rotation: give ") +
             (!options.cameraImu.empty() && options.cameraRImu.empty() ? "--camera-R-imu " : "") +
             (!options.objectImu.empty() && options.objectRImu.empty() ? "--object-R-imu " : "") +
             "(the IMU-to-sensor rotation)";
  else if (!options.cameraRImu.empty() || !options.objectRImu.empty())
    advice = "check --camera-R-imu / --object-R-imu: the rotation maps IMU vectors into the sensor frame "
             "(sensor_R_imu; give the transpose if the file holds imu_R_sensor)";
  else
    advice = "check that the gravity columns are down directions in the camera and object frames";
  std::cerr << program << ": " << gravityFailures << "/" << estimated
            << " frames fail the gravity checks (the gravity does not fit the points): " << advice
            << "; the poses of the other frames use the same gravity: do not trust them" << std::endl;
}
int run(int argc, char **argv)
{
  Options options;
  vpCommandLine cli = commandLine(options);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (cli.given("--threshold") && !cli.given("--focal"))
    return cli.fail("--threshold is in pixels: give the camera's focal length with --focal PX to convert it");
  std::string error;
  if (!vpOutputFile::checkWritable(options.output, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::vector<std::string> inputs;
  for (const std::string &f : {options.input, options.cameraImu, options.objectImu, options.frameTimes,
                               options.cameraRImu, options.objectRImu})
    if (!f.empty())
      inputs.push_back(f);
  if (!vpCsvTools::checkOutputIsNotInput(options.output, inputs, error))
    return cli.fail(error);
  ImuInput imu;
  if (!loadImuInput(options, imu, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::vector<vpGravityFrame> frames;
  // With both IMU streams the points file needs no gravity rows; with one, the other side's columns are used.
  if (!vpGravityPointsIo::readPoints(options.input, frames, error, !(imu.camera && imu.object))) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::vector<vpPoseRow> poses;
  std::map<vpPoseGravity::vpGravityMistake, unsigned int> mistakes;
  unsigned int found = 0;
  for (vpGravityFrame &frame : frames) {
    const std::string imuStatus = gravityFromImu(imu, options, frame);
    if (!imuStatus.empty()) {
      vpPoseRow row;
      row.frame = frame.frame;
      row.status = imuStatus;
      poses.push_back(row);
      continue;
    }
    vpPoseGravity::vpGravityMistake mistake = vpPoseGravity::GRAVITY_MISTAKE_NONE;
    poses.push_back(estimateFrame(frame, options, vpCsvTools::location(options.input, frame.firstLine), mistake));
    ++mistakes[mistake];
    found += poses.back().status == "ok" ? 1 : 0;
  }
  if (!vpGravityPointsIo::writePoses(options.output, poses, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << options.methodName << (options.refine ? " + refinement" : "") << ": " << found << "/" << frames.size()
            << " frames with a pose, written to " << options.output << std::endl;
  printSequenceDiagnosis(poses, mistakes, options, argv[0]);
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
