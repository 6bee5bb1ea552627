/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example make-laser-calibration-images.cpp
  Renders a laser calibration session with vpLaserConicSimulator: a printed chessboard (12 x 9 squares
  of 5 cm on white paper) seen at three distances (0.6, 0.8, 1.0 m) and four tilts of 18 degrees, with the
  laser trace over it, by a 1280x960 camera with barrel distortion. With --laser-light reflectance the laser
  light is scaled by the paper's reflectance as a camera sees it (a near-white saturated core on the white
  squares, a dark red stripe on the black ones); with additive (the default) it is added whatever the surface
  (saturating to white on the white squares and bright red on the black ones). Writes camera.xml (ViSP
  model with distortion), laser_true.yaml (the rendering's laser: pose and opening angle) and
  images/view_XX.png into the output folder: the input of vsp-laser-calibrate.

  With --check FILE, compares the laser calibration FILE with laser_true.yaml of --output instead and
  exits with 1 when the apex, axis or opening angle error exceeds its bound (the end-to-end test).

  \verbatim
  vsp-make-laser-calibration-images --output DIR [--seed N] [--laser-light additive|reflectance]
  vsp-make-laser-calibration-images --output DIR --check laser.yaml [--max-apex-mm 1] [--max-axis-deg 0.1]
                                    [--max-angle-deg 0.05]
  \endverbatim
*/
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "vpCommandLine.h"
#include "vpLaserRigIo.h"
#include "vpOutputFile.h"

namespace
{
struct Options
{
  std::string output, check;
  unsigned int seed = 3;
  std::string laserLight = "additive";
  double maxApexMm = 1.0, maxAxisDeg = 0.1, maxAngleDeg = 0.05;
};

const unsigned int kWidth = 1280, kHeight = 960;
const unsigned int kSquaresX = 12, kSquaresY = 9;
const double kSquare = 0.05;

//! 1000 px focal length, barrel distortion of about 14 px in the corners (k_du of vpPixelMeterConversion).
vpCameraParameters camera()
{
  const vpCameraParameters cam(1000.0, 1000.0, 643.0, 478.0, 0.0, 0.04);
  return vpLaserConicSimulator::fitInverseDistortion(cam, kWidth, kHeight);
}

//! The laser: 34 degrees, 10 cm beside the camera, axis tilted by 3 and -5 degrees.
vpHomogeneousMatrix trueLaserPose()
{
  return vpHomogeneousMatrix(0.10, 0.02, -0.01, vpMath::rad(3.0), vpMath::rad(-5.0), 0.0);
}
const double kOpening = vpMath::rad(34.0);

/*!
  Board poses: the board centre on the laser axis (with an offset so that the trace crosses the board
  off-centre), at three distances, tilted by 18 degrees in four directions and spun in its plane.
*/
std::vector<vpHomogeneousMatrix> boardPoses()
{
  std::vector<vpHomogeneousMatrix> poses;
  const double depths[3] = {0.6, 0.8, 1.0};
  const double tilt = 18.0;
  const double tilts[4][2] = {{tilt, 0.0}, {0.0, tilt}, {-tilt, 0.0}, {0.0, -tilt}};
  const vpHomogeneousMatrix centreInGrid(0.5 * kSquaresX * kSquare, 0.5 * kSquaresY * kSquare, 0, 0, 0, 0);
  const vpHomogeneousMatrix cMl = trueLaserPose();
  for (unsigned int d = 0; d < 3; ++d)
    for (unsigned int t = 0; t < 4; ++t) {
      const double along = depths[d] / cMl[2][2];
      const double cx = cMl[0][3] + along * cMl[0][2] + 0.04 * std::cos(1.3 * (4 * d + t));
      const double cy = cMl[1][3] + along * cMl[1][2] + 0.03 * std::sin(1.3 * (4 * d + t));
      const vpHomogeneousMatrix cMcentre(cx, cy, depths[d], vpMath::rad(tilts[t][0]), vpMath::rad(tilts[t][1]),
                                         vpMath::rad(-15.0 + 10.0 * t));
      poses.push_back(cMcentre * centreInGrid.inverse());
    }
  return poses;
}

double axisAngleDeg(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  const double dot = a[0][2] * b[0][2] + a[1][2] * b[1][2] + a[2][2] * b[2][2];
  return vpMath::deg(std::acos(std::max(-1.0, std::min(1.0, dot))));
}

int check(const Options &options)
{
  vpLaserCalibrationData truth, estimate;
  std::string error;
  if (!vpLaserRigIo::readLaserCalibration(options.output + "/laser_true.yaml", truth, error) ||
      !vpLaserRigIo::readLaserCalibration(options.check, estimate, error)) {
    std::cerr << error << std::endl;
    return EXIT_FAILURE;
  }
  const double apexMm =
      1000.0 * (truth.cMl.getTranslationVector() - estimate.cMl.getTranslationVector()).frobeniusNorm();
  const double axisDeg = axisAngleDeg(truth.cMl, estimate.cMl);
  const double angleDeg = vpMath::deg(std::fabs(truth.openingAngle - estimate.openingAngle));
  std::cout << "apex error " << apexMm << " mm (max " << options.maxApexMm << "), axis error " << axisDeg
            << " deg (max " << options.maxAxisDeg << "), opening angle error " << angleDeg << " deg (max "
            << options.maxAngleDeg << ")" << std::endl;
  const bool ok = apexMm <= options.maxApexMm && axisDeg <= options.maxAxisDeg && angleDeg <= options.maxAngleDeg;
  std::cout << (ok ? "within the bounds" : "OUT OF THE BOUNDS") << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

int render(const Options &options)
{
  std::string error;
  try {
    vpIoTools::makeDirectory(options.output + "/images");
  } catch (const vpException &e) {
    std::cerr << options.output << "/images: cannot be created (" << e.getStringMessage() << ")" << std::endl;
    return EXIT_FAILURE;
  }
  const vpCameraParameters cam = camera();
  vpLaserCalibrationData truth;
  truth.openingAngle = kOpening;
  truth.cMl = trueLaserPose();
  if (!vpLaserRigIo::writeCamera(options.output + "/camera.xml", cam, kWidth, kHeight, error) ||
      !vpLaserRigIo::writeLaserCalibrationYaml(options.output + "/laser_true.yaml", truth, error)) {
    std::cerr << error << std::endl;
    return EXIT_FAILURE;
  }
  vpLaserConicSimulator sim;
  sim.setCamera(cam, kWidth, kHeight);
  sim.setLaser(kOpening, trueLaserPose());
  sim.setGroundChessboard(kSquaresX, kSquaresY, kSquare);
  sim.setSeed(options.seed);
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.floor = vpLaserConicSimulator::FLOOR_DARK_TILES; // the table around the paper
  settings.whiteCore = 0.6;                                 // the stripe saturates to white on the white squares
  settings.reflectanceScaled = options.laserLight == "reflectance";
  // The same light on the white squares (albedo 215) in both modes.
  settings.laserPower = settings.reflectanceScaled ? 400.0 * 255.0 / 215.0 : 400.0;
  settings.noise = 2.0;
  const std::vector<vpHomogeneousMatrix> poses = boardPoses();
  for (size_t k = 0; k < poses.size(); ++k) {
    sim.setGroundPose(poses[k]);
    vpImage<vpRGBa> I;
    sim.render(I, settings);
    char name[64];
    std::snprintf(name, sizeof(name), "/images/view_%02u.png", static_cast<unsigned int>(k));
    // Checked: on a full disk libpng reports its error on the console only, and "written" followed.
    if (!vpOutputFile::writeImage(options.output + name, I, error)) {
      std::cerr << error << std::endl;
      return EXIT_FAILURE;
    }
  }
  std::cout << poses.size() << " views written to " << options.output << "/images" << std::endl;
  return EXIT_SUCCESS;
}

int run(int argc, char **argv)
{
  Options options;
  vpCommandLine cli("--output DIR [--seed N] [--laser-light additive|reflectance]\n"
                    "       | --output DIR --check laser.yaml [--max-apex-mm MM] [--max-axis-deg DEG] [--max-angle-deg "
                    "DEG]",
                    "Renders chessboard views of a camera/laser rig for vsp-laser-calibrate, or checks a calibration "
                    "against the rendering's laser.");
  cli.addString("--output", options.output, "DIR", "folder of camera.xml, laser_true.yaml and images/");
  cli.addUnsigned("--seed", options.seed, "N", "sensor noise seed (default 3)");
  cli.addChoice("--laser-light", options.laserLight, {"additive", "reflectance"}, "MODE",
                "'additive': the laser light added whatever the surface (default), 'reflectance': scaled by it");
  cli.addString("--check", options.check, "FILE", "laser calibration to compare with DIR/laser_true.yaml");
  cli.addDouble("--max-apex-mm", options.maxApexMm, "MM", "largest apex error (default 1)", vpCommandLine::POSITIVE);
  cli.addDouble("--max-axis-deg", options.maxAxisDeg, "DEG", "largest axis error (default 0.1)",
                vpCommandLine::POSITIVE);
  cli.addDouble("--max-angle-deg", options.maxAngleDeg, "DEG", "largest opening angle error (default 0.05)",
                vpCommandLine::POSITIVE);
  cli.require({"--output"});
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  return options.check.empty() ? render(options) : check(options);
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
