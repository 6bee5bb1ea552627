/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-laser-calibrate.cpp
  Command-line laser/camera calibration from colour images of a printed chessboard with the laser trace
  on it (vpLaserConicGridCalibration, then vpLaserConicCalibration): for each image the chessboard
  corners give the grid pose, the trace points on the board are detected, then the laser cone (apex,
  axis and, with --estimate-opening-angle, opening angle) is fitted to all the views.

  \verbatim
  vsp-laser-calibrate --camera camera.xml [--camera-name Camera] (--images DIR | --list images.txt)
                      --board 12x9 --square 0.05 --opening-angle-deg 34 [--estimate-opening-angle]
                      [--guess-apex X,Y,Z] [--guess-axis-deg RX,RY] --output laser.yaml
                      [--report report.txt] [--figure before_after.png] [--robust-scale PX | --no-robust]
                      [--max-reprojection PX] [--corner-clearance PX]
  \endverbatim
  or, without a chessboard, from ordinary frames of the ground at different attitudes (self-calibration,
  vpLaserConicSelfCalibration; code in vpLaserSequenceCalibration.cpp):
  \verbatim
  vsp-laser-calibrate --from-sequence --camera camera.xml (--points points.csv | --images DIR | --list FILE)
                      --laser previous.yaml (--apex-distance M | --previous-baseline | --hold-apex | --known-altitude FRAME:H)
                      [--opening-angle-deg A] [--estimate-opening-angle] [--max-frames N] --output laser.yaml
  \endverbatim
  (points.csv: a header, then rows frame,u,v in pixels). Both modes write the same file; a failed
  calibration writes nothing (the previous file stays).
  Output: the laser calibration in YAML (pose as a vpPoseVector, opening angle, standard deviations: the
  leave-one-view-out jackknife, which includes the grid pose errors, or with fewer than 3 views the formal
  ones from the laser point noise),
  readable by vsp-laser-altimeter --laser and by vpPoseVector::loadYAML(); a report on stdout (and in
  --report) with each image's status, the residuals and the standard deviations. Exit status 0 when the
  calibration succeeded, 1 on a usage or file error or when the calibration failed (the report says why:
  too few usable views, degenerate views, no convergence...).
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicGridCalibration.h>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpImageFileCheck.h"
#include "vpLaserRigIo.h"
#include "vpLaserSequenceCalibration.h"
#include "vpOutputFile.h"
#include "vpPngPlot.h"
#include "vpProgress.h"

