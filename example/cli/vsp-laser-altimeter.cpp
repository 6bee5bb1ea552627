/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-laser-altimeter.cpp
  Command-line altimeter for a camera rigidly attached to a circular laser: for each image, the red
  trace is detected (vpLaserConicDetector) and the ground plane estimated (vpLaserConicPose), giving
  altitude, roll and pitch.

  \verbatim
  vsp-laser-altimeter --camera camera.xml [--camera-name Camera] --laser laser.txt
                      (--images DIR | --list images.txt) --output results.csv
                      [--method GP3|PP3|PP5|PLANE_PAIR] [--overlays DIR] [--threshold PX] [--seed N]
  \endverbatim
  Output: CSV "frame,image,altitude_m,roll_rad,pitch_rad,inliers,status". Exit status 0 when every
  image was processed (frames without a plane say why in their status), 1 on a usage, file or
  format error.
*/
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpLaserOverlay.h"
#include "vpLaserRigIo.h"

namespace fs = std::filesystem;

namespace
{
struct Options
{
  std::string camera, cameraName = "Camera", laser, imagesDir, listFile, output, overlays;
  std::string methodName = "GP3";
  double threshold = 2.0;
  unsigned int seed = 0;
};

vpLaserConicPose::vpLaserConicMethod methodId(const std::string &name)
{
  if (name == "PP3")
    return vpLaserConicPose::PP3;
  if (name == "PP5")
    return vpLaserConicPose::PP5;
  return name == "PLANE_PAIR" ? vpLaserConicPose::PLANE_PAIR : vpLaserConicPose::GP3;
}

//! Declares the options of the program; \e options receives their values.
vpCommandLine commandLine(Options &options)
{
  vpCommandLine cli("--camera camera.xml [--camera-name Camera] --laser laser.txt\n"
                    "          (--images DIR | --list images.txt) --output results.csv\n"
                    "          [--method GP3|PP3|PP5|PLANE_PAIR] [--overlays DIR] [--threshold PX] [--seed N]",
                    "Altitude, roll and pitch of a camera with a circular laser, from the laser trace in each image.");
  cli.addString("--camera", options.camera, "FILE",
                "intrinsics in vpXmlParserCamera format (perspective model without distortion)");
  cli.addString("--camera-name", options.cameraName, "NAME", "camera name in that file (default Camera)");
  cli.addString("--laser", options.laser, "FILE", "laser calibration: 'opening_angle_deg A' then 'cMl' and its 4 rows");
  cli.addString("--images", options.imagesDir, "DIR", "folder of images (.png .jpg .jpeg .ppm .pgm), processed in name order");
  cli.addString("--list", options.listFile, "FILE", "text file with one image path per line (relative to the list's folder)");
  cli.addString("--output", options.output, "FILE",
                "CSV 'frame,image,altitude_m,roll_rad,pitch_rad,inliers,status'; never an input");
  cli.addChoice("--method", options.methodName, {"GP3", "PP3", "PP5", "PLANE_PAIR"}, "METHOD", "estimator (default GP3)");
  cli.addString("--overlays", options.overlays, "DIR", "folder receiving <image>_overlay.png (points, inliers, fitted conic)");
  cli.addDouble("--threshold", options.threshold, "PX", "RANSAC inlier threshold in pixels (default 2)",
                vpCommandLine::POSITIVE);
  cli.addUnsigned("--seed", options.seed, "N", "RANSAC seed (default 0)");
  cli.require({"--camera", "--laser", "--output"});
  return cli;
}

bool hasImageExtension(const fs::path &p)
{
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pgm";
}

//! Images of a folder with an image extension, sorted by name.
bool listFolder(const std::string &folder, std::vector<std::string> &images, std::string &error)
{
  if (!fs::is_directory(folder)) {
    error = folder + ": image folder not found";
    return false;
  }
  for (const fs::directory_entry &entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && hasImageExtension(entry.path()))
      images.push_back(entry.path().string());
  std::sort(images.begin(), images.end());
  if (images.empty()) {
    error = folder + ": no image (.png .jpg .jpeg .ppm .pgm) in this folder";
    return false;
  }
  return true;
}

//! Images named by a list file: one per line, '#' comments, relative to the list's folder.
bool readList(const std::string &listFile, std::vector<std::string> &images, std::string &error)
{
  std::ifstream in(listFile);
  if (!in) {
    error = listFile + ": cannot open the image list";
    return false;
  }
  const fs::path base = fs::path(listFile).parent_path();
  std::string line;
  unsigned int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string entry = vpCsvTools::trim(line);
    if (entry.empty() || entry[0] == '#')
      continue;
    const fs::path p = fs::path(entry).is_absolute() ? fs::path(entry) : base / entry;
    if (!fs::is_regular_file(p)) {
      error = vpCsvTools::location(listFile, lineNumber) + ": image '" + p.string() + "' not found";
      return false;
    }
    images.push_back(p.string());
  }
  if (images.empty()) {
    error = listFile + ": the list names no image";
    return false;
  }
  return true;
}

