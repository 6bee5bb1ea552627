/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Small helpers shared by the tutorial programs, kept out of them so that each tutorial reads as the
  pipeline it shows: the command line and the exit status (vpTutorialProgram), a simulated IMU
  reading, and a captioned image written as PNG. Header only.
*/
#ifndef VP_TUTORIAL_COMMON_H
#define VP_TUTORIAL_COMMON_H

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/io/vpImageIo.h>

/*!
  The frame of a tutorial program: its command line (`--output <dir>`, where the pictures go,
  `--help`, and the integer options the program declares with addOption()) and its exit status
  (success when the tutorial's checks against the simulation's ground truth pass).

  \code
  bool runTutorial(int frames, const std::string &outputDir); // true when the results are within bounds

  int main(int argc, char **argv)
  {
    int frames = 40;
    vpTutorialProgram program("What the program does.");
    program.addOption("--frames", frames, 2, "number of frames");
    return program.run(argc, argv, [&](const std::string &outputDir) { return runTutorial(frames, outputDir); });
  }
  \endcode
*/
class vpTutorialProgram
{
public:
  //! The description is printed by `--help`.
  explicit vpTutorialProgram(const std::string &description) : m_description(description), m_outputDir(".") {}

  //! Declares `name <n>`: an integer stored in value, which must be at least minValue.
  void addOption(const std::string &name, int &value, int minValue, const std::string &help)
  {
    m_options.push_back(Option{name, help, &value, minValue});
  }

  /*!
    Reads the command line, creates the output folder and calls body(outputDir). Returns the exit
    status of the program: EXIT_SUCCESS after `--help` or when body returns true; EXIT_FAILURE on an
    unknown, incomplete or out-of-range option (the usage is printed on the error stream), when the
    folder cannot be created, when body throws a vpException or returns false.
  */
  int run(int argc, char **argv, const std::function<bool(const std::string &)> &body)
  {
    const std::string program = argc > 0 ? argv[0] : "tutorial";
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        printUsage(program, std::cout);
        return EXIT_SUCCESS;
      }
      const bool hasValue = i + 1 < argc;
      if (arg == "--output" && hasValue) {
        m_outputDir = argv[++i];
        continue;
      }
      Option *option = find(arg);
      if (option == nullptr || !hasValue || !parseInteger(argv[i + 1], option->minValue, *option->value)) {
        std::cerr << "Unknown, incomplete or out-of-range option: " << arg;
        if (hasValue && option != nullptr)
          std::cerr << " " << argv[i + 1];
        std::cerr << "\n";
        printUsage(program, std::cerr);
        return EXIT_FAILURE;
      }
      ++i;
    }
    try {
      vpIoTools::makeDirectory(m_outputDir);
      return body(m_outputDir) ? EXIT_SUCCESS : EXIT_FAILURE;
    } catch (const vpException &e) {
      std::cerr << "Error: " << e.getMessage() << std::endl;
      return EXIT_FAILURE;
    }
  }

private:
  struct Option
  {
    std::string name;
    std::string help;
    int *value;
    int minValue;
  };

  Option *find(const std::string &name)
  {
    for (Option &option : m_options)
      if (option.name == name)
        return &option;
    return nullptr;
  }

  //! The whole text must be a base-10 integer within [minValue, INT_MAX].
  static bool parseInteger(const char *text, int minValue, int &value)
  {
    errno = 0;
    char *end = nullptr;
    const long parsed = std::strtol(text, &end, 10);
    if (errno != 0 || end == text || *end != '\0' || parsed < minValue || parsed > INT_MAX)
      return false;
    value = static_cast<int>(parsed);
    return true;
  }

  void printUsage(const std::string &program, std::ostream &os) const
  {
    os << "Usage: " << program << " [--output <dir>]";
    for (const Option &option : m_options)
      os << " [" << option.name << " <n>]";
    os << " [--help]\n  " << m_description << "\n"
       << "  --output <dir>: folder of the PNG files, created if needed (default: current directory)\n";
    for (const Option &option : m_options)
      os << "  " << option.name << " <n>: " << option.help << " (default " << *option.value << ", at least "
         << option.minValue << ")\n";
  }

  std::string m_description;
  std::string m_outputDir;
  std::vector<Option> m_options;
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