namespace
{
struct Options
{
  std::string camera, cameraName = "Camera", imagesDir, listFile, board, output, report, figure;
  std::string guessApex = "0,0,0", guessAxis = "0,0";
  double square = 0.0, openingDeg = 0.0, robustScale = 0.0, maxReprojection = 1.0, cornerClearance = 8.0;
  bool estimateOpening = false, noRobust = false;
};

vpCommandLine commandLine(Options &o)
{
  vpCommandLine cli("--camera camera.xml [--camera-name Camera] (--images DIR | --list images.txt)\n"
                    "          --board NXxNY --square S --opening-angle-deg A [--estimate-opening-angle]\n"
                    "          [--guess-apex X,Y,Z] [--guess-axis-deg RX,RY] --output laser.yaml\n"
                    "          [--report FILE] [--figure FILE.png] [--robust-scale PX | --no-robust] "
                    "[--max-reprojection PX]\n"
                    "          [--corner-clearance PX]",
                    "Laser/camera calibration from images of a chessboard with the laser trace on it (--from-sequence: "
                    "self-calibration from ordinary frames of the ground; --from-sequence --help lists its options).");
  cli.addString("--camera", o.camera, "FILE", "intrinsics in vpXmlParserCamera format (with distortion if it has it)");
  cli.addString("--camera-name", o.cameraName, "NAME", "camera name in that file (default Camera)");
  cli.addString("--images", o.imagesDir, "DIR", "folder of images (.png .jpg .jpeg .ppm .pgm), in name order");
  cli.addString("--list", o.listFile, "FILE", "text file with one image path per line (relative to the list's folder)");
  cli.addString("--board", o.board, "NXxNY", "number of squares of the chessboard, e.g. 12x9 (inner corners 11x8)");
  cli.addDouble("--square", o.square, "S", "side of a square, metres", vpCommandLine::POSITIVE);
  cli.addDouble("--opening-angle-deg", o.openingDeg, "A",
                "full opening angle of the laser, degrees (initial value with --estimate-opening-angle)",
                vpCommandLine::POSITIVE);
  cli.addFlag("--estimate-opening-angle", o.estimateOpening,
              "estimate the opening angle too (grids at several distances)");
  cli.addString("--guess-apex", o.guessApex, "X,Y,Z",
                "rough apex position in the camera frame, metres (default 0,0,0)");
  cli.addString("--guess-axis-deg", o.guessAxis, "RX,RY",
                "rough cone axis Rx(RX) Ry(RY) (0,0,1) in the camera frame, degrees (default 0,0)");
  cli.addString("--output", o.output, "FILE", "laser calibration written in YAML (never an input)");
  cli.addString("--report", o.report, "FILE", "the report, also written to this file");
  cli.addString("--figure", o.figure, "FILE",
                "PNG: the trace of the view with most points, measured and "
                "predicted before and after calibration, on the grid");
  cli.addDouble("--robust-scale", o.robustScale, "PX", "Cauchy loss scale in pixels (default: from the data)",
                vpCommandLine::POSITIVE);
  cli.addFlag("--no-robust", o.noRobust, "plain least squares (no outlier rejection)");
  cli.addDouble("--max-reprojection", o.maxReprojection, "PX",
                "views whose corner reprojection RMS exceeds this are left out (default 1)", vpCommandLine::POSITIVE);
  cli.addDouble("--corner-clearance", o.cornerClearance, "PX",
                "corners closer than this to the laser trace are left out of the grid pose (default 8)",
                vpCommandLine::NON_NEGATIVE);
  cli.require({"--camera", "--board", "--square", "--opening-angle-deg", "--output"});
  return cli;
}

//! "a,b,c" with exactly \e n finite numbers.
bool parseList(const std::string &text, unsigned int n, double *values)
{
  const std::vector<std::string> fields = vpCsvTools::split(text);
  if (fields.size() != n)
    return false;
  for (unsigned int i = 0; i < n; ++i)
    if (!vpCsvTools::toDouble(vpCsvTools::trim(fields[i]), values[i]))
      return false;
  return true;
}

//! "12x9" -> 12, 9 (both >= 3).
bool parseBoard(const std::string &text, unsigned int &nx, unsigned int &ny)
{
  const std::string::size_type x = text.find_first_of("xX");
  if (x == std::string::npos)
    return false;
  double a = 0.0, b = 0.0;
  if (!vpCsvTools::toDouble(text.substr(0, x), a) || !vpCsvTools::toDouble(text.substr(x + 1), b) || a < 3 || b < 3 ||
      a != std::floor(a) || b != std::floor(b) || a > 1000 || b > 1000)
    return false;
  nx = static_cast<unsigned int>(a);
  ny = static_cast<unsigned int>(b);
  return true;
}

//! Splits a curve into its coordinates, for vpPngPlot.
void coordinates(const std::vector<std::pair<double, double> > &curve, std::vector<double> &x, std::vector<double> &y)
{
  x.clear();
  y.clear();
  for (const std::pair<double, double> &p : curve) {
    x.push_back(p.first);
    y.push_back(p.second);
  }
}

//! Measured trace of view \e v with the traces predicted by the initial guess and by the calibration.
void writeFigure(const vpLaserConicCalibration &calib, size_t v, const std::string &title, const std::string &file)
{
  std::vector<double> x, y;
  vpPngPlot plot(title, "grid X (m)", "grid Y (m)", 760, 600);
  coordinates(calib.getMeasuredGridPoints()[v], x, y);
  plot.addPoints("measured", x, y, vpColor::darkGreen);
  coordinates(calib.getInitialPredictedGridPoints()[v], x, y);
  plot.addPoints("predicted by the initial guess", x, y, vpColor::blue);
  coordinates(calib.getPredictedGridPoints()[v], x, y);
  plot.addPoints("predicted by the calibration", x, y, vpColor::red);
  std::string error;
  if (!vpOutputFile::writeThrough(
          file,
          [&](const std::string &scratch) {
            plot.write(scratch);
            return true;
          },
          error))
    throw vpException(vpException::ioError, error);
}

//! Per view: image, points, inliers and RMS distance (mm) of the inliers to the calibrated trace on the grid;
//! \e added: the images given to addImage(), in order.
void reportViews(std::ostream &os, const vpLaserConicGridCalibration &grid, const std::vector<std::string> &added)
{
  const vpLaserConicCalibration &calib = grid.getCalibration();
  const std::vector<std::vector<std::pair<double, double> > > measured = calib.getMeasuredGridPoints(),
                                                              predicted = calib.getPredictedGridPoints();
  const std::vector<std::vector<bool> > inlier = calib.getInlierFlags();
  os << "view,image,points,inliers,rms_mm\n";
  for (size_t v = 0; v < measured.size(); ++v) {
    double sum2 = 0.0;
    unsigned int n = 0;
    for (size_t i = 0; i < measured[v].size(); ++i)
      if (inlier[v][i]) {
        sum2 += vpMath::sqr(measured[v][i].first - predicted[v][i].first) +
                vpMath::sqr(measured[v][i].second - predicted[v][i].second);
        ++n;
      }
    os << v << "," << added[grid.getViewImageIndex()[v]] << "," << measured[v].size() << "," << n << ","
       << (n ? 1000.0 * std::sqrt(sum2 / n) : 0.0) << "\n";
  }
}

//! The calibration part of the report.
void reportCalibration(std::ostream &os, const vpLaserConicCalibration &calib, const vpHomogeneousMatrix &cMl)
{
  // The jackknife over the views includes the grid pose errors, which the formal covariance ignores.
  const bool jk = calib.hasJackknifeStdDeviations();
  const vpColVector s = jk ? calib.getJackknifeStdDeviations() : calib.getStdDeviations();
  os << std::setprecision(6);
  os << "standard deviations (+-): " << (jk ? "jackknife over the views" : "laser point noise only")
     << "; laser point noise only: apex " << 1000.0 * calib.getStdDeviations()[2] << ", "
     << 1000.0 * calib.getStdDeviations()[3] << ", " << 1000.0 * calib.getStdDeviations()[4] << " mm\n";
  os << "views " << calib.getNbViews() << ", laser points " << calib.getNbPoints() << ", inliers "
     << calib.getNbInliers() << " (robust scale " << calib.getRobustScale() << " px)\n";
  os << "RMS residual: " << 1000.0 * calib.getRms() << " mm on the grids, " << calib.getRmsPixels()
     << " px (initial guess: " << 1000.0 * calib.getInitialRms() << " mm)\n";
  os << "condition number of the normal equations: " << calib.getConditionNumber() << "\n";
  os << "apex (mm): " << 1000.0 * cMl[0][3] << " +- " << 1000.0 * s[2] << ", " << 1000.0 * cMl[1][3] << " +- "
     << 1000.0 * s[3] << ", " << 1000.0 * cMl[2][3] << " +- " << 1000.0 * s[4] << "\n";
  os << "axis (camera frame): " << cMl[0][2] << ", " << cMl[1][2] << ", " << cMl[2][2] << "; alpha "
     << vpMath::deg(std::atan2(-cMl[1][2], cMl[2][2])) << " +- " << vpMath::deg(s[0]) << " deg, beta "
     << vpMath::deg(std::asin(cMl[0][2])) << " +- " << vpMath::deg(s[1]) << " deg\n";
  os << "opening angle: " << vpMath::deg(calib.getOpeningAngle()) << " deg"
     << (s[5] > 0.0 ? " +- " + std::to_string(vpMath::deg(s[5])) + " deg (estimated)" : " (given)") << "\n";
}

int run(int argc, char **argv)
{
  Options o;
  vpCommandLine cli = commandLine(o);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (cli.given("--images") == cli.given("--list"))
    return cli.fail("give exactly one of --images DIR and --list FILE");
  if (o.noRobust && cli.given("--robust-scale"))
    return cli.fail("--no-robust and --robust-scale exclude each other");
  unsigned int nx = 0, ny = 0;
  double apex[3], axis[2];
  if (!parseBoard(o.board, nx, ny))
    return cli.fail("--board expects the number of squares as NXxNY (both >= 3), got '" + o.board + "'");
  if (!parseList(o.guessApex, 3, apex))
    return cli.fail("--guess-apex expects X,Y,Z in metres, got '" + o.guessApex + "'");
  if (!parseList(o.guessAxis, 2, axis))
    return cli.fail("--guess-axis-deg expects RX,RY in degrees, got '" + o.guessAxis + "'");
  if (!(o.openingDeg < 180.0))
    return cli.fail("--opening-angle-deg must be in (0, 180)");

  std::string error;
  vpCameraParameters cam;
  unsigned int width = 0, height = 0;
  std::vector<std::string> images;
  std::vector<std::string> inputs = {o.camera};
  if (!o.listFile.empty())
    inputs.push_back(o.listFile);
  // Every output is checked before the images are read and the calibration solved.
  if (!vpOutputFile::checkWritable(o.output, error) ||
      (!o.report.empty() && !vpOutputFile::checkWritable(o.report, error)) ||
      (!o.figure.empty() && !vpOutputFile::checkWritable(o.figure, error)) ||
      !vpLaserRigIo::readCamera(o.camera, o.cameraName, cam, width, height, error) ||
      !vpLaserRigIo::listImages(o.imagesDir.empty() ? o.listFile : o.imagesDir, o.imagesDir.empty(), images, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  // No output over an input (the camera file, the list, an image: each was overwritten by --report or
  // --output) or over another output.
  inputs.insert(inputs.end(), images.begin(), images.end());
  if (!vpCsvTools::checkOutputs({o.output, o.report, o.figure}, inputs, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }

  vpLaserConicGridCalibration grid;
  grid.setCameraParameters(cam);
  grid.setChessboard(nx, ny, o.square);
  grid.setMaxReprojectionError(o.maxReprojection);
  grid.setCornerClearance(o.cornerClearance);
  vpLaserConicCalibration &calib = grid.getCalibration();
  calib.setOpeningAngle(vpMath::rad(o.openingDeg));
  calib.setOpeningAngleEstimation(o.estimateOpening);
  calib.setViewJackknife(true);
  calib.setRobustLoss(o.noRobust ? vpLaserConicCalibration::LOSS_NONE : vpLaserConicCalibration::LOSS_CAUCHY,
                      o.robustScale);

  std::ostringstream report;
  report << "image,status,corner_rms_px,laser_points\n";
  // The images given to the calibration, in order: a view's image index counts these, not the images listed
  // (an unreadable image before a view shifted every later view's name in the report and the figure).
  std::vector<std::string> added;
  vpProgress progress("vsp-laser-calibrate: images", images.size());
  for (size_t k = 0; k < images.size(); ++k) {
    progress.update(k);
    const std::string &file = images[k];
    vpImage<vpRGBa> I;
    std::string status, why;
    if (!vpImageFileCheck::read(file, I, why))
      status = "unreadable image (" + why + ")";
    if (status.empty() && (I.getWidth() != width || I.getHeight() != height) && width > 0)
      status = "image size " + std::to_string(I.getWidth()) + "x" + std::to_string(I.getHeight()) +
               " differs from the camera's " + std::to_string(width) + "x" + std::to_string(height);
    if (status.empty()) {
      const vpLaserConicGridCalibration::vpGridViewStatus s = grid.addImage(I);
      added.push_back(file);
      status = vpLaserConicGridCalibration::getViewStatusMessage(s);
      report << file << "," << status << "," << grid.getReprojectionErrors().back() << ","
             << grid.getLaserPoints().back().size() << "\n";
    } else {
      report << file << "," << status << ",,\n";
    }
  }
  progress.finish();
  report << "\n" << calib.getNbViews() << "/" << images.size() << " images usable\n";

  const vpHomogeneousMatrix guess(vpTranslationVector(apex[0], apex[1], apex[2]),
                                  vpRotationMatrix(vpMath::rad(axis[0]), 0, 0) *
                                      vpRotationMatrix(0, vpMath::rad(axis[1]), 0));
  vpHomogeneousMatrix cMl = guess;
  bool ok = false;
  std::string failure;
  if (calib.getNbViews() > 0)
    std::cerr << "vsp-laser-calibrate: solving on " << calib.getNbViews() << " views (" << calib.getNbPoints()
              << " laser points; with the jackknife over the views this takes a few seconds per view)..." << std::endl;
  if (calib.getNbViews() == 0)
    failure = "no usable view";
  else if (!(ok = calib.compute(cMl)))
    failure = vpLaserConicCalibration::getStatusMessage(calib.getStatus()) + " (" + calib.getStatusDetails() + ")";
  if (!ok) {
    report << "calibration failed: " << failure << "\n";
  } else {
    reportViews(report, grid, added);
    reportCalibration(report, calib, cMl);
    vpLaserCalibrationData data;
    data.openingAngle = calib.getOpeningAngle();
    data.cMl = cMl;
    data.hasStdDeviations = true;
    data.stdDeviations = calib.hasJackknifeStdDeviations() ? calib.getJackknifeStdDeviations()
                                                           : calib.getStdDeviations();
    data.rms = calib.getRms();
    data.nbViews = calib.getNbViews();
    if (!vpLaserRigIo::writeLaserCalibrationYaml(o.output, data, error)) {
      std::cerr << argv[0] << ": " << error << std::endl;
      return EXIT_FAILURE;
    }
    report << "written to " << o.output << "\n";
    if (!o.figure.empty()) {
      size_t best = 0;
      for (size_t v = 1; v < calib.getNbViews(); ++v)
        if (calib.getMeasuredGridPoints()[v].size() > calib.getMeasuredGridPoints()[best].size())
          best = v;
      const std::string name = added[grid.getViewImageIndex()[best]];
      try {
        writeFigure(calib, best, "Laser trace on the grid: " + name.substr(name.find_last_of('/') + 1), o.figure);
      } catch (const vpException &e) {
        std::cout << report.str();
        std::cerr << argv[0] << ": " << e.getStringMessage() << std::endl;
        return EXIT_FAILURE;
      }
      report << "figure written to " << o.figure << "\n";
    }
  }
  std::cout << report.str();
  if (!o.report.empty()) {
    if (!vpOutputFile::writeText(o.report, report.str(), error)) {
      std::cerr << argv[0] << ": " << error << std::endl;
      return EXIT_FAILURE;
    }
  }
  if (!ok)
    std::cerr << argv[0] << ": calibration failed: " << failure << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace

int main(int argc, char **argv)
{
  if (vspLaserSequenceCalibration::requested(argc, argv))
    return vpCommandLine::runGuarded(vspLaserSequenceCalibration::run, argc, argv);
  return vpCommandLine::runGuarded(run, argc, argv);
}
