/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Small helpers shared by the tutorial programs, kept out of them so that each tutorial reads as the
  pipeline it shows: the command line (vpCommandLine of example/common) and the exit status
  (vpTutorialProgram), the window of --display (vpTutorialViewer), a simulated IMU reading, a check,
  and a captioned image written as PNG. Installed with the package (VispSensorPose::vsp_tutorial_common),
  so that a tutorial folder copied out of the repository builds against an install.
*/
#ifndef VP_TUTORIAL_COMMON_H
#define VP_TUTORIAL_COMMON_H

#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <string>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/gui/vpDisplayOpenCV.h>
#include <visp3/gui/vpDisplayX.h>
#include <visp3/io/vpImageIo.h>

#include "vpCommandLine.h"

/*!
  The frame of a tutorial program: its command line (vpCommandLine with `--output <dir>`, where the
  pictures go, `--display`, which opens a window, `--help`, and the integer options the program
  declares with addOption()) and its exit status (success when the tutorial's checks against the
  simulation's ground truth pass). Without `--display` the program is headless, as under ctest.

  \code
  bool runTutorial(int frames, const std::string &outputDir); // true when the results are within bounds

  int main(int argc, char **argv)
  {
    int frames = 40;
    vpTutorialProgram program("[--frames N]", "What the program does.");
    program.addOption("--frames", frames, 2, "number of frames");
    return program.run(argc, argv, [&](const std::string &outputDir) { return runTutorial(frames, outputDir); });
    // program.display() tells, inside the lambda, whether --display was given.
  }
  \endcode
*/
class vpTutorialProgram
{
public:
  //! \e options is the synopsis of the program's own options; the description is printed by `--help`.
  vpTutorialProgram(const std::string &options, const std::string &description)
    : m_outputDir("."), m_display(false),
      m_commandLine(options.empty() ? "[--output DIR] [--display]" : "[--output DIR] [--display] " + options,
                    description)
  {
    m_commandLine.addString("--output", m_outputDir, "DIR",
                            "folder of the PNG files, created if needed (default: current directory)");
    m_commandLine.addFlag("--display", m_display,
                          "show the frames in a window (vpDisplayX or vpDisplayOpenCV); headless by default");
  }
  vpTutorialProgram(const vpTutorialProgram &) = delete; // the command line refers to m_outputDir
  vpTutorialProgram &operator=(const vpTutorialProgram &) = delete;

  //! Declares `name N`: an integer stored in value, which must be at least minValue.
  void addOption(const std::string &name, int &value, int minValue, const std::string &help)
  {
    m_commandLine.addInt(name, value, "N", help + " (default " + std::to_string(value) + ")", minValue);
  }

  //! Declares `name VALUE`: a string stored in value.
  void addString(const std::string &name, std::string &value, const std::string &valueName, const std::string &help)
  {
    m_commandLine.addString(name, value, valueName, help);
  }

  //! True when the program was run with --display (valid once run() has parsed the command line).
  bool display() const { return m_display; }

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

  /*!
    The main of a tutorial with one integer option: declares `name N` (default \e value, at least
    \e minValue), then runs body(N, outputDir, display()) as run() above does.
  */
  int run(int argc, char **argv, const std::string &name, int value, int minValue, const std::string &help,
          const std::function<bool(int, const std::string &, bool)> &body)
  {
    addOption(name, value, minValue, help);
    return run(argc, argv, [&](const std::string &outputDir) { return body(value, outputDir, m_display); });
  }

private:
  std::string m_outputDir;
  bool m_display;
  vpCommandLine m_commandLine;
};

/*!
  The window of a tutorial run with --display: vpDisplayX, or vpDisplayOpenCV when ViSP was built
  without X11. A viewer that is not enabled (the default, headless runs under ctest) does nothing, so
  the tutorial's loop calls it unconditionally.

  \code
  vpTutorialViewer viewer(program.display(), "Tracking");
  for (...) {
    viewer.show(I); // I: vpImage<unsigned char> or vpImage<vpRGBa>
    vpDisplay::displayFrame(viewer.image(), cMo, cam, 0.05, vpColor::none, 2); // any vpDisplay drawing
    viewer.flush();
  }
  viewer.waitClick();
  \endcode
*/
class vpTutorialViewer
{
public:
  //! A viewer that opens a window titled \e title at the first show() when \e enabled.
  vpTutorialViewer(bool enabled, const std::string &title) : m_enabled(enabled), m_title(title) {}

  //! True when frames are shown.
  bool enabled() const { return m_enabled; }

  //! Copies I into the window's image and displays it; draw on image() then call flush().
  void show(const vpImage<unsigned char> &I)
  {
    if (!m_enabled)
      return;
    vpImageConvert::convert(I, m_image);
    open();
    vpDisplay::display(m_image);
  }
  //! \overload
  void show(const vpImage<vpRGBa> &I)
  {
    if (!m_enabled)
      return;
    m_image = I;
    open();
    vpDisplay::display(m_image);
  }

  //! The image shown, for vpDisplay drawing calls between show() and flush().
  vpImage<vpRGBa> &image() { return m_image; }

  //! Shows what was drawn, then waits \e waitMs milliseconds so that the motion can be followed.
  void flush(double waitMs = 30)
  {
    if (!m_enabled)
      return;
    vpDisplay::flush(m_image);
    vpTime::wait(waitMs);
  }

  //! Prints \e message in the window and waits for a click (the end of the tutorial).
  void waitClick(const std::string &message = "Click to quit")
  {
    if (!m_enabled || !m_display)
      return;
    vpDisplay::displayText(m_image, static_cast<int>(m_image.getHeight()) - 20, 10, message, vpColor::red);
    vpDisplay::flush(m_image);
    vpDisplay::getClick(m_image, true);
  }

private:
  //! Opens the window at the first frame, and again when the image size changes.
  void open()
  {
    if (m_display && m_display->getWidth() == m_image.getWidth() && m_display->getHeight() == m_image.getHeight())
      return;
    m_display.reset();
#if defined(VISP_HAVE_X11)
    m_display = std::make_unique<vpDisplayX>(m_image, 50, 50, m_title);
#elif defined(VISP_HAVE_OPENCV)
    m_display = std::make_unique<vpDisplayOpenCV>(m_image, 50, 50, m_title);
#else
    throw vpException(vpException::fatalError, "--display: ViSP was built without X11 and without OpenCV");
#endif
  }

  bool m_enabled;
  std::string m_title;
  vpImage<vpRGBa> m_image;
  std::unique_ptr<vpDisplay> m_display;
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

//! Error of an estimated pose against the truth: translation (mm) and rotation angle (deg) of the difference.
inline void vpTutorialPoseError(const vpHomogeneousMatrix &cMoEst, const vpHomogeneousMatrix &cMoTrue, double &errMm,
                                double &errDeg)
{
  errMm = 1000.0 * (cMoEst.getTranslationVector() - cMoTrue.getTranslationVector()).frobeniusNorm();
  errDeg = vpMath::deg(vpThetaUVector((cMoEst * cMoTrue.inverse()).getRotationMatrix()).getTheta());
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
