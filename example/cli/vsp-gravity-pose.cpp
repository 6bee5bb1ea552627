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
                   [--threshold T] [--seed N]
  \endverbatim
  Exit status: 0 when every frame was processed (frames without a pose get a status word in the
  output), 1 on a usage, file or format error (nothing is written then).
*/
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/pose_gravity/vpPoseGravity.h>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpGravityPointsIo.h"

namespace
{
struct Options
{
  std::string input, output;
  std::string methodName = "LEAST_SQUARES";
  bool refine = false;
  double threshold = 4e-3;
  unsigned int seed = 0;
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
                    "          [--threshold T] [--seed N]",
                    "Gravity-aided pose of each frame from its 2D/3D points and the two gravity vectors.");
  cli.addString("--input", options.input, "FILE",
                "per-frame gravity and 2D/3D points (rows 'frame,gravity,gcx,gcy,gcz,gox,goy,goz'\n"
                "and 'frame,point,oX,oY,oZ,x,y' with normalized image coordinates x, y)");
  cli.addString("--output", options.output, "FILE",
                "CSV 'frame,status,tx,ty,tz,tux,tuy,tuz' (cMo: translation in metres, theta-u in\n"
                "radians); never the input file");
  cli.addChoice("--method", options.methodName, {"P3P", "LEAST_SQUARES", "RANSAC"}, "METHOD",
                "P3P (first three points), LEAST_SQUARES (all points, default) or RANSAC");
  cli.addFlag("--refine", options.refine, "maximum-likelihood refinement of each pose on its points (RANSAC: inliers)");
  cli.addDouble("--threshold", options.threshold, "T",
                "RANSAC inlier threshold in normalized coordinates, pixels / focal (default 4e-3)", vpCommandLine::POSITIVE);
  cli.addUnsigned("--seed", options.seed, "N", "RANSAC seed (default 0)");
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
  return lookUp<vpPoseGravity::vpPoseGravityStatus>(status,
                                                    {{vpPoseGravity::STATUS_OK, "ok"},
                                                     {vpPoseGravity::STATUS_COINCIDENT_IMAGE_POINTS, "coincident_image_points"},
                                                     {vpPoseGravity::STATUS_VERTICAL_RAY, "vertical_ray"},
                                                     {vpPoseGravity::STATUS_NO_SOLUTION, "no_solution"},
                                                     {vpPoseGravity::STATUS_NO_CONSENSUS, "no_consensus"},
                                                     {vpPoseGravity::STATUS_REFINEMENT_FAILED, "refinement_failed"},
                                                     {vpPoseGravity::STATUS_INCONSISTENT_GRAVITY, "inconsistent_gravity"},
                                                     {vpPoseGravity::STATUS_GRAVITY_SIGN_REVERSED, "gravity_sign_reversed"},
                                                     {vpPoseGravity::STATUS_BEHIND_CAMERA, "behind_camera"}},
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

vpPoseRow estimateFrame(const vpGravityFrame &frame, const Options &options, const std::string &where)
{
  vpPoseRow row;
  row.frame = frame.frame;
  vpPoseGravity pose;
  pose.setRansacThreshold(options.threshold);
  pose.setRansacSeed(options.seed);
  try {
    pose.setCameraGravity(frame.gCam);
    pose.setObjectGravity(frame.gObj);
    pose.addPoints(frame.points);
    vpHomogeneousMatrix cMo;
    if (!pose.computePose(methodId(options.methodName), cMo)) {
      row.status = statusWord(pose.getStatus());
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
} // namespace

int main(int argc, char **argv)
{
  Options options;
  vpCommandLine cli = commandLine(options);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  std::string error;
  if (!vpCsvTools::checkOutputIsNotInput(options.output, {options.input}, error))
    return cli.fail(error);
  std::vector<vpGravityFrame> frames;
  if (!vpGravityPointsIo::readPoints(options.input, frames, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::vector<vpPoseRow> poses;
  unsigned int found = 0;
  for (const vpGravityFrame &frame : frames) {
    poses.push_back(estimateFrame(frame, options, vpCsvTools::location(options.input, frame.firstLine)));
    found += poses.back().status == "ok" ? 1 : 0;
  }
  if (!vpGravityPointsIo::writePoses(options.output, poses, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << options.methodName << (options.refine ? " + refinement" : "") << ": " << found << "/"
            << frames.size() << " frames with a pose, written to " << options.output << std::endl;
  return EXIT_SUCCESS;
}