//! Image paths from --images or --list.
bool listImages(const Options &options, std::vector<std::string> &images, std::string &error)
{
  if (!(options.imagesDir.empty() ? readList(options.listFile, images, error)
                                  : listFolder(options.imagesDir, images, error)))
    return false;
  for (const std::string &image : images)
    if (image.find(',') != std::string::npos) {
      // Paths are written unquoted in the results CSV, where a comma would shift the columns.
      error = "image path '" + image + "' contains a comma, which the CSV output cannot hold: rename it";
      return false;
    }
  return true;
}

//! Refuses a results CSV that would overwrite one of the files named on the command line.
bool checkOutputIsNotNamedInput(const Options &options, std::string &error)
{
  std::vector<std::string> inputs = {options.camera, options.laser};
  if (!options.listFile.empty())
    inputs.push_back(options.listFile);
  return vpCsvTools::checkOutputIsNotInput(options.output, inputs, error);
}

//! Refuses outputs that would overwrite an image (results CSV, or overlays in the image folder).
bool checkOutputsAgainstImages(const Options &options, const std::vector<std::string> &images, std::string &error)
{
  if (!vpCsvTools::checkOutputIsNotInput(options.output, images, error))
    return false;
  if (!options.overlays.empty()) {
    for (const std::string &image : images)
      if (vpCsvTools::samePath(options.overlays, fs::path(image).parent_path().string())) {
        error = "--overlays '" + options.overlays + "' is a folder of input images: choose another folder";
        return false;
      }
  }
  return true;
}

//! Minimum number of points of a method.
unsigned int minimumPoints(vpLaserConicPose::vpLaserConicMethod method)
{
  return (method == vpLaserConicPose::PP3 || method == vpLaserConicPose::GP3) ? 3u : 5u;
}

struct FrameResult
{
  double altitude = 0.0, roll = 0.0, pitch = 0.0;
  unsigned int inliers = 0;
  std::string status = "ok";
};

