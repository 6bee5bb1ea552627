/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-demo.cpp
  The main demo, run without arguments on the data shipped in data/:
  -# the simulated laser sequence (data/laser_sequence): each image through vpLaserConicDetector,
     then GP3, PP3, PP5 and PLANE_PAIR (vpLaserConicPose), compared with the ground truth;
  -# the simulated gravity-aided pose sequence (data/gravity_sequence): vpPoseGravity with P3P,
     P3P + refinePose, LEAST_SQUARES and RANSAC, and vpPose on the same points for comparison.
  It prints a per-method summary and writes CSV results, PNG plots and overlays to the output folder.

  \verbatim
  vsp-demo [--output DIR] [--data DIR] [--frames N] [--check]
  \endverbatim
*/
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include <visp3/core/vpException.h>

#include "demoCommon.h"
#include "vpCsvTools.h"

namespace
{
void printUsage(std::ostream &os, const char *program)
{
  os << "Usage: " << program << " [--output DIR] [--data DIR] [--frames N] [--check]\n"
     << "  --output  folder for the CSV results, PNG plots and overlays (default ./demo-output)\n"
     << "  --data    folder holding laser_sequence/ and gravity_sequence/ (default " << VSP_DATA_DIR << ")\n"
     << "  --frames  process only the first N frames of each sequence\n"
     << "  --check   exit with status 1 when an error exceeds its bound (see the bounds printed)\n";
}

bool parseOptions(int argc, char **argv, vpDemoOptions &options, bool &help, std::string &error)
{
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return true;
    }
    if (arg == "--check") {
      options.check = true;
      continue;
    }
    if (arg != "--output" && arg != "--data" && arg != "--frames") {
      error = "unknown option '" + arg + "'";
      return false;
    }
    if (i + 1 >= argc) {
      error = "option " + arg + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    if (arg == "--output")
      options.outputDir = value;
    else if (arg == "--data")
      options.dataDir = value;
    else if (!vpCsvTools::parseIndex(value, options.maxFrames, "--frames", "value", error))
      return false;
  }
  return true;
}

void printBounds(const std::vector<vpAccuracyBound> &bounds)
{
  for (const vpAccuracyBound &b : bounds)
    std::cout << "  " << b.method << " " << b.statistic << " " << b.quantity << " error <= " << b.value << "  ("
              << b.why << ")\n";
}
} // namespace

int main(int argc, char **argv)
{
  vpDemoOptions options;
  options.dataDir = VSP_DATA_DIR;
  options.outputDir = "demo-output";
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
  std::error_code ec;
  std::filesystem::create_directories(options.outputDir, ec);
  if (!std::filesystem::is_directory(options.outputDir)) {
    std::cerr << argv[0] << ": cannot create the output folder '" << options.outputDir << "'" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Data: " << options.dataDir << "\nOutput: " << std::filesystem::absolute(options.outputDir).string()
            << std::endl;

  std::vector<vpMethodSummary> laser, gravity;
  std::vector<std::string> files;
  try {
    if (!runLaserDemo(options, laser, files) || !runGravityDemo(options, gravity, files))
      return EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << argv[0] << ": " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }

  printSummary(std::cout, "Summary of the laser sequence", laser);
  printSummary(std::cout, "Summary of the gravity-aided pose sequence", gravity);
  std::cout << "\nWrote " << files.size() << " files to " << std::filesystem::absolute(options.outputDir).string()
            << ":\n";
  for (const std::string &f : files)
    std::cout << "  " << std::filesystem::path(f).filename().string() << "\n";

  if (!options.check)
    return EXIT_SUCCESS;
  std::cout << "\nChecks (--check):\n";
  printBounds(laserBounds());
  printBounds(gravityBounds());
  // Every estimator must give a result on at least 95 % of the frames of these clean sequences.
  const bool pass = checkBounds(std::cout, laser, laserBounds(), 0.95) &&
                    checkBounds(std::cout, gravity, gravityBounds(), 0.95);
  std::cout << (pass ? "All checks passed" : "Some checks FAILED") << std::endl;
  return pass ? EXIT_SUCCESS : EXIT_FAILURE;
}
