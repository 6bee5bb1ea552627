/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserSequenceCalibration.cpp
  \brief vsp-laser-calibrate --from-sequence: reads the frames' laser points (CSV frame,u,v or images
  through vpLaserConicDetector), self-calibrates the laser with the given scale constraint and writes the
  calibration file of the chessboard mode. The output is written only when the calibration succeeded.
*/
#include "vpLaserSequenceCalibration.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpImageFileCheck.h"
#include "vpLaserRigIo.h"
#include "vpOutputFile.h"

namespace vspLaserSequenceCalibration
{
namespace
{
struct Options
{
  std::string camera, cameraName = "Camera", points, imagesDir, listFile, laser, output, report, knownAltitude;
  double openingDeg = 0.0, apexDistance = 0.0, maxStdDeg = 0.1;
  unsigned int maxFrames = 40;
  bool sequence = false, previousBaseline = false, holdApex = false, estimateOpening = false;
};

vpCommandLine commandLine(Options &o)
{
  vpCommandLine cli(
      "--from-sequence --camera camera.xml [--camera-name Camera]\n"
      "          (--points points.csv | --images DIR | --list images.txt) --laser previous.yaml\n"
      "          [--opening-angle-deg A] [--apex-distance M | --previous-baseline | --hold-apex]\n"
      "          [--known-altitude FRAME:H[,FRAME:H...]] (at least one of them)\n"
      "          [--estimate-opening-angle] [--max-frames N] [--max-std-deg D] --output laser.yaml [--report FILE]",
      "Laser/camera self-calibration from ordinary frames of the ground at different attitudes (no chessboard).\n"
      "Images determine the cone but for its scale and for a one-parameter family of cones (the opening\n"
      "angle traded against the axis): give one length (apex distance, the previous calibration's baseline,\n"
      "or one frame's altitude) and the opening angle is held; give two (two frames' altitudes at different\n"
      "heights, or an apex constraint and one altitude) and the axis is far better determined, the angle\n"
      "can be estimated. A length off by x % gives altitudes off by x %.");
  cli.addFlag("--from-sequence", o.sequence, "the sequence mode (this usage)");
  cli.addString("--camera", o.camera, "FILE", "intrinsics in vpXmlParserCamera format (with distortion if it has it)");
  cli.addString("--camera-name", o.cameraName, "NAME", "camera name in that file (default Camera)");
  cli.addString("--points", o.points, "FILE", "CSV with a header and rows frame,u,v (pixels; frames numbered from 0)");
  cli.addString("--images", o.imagesDir, "DIR", "folder of images, in name order (laser points detected)");
  cli.addString("--list", o.listFile, "FILE", "text file with one image path per line");
  cli.addString("--laser", o.laser, "FILE", "previous calibration (YAML or text): the initial guess");
  cli.addDouble("--opening-angle-deg", o.openingDeg, "A", "full opening angle, degrees (default: the --laser file's)",
                vpCommandLine::POSITIVE);
  cli.addDouble("--apex-distance", o.apexDistance, "M", "scale: measured distance camera centre - laser apex, metres",
                vpCommandLine::POSITIVE);
  cli.addFlag("--previous-baseline", o.previousBaseline, "scale: the apex distance of the --laser file");
  cli.addFlag("--hold-apex", o.holdApex, "scale: the apex of the --laser file, held (only the axis estimated)");
  cli.addString("--known-altitude", o.knownAltitude, "FRAME:H[,FRAME:H...]",
                "scale: altitude H (metres) of frame FRAME; several frames at different heights are the second length");
  cli.addFlag("--estimate-opening-angle", o.estimateOpening,
              "estimate the opening angle (needs two lengths: two known altitudes, or an apex constraint and one)");
  cli.addUnsigned("--max-frames", o.maxFrames, "N", "frames kept by information (default 40)", 3);
  cli.addDouble("--max-std-deg", o.maxStdDeg, "D",
                "refuse when the axis standard deviation exceeds D degrees (apex direction 2 D; default 0.1)",
                vpCommandLine::POSITIVE);
  cli.addString("--output", o.output, "FILE", "laser calibration written in YAML, only on success");
  cli.addString("--report", o.report, "FILE", "the report, also written to this file");
  cli.require({"--camera", "--laser", "--output"});
  return cli;
}

//! Frames of a CSV frame,u,v (header line first). \return false with \e error naming the line.
bool readPoints(const std::string &file, std::map<unsigned int, std::vector<vpImagePoint> > &frames, std::string &error)
{
  std::ifstream in(file.c_str());
  if (!in) {
    error = file + ": cannot open the points file";
    return false;
  }
  std::string line;
  unsigned int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 || vpCsvTools::trim(line).empty())
      continue;
    const std::vector<std::string> fields = vpCsvTools::split(line);
    double f = 0.0, u = 0.0, v = 0.0;
    if (fields.size() != 3 || !vpCsvTools::toDouble(fields[0], f) || !vpCsvTools::toDouble(fields[1], u) ||
        !vpCsvTools::toDouble(fields[2], v) || f < 0.0 || f != std::floor(f) || f > 1e9) {
      error = file + ":" + std::to_string(number) + ": expected frame,u,v (a whole frame number, finite pixels)";
      return false;
    }
    frames[static_cast<unsigned int>(f)].push_back(vpImagePoint(v, u));
  }
  if (frames.empty()) {
    error = file + ": no data row";
    return false;
  }
  return true;
}