FrameResult processImage(const std::string &image, const Options &options, vpLaserConicPose &estimator,
                         vpLaserConicDetector &detector)
{
  FrameResult result;
  vpImage<vpRGBa> I;
  std::string why = "empty image";
  try {
    vpImageIo::read(I, image);
  } catch (const vpException &e) {
    why = e.getStringMessage();
  }
  if (I.getSize() == 0) { // a file that is not an image may also read as an empty image
    std::cerr << image << ": cannot be read as an image (" << why << ")" << std::endl;
    result.status = "unreadable_image";
    return result;
  }
  const std::vector<vpImagePoint> points = detector.detect(I);
  vpMatrix conic;
  std::vector<unsigned int> inliers;
  if (points.size() < minimumPoints(methodId(options.methodName))) {
    result.status = "not_enough_points";
  } else {
    vpPlane plane;
    try {
      if (estimator.computePlane(points, methodId(options.methodName), plane)) {
        result.altitude = estimator.getAltitude();
        result.roll = estimator.getRoll();
        result.pitch = estimator.getPitch();
        inliers = estimator.getInliers();
        result.inliers = static_cast<unsigned int>(inliers.size());
        conic = estimator.getImageConic();
      } else {
        result.status = "no_plane";
        std::cerr << image << ": no plane (" << estimator.getFailureReason() << ")" << std::endl;
      }
    } catch (const vpException &e) {
      result.status = "error";
      std::cerr << image << ": " << e.getStringMessage() << std::endl;
    }
  }
  if (!options.overlays.empty()) {
    char caption[256];
    if (result.status == "ok")
      std::snprintf(caption, sizeof(caption), "%s %s: altitude %.3f m, roll %.2f deg, pitch %.2f deg, %u/%zu inliers",
                    fs::path(image).filename().string().c_str(), options.methodName.c_str(), result.altitude,
                    vpMath::deg(result.roll), vpMath::deg(result.pitch), result.inliers, points.size());
    else
      std::snprintf(caption, sizeof(caption), "%s %s: %s (%zu points)", fs::path(image).filename().string().c_str(),
                    options.methodName.c_str(), result.status.c_str(), points.size());
    vpLaserOverlay::draw(I, points, inliers, conic, caption);
    vpImageIo::write(I, (fs::path(options.overlays) / (fs::path(image).stem().string() + "_overlay.png")).string());
  }
  return result;
}
/*!
  Reads the camera, the laser calibration and the image list, and checks that no output names an
  input. \return false with \e error naming the file at fault.
*/
bool readInputs(const Options &options, vpCameraParameters &cam, double &openingAngle, vpHomogeneousMatrix &cMl,
                std::vector<std::string> &images, std::string &error)
{
  unsigned int width = 0, height = 0; // not needed: images of any size are accepted
  // The output is checked against the named files first, so that a wrong command line is refused
  // before the image list is read; then against the images.
  return vpLaserRigIo::readCamera(options.camera, options.cameraName, cam, width, height, error) &&
         vpLaserRigIo::readLaserCalibration(options.laser, openingAngle, cMl, error) &&
         checkOutputIsNotNamedInput(options, error) && listImages(options, images, error) &&
         checkOutputsAgainstImages(options, images, error);
}

//! One row of the results CSV; the numbers are "nan" when the frame has no plane.
void writeRow(std::ostream &out, size_t frame, const std::string &image, const FrameResult &r)
{
  out << frame << "," << image << ",";
  if (r.status == "ok")
    out << vpCsvTools::formatDouble(r.altitude) << "," << vpCsvTools::formatDouble(r.roll) << ","
        << vpCsvTools::formatDouble(r.pitch);
  else
    out << "nan,nan,nan";
  out << "," << r.inliers << "," << r.status << "\n";
}

//! The program; main() only adds a last-resort error report.
int run(int argc, char **argv)
{
  Options options;
  vpCommandLine cli = commandLine(options);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (cli.given("--images") == cli.given("--list"))
    return cli.fail("give exactly one of --images DIR and --list FILE");
  std::string error;
  vpCameraParameters cam;
  double openingAngle = 0.0;
  vpHomogeneousMatrix cMl;
  std::vector<std::string> images;
  if (!readInputs(options, cam, openingAngle, cMl, images, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  if (!options.overlays.empty()) {
    std::error_code ec;
    fs::create_directories(options.overlays, ec);
    if (!fs::is_directory(options.overlays)) {
      std::cerr << argv[0] << ": cannot create the overlay folder '" << options.overlays << "'" << std::endl;
      return EXIT_FAILURE;
    }
  }
  std::ofstream out(options.output);
  if (!out) {
    std::cerr << argv[0] << ": " << options.output << ": cannot be written" << std::endl;
    return EXIT_FAILURE;
  }

  vpLaserConicPose estimator;
  vpLaserConicDetector detector;
  try {
    estimator.setCameraParameters(cam);
    estimator.setLaser(openingAngle, cMl);
    estimator.setRansacThreshold(options.threshold);
    estimator.setRansacSeed(options.seed);
  } catch (const vpException &e) {
    std::cerr << argv[0] << ": " << options.laser << ": " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
  out << "frame,image,altitude_m,roll_rad,pitch_rad,inliers,status\n";
  unsigned int found = 0;
  for (size_t k = 0; k < images.size(); ++k) {
    const FrameResult r = processImage(images[k], options, estimator, detector);
    writeRow(out, k, images[k], r);
    found += r.status == "ok" ? 1 : 0;
  }
  if (!out) {
    std::cerr << argv[0] << ": " << options.output << ": write error" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << options.methodName << ": " << found << "/" << images.size() << " images with a plane, written to "
            << options.output << (options.overlays.empty() ? "" : ", overlays in " + options.overlays) << std::endl;
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
