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
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpXmlParserCamera.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "vpCsvTools.h"
#include "vpLaserOverlay.h"
#include "vpLaserRigIo.h"

namespace fs = std::filesystem;

namespace
{
struct Options
{
  std::string camera, cameraName = "Camera", laser, imagesDir, listFile, output, overlays;
  vpLaserConicPose::vpLaserConicMethod method = vpLaserConicPose::GP3;
  std::string methodName = "GP3";
  double threshold = 2.0;
  unsigned int seed = 0;
};

void printUsage(std::ostream &os, const char *program)
{
  os << "Usage: " << program
     << " --camera camera.xml [--camera-name Camera] --laser laser.txt\n"
        "          (--images DIR | --list images.txt) --output results.csv\n"
        "          [--method GP3|PP3|PP5|PLANE_PAIR] [--overlays DIR] [--threshold PX] [--seed N]\n"
        "  --camera       intrinsics in vpXmlParserCamera format (perspective model without distortion)\n"
        "  --camera-name  camera name in that file (default Camera)\n"
        "  --laser        laser calibration: 'opening_angle_deg A' then 'cMl' and its 4 rows\n"
        "  --images       folder of images (.png .jpg .jpeg .ppm .pgm), processed in name order\n"
        "  --list         text file with one image path per line (relative to the list's folder)\n"
        "  --output       CSV 'frame,image,altitude_m,roll_rad,pitch_rad,inliers,status'; never an input\n"
        "  --method       estimator (default GP3)\n"
        "  --overlays     folder receiving <image>_overlay.png (points, inliers, fitted conic)\n"
        "  --threshold    RANSAC inlier threshold in pixels (default 2)\n"
        "  --seed         RANSAC seed (default 0)\n";
}

bool parseMethod(const std::string &name, Options &options)
{
  const std::pair<const char *, vpLaserConicPose::vpLaserConicMethod> methods[] = {
      {"GP3", vpLaserConicPose::GP3},
      {"PP3", vpLaserConicPose::PP3},
      {"PP5", vpLaserConicPose::PP5},
      {"PLANE_PAIR", vpLaserConicPose::PLANE_PAIR}};
  for (const auto &m : methods)
    if (name == m.first) {
      options.method = m.second;
      options.methodName = name;
      return true;
    }
  return false;
}

bool parseOptions(int argc, char **argv, Options &options, bool &help, std::string &error)
{
  const std::vector<std::string> valued = {"--camera", "--camera-name", "--laser",     "--images", "--list",
                                           "--output", "--method",      "--overlays", "--threshold", "--seed"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return true;
    }
    if (std::find(valued.begin(), valued.end(), arg) == valued.end()) {
      error = "unknown option '" + arg + "'";
      return false;
    }
    if (i + 1 >= argc) {
      error = "option " + arg + " needs a value";
      return false;
    }
    const std::string value = argv[++i];
    if (arg == "--camera")
      options.camera = value;
    else if (arg == "--camera-name")
      options.cameraName = value;
    else if (arg == "--laser")
      options.laser = value;
    else if (arg == "--images")
      options.imagesDir = value;
    else if (arg == "--list")
      options.listFile = value;
    else if (arg == "--output")
      options.output = value;
    else if (arg == "--overlays")
      options.overlays = value;
    else if (arg == "--method" && !parseMethod(value, options)) {
      error = "unknown method '" + value + "' (GP3, PP3, PP5 or PLANE_PAIR)";
      return false;
    } else if (arg == "--threshold" &&
               (!vpCsvTools::parseDouble(value, options.threshold, "--threshold", "value", error) ||
                !(options.threshold > 0.0))) {
      error = "--threshold must be a positive number of pixels, got '" + value + "'";
      return false;
    } else if (arg == "--seed" && !vpCsvTools::parseIndex(value, options.seed, "--seed", "value", error))
      return false;
  }
  if (options.camera.empty() || options.laser.empty() || options.output.empty()) {
    error = "--camera, --laser and --output are required";
    return false;
  }
  if (options.imagesDir.empty() == options.listFile.empty()) {
    error = "give exactly one of --images DIR and --list FILE";
    return false;
  }
  return true;
}

//! Reads the named camera from a vpXmlParserCamera file; the image size must be in the file.
bool readCamera(const Options &options, vpCameraParameters &cam, std::string &error)
{
  if (!fs::is_regular_file(options.camera)) {
    error = options.camera + ": camera file not found";
    return false;
  }
  vpXmlParserCamera parser;
  vpCameraParameters parsed;
  try {
    if (parser.parse(parsed, options.camera, options.cameraName, vpCameraParameters::perspectiveProjWithoutDistortion) !=
        vpXmlParserCamera::SEQUENCE_OK) {
      error = options.camera + ": no camera named '" + options.cameraName +
              "' with a perspective model without distortion (vpXmlParserCamera format)";
      return false;
    }
  } catch (const vpException &e) {
    error = options.camera + ": not a vpXmlParserCamera file (" + e.getStringMessage() + ")";
    return false;
  }
  if (!(parsed.get_px() > 0.0) || !(parsed.get_py() > 0.0)) {
    error = options.camera + ": focal lengths px, py must be positive";
    return false;
  }
  cam = parsed;
  return true;
}

