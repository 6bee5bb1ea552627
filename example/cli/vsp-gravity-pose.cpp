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

#include "vpCsvTools.h"
#include "vpGravityPointsIo.h"

namespace
{
struct Options
{
  std::string input, output;
  vpPoseGravity::vpPoseGravityMethod method = vpPoseGravity::LEAST_SQUARES;
  std::string methodName = "LEAST_SQUARES";
  bool refine = false;
  double threshold = 1e-3;
  unsigned int seed = 0;
};

void printUsage(std::ostream &os, const char *program)
{
  os << "Usage: " << program
     << " --input points.csv --output poses.csv [--method P3P|LEAST_SQUARES|RANSAC] [--refine]\n"
        "          [--threshold T] [--seed N]\n"
        "  --input      per-frame gravity and 2D/3D points (rows 'frame,gravity,gcx,gcy,gcz,gox,goy,goz'\n"
        "               and 'frame,point,oX,oY,oZ,x,y' with normalized image coordinates x, y)\n"
        "  --output     CSV 'frame,status,tx,ty,tz,tux,tuy,tuz' (cMo: translation in metres, theta-u in\n"
        "               radians); never the input file\n"
        "  --method     P3P (first three points), LEAST_SQUARES (all points, default) or RANSAC\n"
        "  --refine     maximum-likelihood refinement of each pose on its points (RANSAC: inliers)\n"
        "  --threshold  RANSAC inlier threshold in normalized coordinates (default 1e-3)\n"
        "  --seed       RANSAC seed (default 0)\n";
}

bool parseMethod(const std::string &name, Options &options)
{
  if (name == "P3P")
    options.method = vpPoseGravity::P3P;
  else if (name == "LEAST_SQUARES")
    options.method = vpPoseGravity::LEAST_SQUARES;
  else if (name == "RANSAC")
    options.method = vpPoseGravity::RANSAC;
  else
    return false;
  options.methodName = name;
  return true;
}

//! Parses the command line. \return false with \e error on a bad option.
bool parseOptions(int argc, char **argv, Options &options, bool &help, std::string &error)
{
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return true;
    }
    if (arg == "--refine") {
      options.refine = true;
      continue;
    }
    if (arg != "--input" && arg != "--output" && arg != "--method" && arg != "--threshold" && arg != "--seed") {
      error = "unknown option '" + arg + "'";
      return false;
    }
    if (i + 1 >= argc) {
      error = "option " + arg + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    if (arg == "--input")
      options.input = value;
    else if (arg == "--output")
      options.output = value;
    else if (arg == "--method" && !parseMethod(value, options)) {
      error = "unknown method '" + value + "' (P3P, LEAST_SQUARES or RANSAC)";
      return false;
    } else if (arg == "--threshold") {
      if (!vpCsvTools::parseDouble(value, options.threshold, "--threshold", "value", error) ||
          !(options.threshold > 0.0)) {
        error = "--threshold must be a positive number, got '" + value + "'";
        return false;
      }
    } else if (arg == "--seed" && !vpCsvTools::parseIndex(value, options.seed, "--seed", "value", error))
      return false;
  }
  if (options.input.empty() || options.output.empty()) {
    error = "--input and --output are required";
    return false;
  }
  return vpCsvTools::checkOutputIsNotInput(options.output, {options.input}, error);
}

//! Short status word of a vpPoseGravity status, for the CSV.
std::string statusWord(vpPoseGravity::vpPoseGravityStatus status)
{
  switch (status) {
  case vpPoseGravity::STATUS_OK:
    return "ok";
  case vpPoseGravity::STATUS_COINCIDENT_IMAGE_POINTS:
    return "coincident_image_points";
  case vpPoseGravity::STATUS_VERTICAL_RAY:
    return "vertical_ray";
  case vpPoseGravity::STATUS_NO_SOLUTION:
    return "no_solution";
  case vpPoseGravity::STATUS_NO_CONSENSUS:
    return "no_consensus";
  case vpPoseGravity::STATUS_REFINEMENT_FAILED:
    return "refinement_failed";
  case vpPoseGravity::STATUS_NOT_COMPUTED:
  default:
    return "not_computed";
  }
}

//! Status word of an input error reported by vpPoseGravity for one frame.
std::string errorWord(const vpException &e)
{
  switch (e.getCode()) {
  case vpPoseGravityException::badGravityError:
    return "bad_gravity";
  case vpPoseGravityException::notEnoughPointError:
    return "not_enough_points";
  case vpPoseGravityException::badPointError:
    return "bad_point";
  case vpPoseGravityException::degeneratePointsError:
    return "degenerate_points";
  default:
    return "error";
  }
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
    if (!pose.computePose(options.method, cMo)) {
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
  bool help = false;
  std::string error;
  if (!parseOptions(argc, argv, options, help, error)) {
    std::cerr << argv[0] << ": " << error << "\n";
    printUsage(std::cerr, argv[0]);
    return EXIT_FAILURE;
  }
  if (help) {
    printUsage(std::cout, argv[0]);
    return EXIT_SUCCESS;
  }
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
