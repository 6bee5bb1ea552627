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
#include "vpLaserRigIo.h"

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
      "          [--opening-angle-deg A] (--apex-distance M | --previous-baseline | --hold-apex |\n"
      "          --known-altitude FRAME:H)"
      "          [--estimate-opening-angle] [--max-frames N] [--max-std-deg D] --output laser.yaml [--report FILE]",
      "Laser/camera self-calibration from ordinary frames of the ground at different attitudes (no chessboard).\n"
      "Images determine the cone but for its scale: give one length (apex distance, the previous\n"
      "calibration's baseline, or one frame's altitude). A length off by x % gives altitudes off by x %.");
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
  cli.addString("--known-altitude", o.knownAltitude, "FRAME:H", "scale: altitude H (metres) of frame FRAME");
  cli.addFlag("--estimate-opening-angle", o.estimateOpening,
              "estimate the opening angle (needs known altitudes of several tilted frames)");
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

//! Frames detected in images (one frame per image, numbered in order).
bool detectPoints(const Options &o, std::map<unsigned int, std::vector<vpImagePoint> > &frames, std::ostream &report,
                  std::string &error)
{
  std::vector<std::string> images;
  if (!vpLaserRigIo::listImages(o.imagesDir.empty() ? o.listFile : o.imagesDir, o.imagesDir.empty(), images, error))
    return false;
  vpLaserConicDetector detector;
  for (size_t k = 0; k < images.size(); ++k) {
    vpImage<vpRGBa> I;
    try {
      vpImageIo::read(I, images[k]);
    } catch (const vpException &e) {
      report << "frame " << k << " (" << images[k] << "): unreadable image, left out\n";
      continue;
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

int run(int argc, char **argv)
{
  Options o;
  vpCommandLine cli = commandLine(o);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if ((cli.given("--points") ? 1 : 0) + (cli.given("--images") ? 1 : 0) + (cli.given("--list") ? 1 : 0) != 1)
    return cli.fail("give exactly one of --points FILE, --images DIR and --list FILE");
  const int scales = (cli.given("--apex-distance") ? 1 : 0) + (o.previousBaseline ? 1 : 0) + (o.holdApex ? 1 : 0) +
                     (cli.given("--known-altitude") ? 1 : 0);
  if (scales == 0)
    return cli.fail("no scale constraint: images do not determine the apex distance; give --apex-distance M, "
                    "--previous-baseline, --hold-apex or --known-altitude FRAME:H");
  if (scales > 1)
    return cli.fail("give one scale constraint only (--apex-distance, --previous-baseline, --hold-apex or "
                    "--known-altitude)");
  unsigned int knownFrame = 0;
  double knownAltitude = 0.0;
  if (cli.given("--known-altitude")) {
    const std::string::size_type colon = o.knownAltitude.find(':');
    double f = -1.0;
    if (colon == std::string::npos || !vpCsvTools::toDouble(o.knownAltitude.substr(0, colon), f) || f < 0.0 ||
        f != std::floor(f) || !vpCsvTools::toDouble(o.knownAltitude.substr(colon + 1), knownAltitude) ||
        !(knownAltitude > 0.0))
      return cli.fail("--known-altitude expects FRAME:H (a frame number, a positive altitude in metres), got '" +
                      o.knownAltitude + "'");
    knownFrame = static_cast<unsigned int>(f);
  }

  std::string error;
  vpCameraParameters cam;
  unsigned int width = 0, height = 0;
  vpLaserCalibrationData previous;
  std::vector<std::string> inputs = {o.camera, o.laser};
  if (!o.points.empty())
    inputs.push_back(o.points);
  if (!o.listFile.empty())
    inputs.push_back(o.listFile);
  if (!vpLaserRigIo::readCamera(o.camera, o.cameraName, cam, width, height, error) ||
      !vpLaserRigIo::readLaserCalibration(o.laser, previous, error) ||
      !vpCsvTools::checkOutputIsNotInput(o.output, inputs, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::ostringstream report;
  std::map<unsigned int, std::vector<vpImagePoint> > frames;
  if (!(o.points.empty() ? detectPoints(o, frames, report, error) : readPoints(o.points, frames, error))) {
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
  bool knownAdded = false;
  for (const std::pair<const unsigned int, std::vector<vpImagePoint> > &f : frames) {
    if (f.second.size() < 5) {
      report << "frame " << f.first << ": " << f.second.size() << " laser points, left out\n";
      continue;
    }
    const unsigned int index = selfcal.addFrame(f.second);
    if (cli.given("--known-altitude") && f.first == knownFrame) {
      selfcal.setKnownAltitude(index, knownAltitude);
      knownAdded = true;
    }
  }
  if (cli.given("--known-altitude") && !knownAdded)
    return cli.fail("--known-altitude: frame " + std::to_string(knownFrame) + " has no usable laser trace");
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
  if (!o.report.empty()) {
    std::ofstream out(o.report.c_str());
    if (!(out << report.str())) {
      std::cerr << argv[0] << ": " << o.report << ": cannot be written" << std::endl;
      return EXIT_FAILURE;
    }
  }
  if (!ok)
    std::cerr << argv[0] << ": self-calibration failed; " << o.output << " left as it was" << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace vspLaserSequenceCalibration