bool hasImageExtension(const fs::path &p)
{
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pgm";
}

//! Image paths from --images (sorted by name) or --list (one per line, '#' comments, relative to the list).
bool listImages(const Options &options, std::vector<std::string> &images, std::string &error)
{
  if (!options.imagesDir.empty()) {
    if (!fs::is_directory(options.imagesDir)) {
      error = options.imagesDir + ": image folder not found";
      return false;
    }
    for (const fs::directory_entry &entry : fs::directory_iterator(options.imagesDir))
      if (entry.is_regular_file() && hasImageExtension(entry.path()))
        images.push_back(entry.path().string());
    std::sort(images.begin(), images.end());
    if (images.empty()) {
      error = options.imagesDir + ": no image (.png .jpg .jpeg .ppm .pgm) in this folder";
      return false;
    }
    return true;
  }
  std::ifstream in(options.listFile);
  if (!in) {
    error = options.listFile + ": cannot open the image list";
    return false;
  }
  const fs::path base = fs::path(options.listFile).parent_path();
  std::string line;
  unsigned int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string entry = vpCsvTools::trim(line);
    if (entry.empty() || entry[0] == '#')
      continue;
    const fs::path p = fs::path(entry).is_absolute() ? fs::path(entry) : base / entry;
    if (!fs::is_regular_file(p)) {
      error = vpCsvTools::location(options.listFile, lineNumber) + ": image '" + p.string() + "' not found";
      return false;
    }
    images.push_back(p.string());
  }
  if (images.empty()) {
    error = options.listFile + ": the list names no image";
    return false;
  }
  return true;
}

//! Refuses outputs that would overwrite an input (results CSV, or overlays in the image folder).
bool checkOutputs(const Options &options, const std::vector<std::string> &images, std::string &error)
{
  std::vector<std::string> inputs = {options.camera, options.laser};
  if (!options.listFile.empty())
    inputs.push_back(options.listFile);
  inputs.insert(inputs.end(), images.begin(), images.end());
  if (!vpCsvTools::checkOutputIsNotInput(options.output, inputs, error))
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
  try {
    vpImageIo::read(I, image);
  } catch (const vpException &e) {
    std::cerr << image << ": cannot be read as an image (" << e.getStringMessage() << ")" << std::endl;
    result.status = "unreadable_image";
    return result;
  }
  const std::vector<vpImagePoint> points = detector.detect(I);
  vpMatrix conic;
  std::vector<unsigned int> inliers;
  if (points.size() < minimumPoints(options.method)) {
    result.status = "not_enough_points";
  } else {
    vpPlane plane;
    try {
      if (estimator.computePlane(points, options.method, plane)) {
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
    const std::string caption = options.methodName + " " + result.status + " altitude " +
                                vpCsvTools::formatDouble(std::round(result.altitude * 1000.0) / 1000.0) + " m";
    vpLaserOverlay::draw(I, points, inliers, conic, caption);
    vpImageIo::write(I, (fs::path(options.overlays) / (fs::path(image).stem().string() + "_overlay.png")).string());
  }
  return result;
}
} // namespace

int main(int argc, char **argv)
{
  Options options;
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
  vpCameraParameters cam;
  double openingAngle = 0.0;
  vpHomogeneousMatrix cMl;
  std::vector<std::string> images;
  // The output is checked against the named files first, so that a wrong command line is refused
  // before the image list is read.
  if (!readCamera(options, cam, error) ||
      !vpLaserRigIo::readLaserCalibration(options.laser, openingAngle, cMl, error) ||
      !checkOutputs(options, images, error) || !listImages(options, images, error) ||
      !checkOutputs(options, images, error)) {
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
    out << k << "," << images[k] << ",";
    if (r.status == "ok") {
      out << vpCsvTools::formatDouble(r.altitude) << "," << vpCsvTools::formatDouble(r.roll) << ","
          << vpCsvTools::formatDouble(r.pitch);
      ++found;
    } else {
      out << "nan,nan,nan";
    }
    out << "," << r.inliers << "," << r.status << "\n";
  }
  if (!out) {
    std::cerr << argv[0] << ": " << options.output << ": write error" << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << options.methodName << ": " << found << "/" << images.size() << " images with a plane, written to "
            << options.output << (options.overlays.empty() ? "" : ", overlays in " + options.overlays) << std::endl;
  return EXIT_SUCCESS;
}