/*!
  Frames detected in images (one frame per image, numbered in order). An image of another size than the camera
  file's \e width x \e height (when it gives one) is an error: the intrinsics are not its.
*/
bool detectPoints(const Options &o, unsigned int width, unsigned int height,
                  std::map<unsigned int, std::vector<vpImagePoint> > &frames, std::ostream &report, std::string &error)
{
  std::vector<std::string> images;
  if (!vpLaserRigIo::listImages(o.imagesDir.empty() ? o.listFile : o.imagesDir, o.imagesDir.empty(), images, error))
    return false;
  vpLaserConicDetector detector;
  for (size_t k = 0; k < images.size(); ++k) {
    vpImage<vpRGBa> I;
    std::string why;
    if (!vpImageFileCheck::read(images[k], I, why)) { // a truncated JPEG too, which vpImageIo::read() took
      report << "frame " << k << " (" << images[k] << "): unreadable image (" << why << "), left out\n";
      continue;
    }
    if (width > 0 && (I.getWidth() != width || I.getHeight() != height)) {
      error = images[k] + ": " + std::to_string(I.getWidth()) + "x" + std::to_string(I.getHeight()) +
              " image, the camera file's are " + std::to_string(width) + "x" + std::to_string(height);
      return false;
    }
    frames[static_cast<unsigned int>(k)] = detector.detect(I);
  }
  return true;
}

void writeReport(std::ostream &os, const vpLaserConicSelfCalibration &selfcal, const vpHomogeneousMatrix &cMl, double A)
{
  const vpColVector s = selfcal.getStdDeviations();
  os << std::setprecision(6);
  const std::vector<bool> used = selfcal.getFrameUsed();
  os << "frames used " << std::count(used.begin(), used.end(), true) << "/" << selfcal.getNbFrames() << ", points "
     << selfcal.getNbPoints() << ", inliers " << selfcal.getNbInliers() << ", RMS " << selfcal.getRmsPixels()
     << " px\n";
  double weak = 0.0, strong = 0.0;
  selfcal.getAttitudeSpread(weak, strong);
  os << "attitude spread " << vpMath::deg(weak) << " / " << vpMath::deg(strong) << " deg (weakest / strongest)\n";
  os << "apex (mm): " << 1000.0 * cMl[0][3] << " +- " << 1000.0 * s[2] << ", " << 1000.0 * cMl[1][3] << " +- "
     << 1000.0 * s[3] << ", " << 1000.0 * cMl[2][3] << " +- " << 1000.0 * s[4] << "\n";
  os << "axis (camera frame): " << cMl[0][2] << ", " << cMl[1][2] << ", " << cMl[2][2] << " +- "
     << vpMath::deg(selfcal.getAxisStdDeviation()) << " deg; apex direction +- "
     << vpMath::deg(selfcal.getApexDirectionStdDeviation()) << " deg\n";
  os << "opening angle: " << vpMath::deg(A) << " deg" << (s[5] > 0.0 ? " (estimated)" : " (held)") << "\n";
}
} // namespace

bool requested(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--from-sequence") == 0)
      return true;
  return false;
}

//! Parses FRAME:H[,FRAME:H...] (frame numbers, positive altitudes); false on anything else.
bool parseKnownAltitudes(const std::string &text, std::map<unsigned int, double> &known)
{
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const std::string::size_type colon = item.find(':');
    double f = -1.0, h = 0.0;
    // A frame number beyond an unsigned int's range wrapped (2^32 became frame 0).
    if (colon == std::string::npos || !vpCsvTools::toDouble(item.substr(0, colon), f) || f < 0.0 ||
        f > std::numeric_limits<unsigned int>::max() || f != std::floor(f) ||
        !vpCsvTools::toDouble(item.substr(colon + 1), h) || !(h > 0.0))
      return false;
    known[static_cast<unsigned int>(f)] = h;
  }
  return !known.empty();
}

