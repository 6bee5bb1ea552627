/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Small helpers shared by the tutorial programs, kept out of them so that each tutorial reads as the
  pipeline it shows: the command line (vpCommandLine of example/common) and the exit status
  (vpTutorialProgram), a simulated IMU reading, a check, and a captioned image written as PNG.
*/
#ifndef VP_TUTORIAL_COMMON_H
#define VP_TUTORIAL_COMMON_H

#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <string>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/io/vpImageIo.h>

#include "vpCommandLine.h"

/*!
  The frame of a tutorial program: its command line (vpCommandLine with `--output <dir>`, where the
  pictures go, `--help`, and the integer options the program declares with addOption()) and its exit
  status (success when the tutorial's checks against the simulation's ground truth pass).

  \code
  bool runTutorial(int frames, const std::string &outputDir); // true when the results are within bounds

  int main(int argc, char **argv)
  {
    int frames = 40;
    vpTutorialProgram program("[--frames N]", "What the program does.");
    program.addOption("--frames", frames, 2, "number of frames");
    return program.run(argc, argv, [&](const std::string &outputDir) { return runTutorial(frames, outputDir); });
  }
  \endcode
*/
class vpTutorialProgram
{
public:
  //! \e options is the synopsis of the program's own options; the description is printed by `--help`.
  vpTutorialProgram(const std::string &options, const std::string &description)
    : m_outputDir("."), m_commandLine(options.empty() ? "[--output DIR]" : "[--output DIR] " + options, description)
  {
    m_commandLine.addString("--output", m_outputDir, "DIR",
                            "folder of the PNG files, created if needed (default: current directory)");
  }
  vpTutorialProgram(const vpTutorialProgram &) = delete; // the command line refers to m_outputDir
  vpTutorialProgram &operator=(const vpTutorialProgram &) = delete;

  //! Declares `name N`: an integer stored in value, which must be at least minValue.
  void addOption(const std::string &name, int &value, int minValue, const std::string &help)
  {
    m_commandLine.addInt(name, value, "N", help + " (default " + std::to_string(value) + ")", minValue);
  }

  /*!
    Reads the command line, creates the output folder and calls body(outputDir). Returns the exit
    status of the program: EXIT_SUCCESS after `--help` or when body returns true; EXIT_FAILURE on a
    bad command line, when the folder cannot be created, when body throws a vpException or returns
    false.
  */
  int run(int argc, char **argv, const std::function<bool(const std::string &)> &body)
  {
    if (!m_commandLine.parse(argc, argv))
      return m_commandLine.exitStatus();
    try {
      vpIoTools::makeDirectory(m_outputDir);
      return body(m_outputDir) ? EXIT_SUCCESS : EXIT_FAILURE;
    } catch (const vpException &e) {
      std::cerr << "Error: " << e.getMessage() << std::endl;
      return EXIT_FAILURE;
    }
  }

private:
  std::string m_outputDir;
  vpCommandLine m_commandLine;
};

/*!
  What an IMU measures of the gravity direction g: g plus Gaussian noise of standard deviation sigma
  on each component (for a unit g, sigma in radians is about the tilt noise).
*/
inline vpColVector vpTutorialMeasureGravity(const vpColVector &g, double sigma, std::mt19937 &rng)
{
  std::normal_distribution<double> noise(0.0, sigma);
  vpColVector measured(3);
  for (unsigned int i = 0; i < 3; ++i)
    measured[i] = g[i] + noise(rng);
  return measured;
}

//! Returns ok; when it is false, prints "FAILED: " and what failed (the bounds) on the error stream.
inline bool vpTutorialCheck(bool ok, const std::string &what)
{
  if (!ok)
    std::cerr << "FAILED: " << what << std::endl;
  return ok;
}

//! Writes I as PNG (or any format vpImageIo knows from the extension) with a caption at its top left.
inline void vpTutorialWriteCaptioned(vpImage<vpRGBa> &I, const std::string &caption, const vpColor &color,
                                     const std::string &filename)
{
  const vpFont font(18);
  font.drawText(I, caption, vpImagePoint(8, 8), color, vpColor::black);
  vpImageIo::write(I, filename);
}

#endif
