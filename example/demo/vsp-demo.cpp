/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-demo.cpp
  The main demo, run without arguments on the data shipped in data/:
  -# the simulated hard laser sequence (data/laser_hard): each image through vpLaserConicDetector,
     then GP3, PP3, PP5 and PLANE_PAIR (vpLaserConicPose), compared with the ground truth;
  -# the simulated gravity-aided pose sequence (data/gravity_sequence): vpPoseGravity with P3P,
     P3P + refinePose, LEAST_SQUARES and RANSAC, and vpPose on the same points for comparison.
  It prints a per-method summary and writes CSV results, PNG plots and overlays to the output folder.

  \verbatim
  vsp-demo [--output DIR] [--data DIR] [--frames N] [--check]
  \endverbatim
  Without --data, the data is looked for relative to the program itself: installed as
  <prefix>/bin/vsp-demo, it reads <prefix>/share/VispSensorPose/data (VSP_DATA_RELATIVE_TO_PROGRAM); in
  the build tree a link at the same relative place points to the repository's data/. No absolute path
  is compiled in, so the installed tree can be moved.
*/
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include <visp3/core/vpException.h>

#include "demoCommon.h"
#include "vpCommandLine.h"

namespace
{
/*!
  The folder of the running program: /proc/self/exe (links resolved), or argv[0] when that is
  unavailable.
*/
std::filesystem::path programFolder(const char *argv0)
{
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty())
    exe = std::filesystem::weakly_canonical(std::filesystem::absolute(argv0), ec);
  return exe.parent_path();
}

//! Default data folder: VSP_DATA_RELATIVE_TO_PROGRAM (set by CMake from the install layout) below the program's folder.
std::string defaultDataDir(const char *argv0)
{
  return (programFolder(argv0) / VSP_DATA_RELATIVE_TO_PROGRAM).lexically_normal().string();
}

//! Declares the options of the demo; \e options receives their values.
vpCommandLine commandLine(vpDemoOptions &options)
{
  vpCommandLine cli("[--output DIR] [--data DIR] [--frames N] [--check]",
                    "Runs the laser and gravity-aided pose sequences of data/ and compares every method with the "
                    "ground truth.");
  cli.addString("--output", options.outputDir, "DIR",
                "folder for the CSV results, PNG plots and overlays (default ./demo-output)");
  cli.addString("--data", options.dataDir, "DIR",
                "folder holding laser_hard/ and gravity_sequence/ (default " + options.dataDir +
                    ": " VSP_DATA_RELATIVE_TO_PROGRAM " from the folder of this program)");
  cli.addUnsigned("--frames", options.maxFrames, "N", "process only the first N frames of each sequence", 1);
  cli.addFlag("--check", options.check, "exit with status 1 when an error exceeds its bound (see the bounds printed)");
  return cli;
}

//! True when \e path is \e folder or lies below it (paths made absolute, "..", "." and links resolved).
bool isInside(const std::string &path, const std::string &folder)
{
  const auto resolve = [](const std::string &name) {
    std::error_code ec;
    std::filesystem::path r = std::filesystem::weakly_canonical(std::filesystem::absolute(name), ec);
    return r.has_filename() ? r : r.parent_path(); // "dir/" and "dir" alike
  };
  const std::filesystem::path p = resolve(path), f = resolve(folder);
  const auto mismatch = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
  return mismatch.first == f.end();
}

//! Prints the bounds of --check, each in the unit of its error column in \e summaries.
void printBounds(const std::vector<vpAccuracyBound> &bounds, const std::vector<vpMethodSummary> &summaries)
{
  for (const vpAccuracyBound &b : bounds) {
    std::string unit;
    for (const vpMethodSummary &s : summaries)
      for (const vpErrorColumn &c : s.errors)
        if (s.method == b.method && c.name == b.quantity)
          unit = " " + c.unit;
    std::cout << "  " << b.method << " " << b.statistic << " " << b.quantity << " error <= " << b.value << unit << "  ("
              << b.why << ")\n";
  }
}
} // namespace

int main(int argc, char **argv)
{
  vpDemoOptions options;
  options.dataDir = defaultDataDir(argv[0]);
  options.outputDir = "demo-output";
  vpCommandLine cli = commandLine(options);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (!std::filesystem::is_directory(options.dataDir))
    return cli.fail("no data folder '" + options.dataDir + "': give the folder holding laser_sequence/ and " +
                    "gravity_sequence/ with --data DIR");
  if (isInside(options.outputDir, options.dataDir))
    return cli.fail("the output folder '" + options.outputDir + "' is inside the data folder '" + options.dataDir +
                    "': choose another one (the shipped data is never written)");
  std::error_code ec;
  std::filesystem::create_directories(options.outputDir, ec);
  if (!std::filesystem::is_directory(options.outputDir)) {
    std::cerr << argv[0] << ": cannot create the output folder '" << options.outputDir << "'" << std::endl;
    return EXIT_FAILURE;
  }
  const std::string outputPath = std::filesystem::absolute(options.outputDir).lexically_normal().string();
  std::cout << "Data: " << std::filesystem::weakly_canonical(std::filesystem::absolute(options.dataDir), ec).string()
            << "\nOutput: " << outputPath << std::endl;

  std::vector<vpMethodSummary> laser, gravity;
  std::string laserNote, gravityNote;
  std::vector<std::string> files;
  try {
    if (!runLaserDemo(options, laser, laserNote, files) || !runGravityDemo(options, gravity, gravityNote, files))
      return EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << argv[0] << ": " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }

  printSummary(std::cout, "Summary of the laser sequence", laser, laserNote);
  printSummary(std::cout, "Summary of the gravity-aided pose sequence", gravity, gravityNote);
  std::cout << "\nWrote " << files.size() << " files to " << outputPath << ":\n";
  for (const std::string &f : files)
    std::cout << "  " << std::filesystem::path(f).filename().string() << "\n";

  if (!options.check)
    return EXIT_SUCCESS;
  std::cout << "\nChecks (--check):\n";
  printBounds(laserBounds(), laser);
  printBounds(gravityBounds(), gravity);
  // Every estimator must give a result on at least 95 % of the frames of the laser sequence; on the
  // gravity sequence, 10 of the 60 frames hold a mismatched point, which LEAST_SQUARES may refuse.
  const bool laserPass = checkBounds(std::cout, laser, laserBounds(), 0.95);
  const bool pass = checkBounds(std::cout, gravity, gravityBounds(), 0.8) && laserPass;
  std::cout << (pass ? "All checks passed" : "Some checks FAILED") << std::endl;
  return pass ? EXIT_SUCCESS : EXIT_FAILURE;
}