int run(int argc, char **argv)
{
  Options o;
  vpCommandLine cli = commandLine(o);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if ((cli.given("--points") ? 1 : 0) + (cli.given("--images") ? 1 : 0) + (cli.given("--list") ? 1 : 0) != 1)
    return cli.fail("give exactly one of --points FILE, --images DIR and --list FILE");
  const int apexScales = (cli.given("--apex-distance") ? 1 : 0) + (o.previousBaseline ? 1 : 0) + (o.holdApex ? 1 : 0);
  if (apexScales == 0 && !cli.given("--known-altitude"))
    return cli.fail("no scale constraint: images do not determine the apex distance; give --apex-distance M, "
                    "--previous-baseline, --hold-apex or --known-altitude FRAME:H");
  if (apexScales > 1)
    return cli.fail("give one apex constraint only (--apex-distance, --previous-baseline or --hold-apex)");
  std::map<unsigned int, double> known;
  if (cli.given("--known-altitude") && !parseKnownAltitudes(o.knownAltitude, known))
    return cli.fail("--known-altitude expects FRAME:H[,FRAME:H...] (frame numbers, positive altitudes in metres), "
                    "got '" +
                    o.knownAltitude + "'");

  std::string error;
  vpCameraParameters cam;
  unsigned int width = 0, height = 0;
  vpLaserCalibrationData previous;
  std::vector<std::string> inputs = {o.camera, o.laser};
  if (!o.points.empty())
    inputs.push_back(o.points);
  if (!o.listFile.empty())
    inputs.push_back(o.listFile);
  // Every output is checked before the work (the report's folder was found missing after the calibration had
  // run and its YAML been written), and against every input and the other output.
  if (!vpOutputFile::checkWritable(o.output, error) ||
      (!o.report.empty() && !vpOutputFile::checkWritable(o.report, error)) ||
      !vpLaserRigIo::readCamera(o.camera, o.cameraName, cam, width, height, error) ||
      !vpLaserRigIo::readLaserCalibration(o.laser, previous, error) ||
      !vpCsvTools::checkOutputs({o.output, o.report}, inputs, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::ostringstream report;
  std::map<unsigned int, std::vector<vpImagePoint> > frames;
  if (!(o.points.empty() ? detectPoints(o, width, height, frames, report, error)
                         : readPoints(o.points, frames, error))) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }

  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(cam);
  selfcal.setLaser(cli.given("--opening-angle-deg") ? vpMath::rad(o.openingDeg) : previous.openingAngle, previous.cMl);
  selfcal.setOpeningAngleEstimation(o.estimateOpening);
  selfcal.setMaxFrames(o.maxFrames);
  selfcal.setMaxAngularStdDeviation(vpMath::rad(o.maxStdDeg));
  if (o.apexDistance > 0.0)
    selfcal.setApexDistance(o.apexDistance);
  selfcal.setApexHeld(o.holdApex);
  if (o.previousBaseline)
    selfcal.setApexDistance(previous.cMl.getTranslationVector().frobeniusNorm());
  size_t knownAdded = 0;
  for (const std::pair<const unsigned int, std::vector<vpImagePoint> > &f : frames) {
    if (f.second.size() < 5) {
      report << "frame " << f.first << ": " << f.second.size() << " laser points, left out\n";
      continue;
    }
    const unsigned int index = selfcal.addFrame(f.second);
    const std::map<unsigned int, double>::const_iterator k = known.find(f.first);
    if (k != known.end()) {
      selfcal.setKnownAltitude(index, k->second);
      ++knownAdded;
    }
  }
  if (knownAdded < known.size())
    return cli.fail("--known-altitude: a frame given has no usable laser trace");
  vpHomogeneousMatrix cMl;
  double A = 0.0;
  bool ok = false;
  if (selfcal.getNbFrames() < 3)
    report << "self-calibration failed: fewer than 3 frames with a laser trace\n";
  else if (!(ok = selfcal.compute(cMl, A)))
    report << "self-calibration failed: " << vpLaserConicSelfCalibration::getStatusMessage(selfcal.getStatus()) << " ("
           << selfcal.getStatusDetails() << ")\n";
  if (ok) {
    writeReport(report, selfcal, cMl, A);
    vpLaserCalibrationData data;
    data.openingAngle = A;
    data.cMl = cMl;
    data.hasStdDeviations = true;
    data.stdDeviations = selfcal.getStdDeviations();
    const std::vector<bool> used = selfcal.getFrameUsed();
    data.nbViews = static_cast<unsigned int>(std::count(used.begin(), used.end(), true));
    if (!vpLaserRigIo::writeLaserCalibrationYaml(o.output, data, error)) {
      std::cerr << argv[0] << ": " << error << std::endl;
      return EXIT_FAILURE;
    }
    report << "written to " << o.output << "\n";
  }
  std::cout << report.str();
  if (!o.report.empty()) { // written completely or not at all; a full disk is an error (it ended with 0)
    if (!vpOutputFile::writeText(o.report, report.str(), error)) {
      std::cerr << argv[0] << ": " << error << std::endl;
      return EXIT_FAILURE;
    }
  }
  if (!ok)
    std::cerr << argv[0] << ": self-calibration failed; " << o.output << " left as it was" << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace vspLaserSequenceCalibration
