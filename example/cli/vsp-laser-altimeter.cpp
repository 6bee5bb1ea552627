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
  vsp-laser-altimeter --camera camera.xml [--camera-name Camera] --laser laser.yaml|laser.txt
                      (--images DIR | --list images.txt) --output results.csv
                      [--method GP3|PP3|PP5|PLANE_PAIR] [--overlays DIR] [--threshold PX] [--seed N]
                      [--max-altitude-dilution K] [--max-attitude-sd DEG]
                      [--detector ridge|hsv] [--min-contrast GREY] [--noise-factor K] [--max-stripe-width PX]
                      [--saturation-level LEVEL] [--min-segment PX] [--sampling-step N] [--track PX]
                      [--no-guided] [--guided-margin PX] [--guided-step N] [--guided-factor K]
                      [--truth groundtruth.csv] [--max-altitude-error MM] [--max-nees K]
                      [--covariance-inflation K] [--imu imu.csv --frame-times times.csv --filtered imu_rate.csv]
  \endverbatim
  The camera file may hold the perspective model with distortion (kud, kdu): it is then used (the
  detected pixels are converted with vpPixelMeterConversion, the overlays drawn through the model).
  Output: CSV "frame,image,points,altitude_m,roll_rad,pitch_rad,inliers,status,sd_altitude_m,sd_roll_rad,
  sd_pitch_rad": the last three are the standard deviations of the estimate, from its covariance at the variance
  scale --covariance-inflation (default vpLaserConicPose::recommendedDetectorInflation()). Exit status 0 when every
  image was processed (frames without a plane, and unreadable images, say why in their status), 1 on a
  usage, file or format error, an image whose size is not the camera file's, a failed write (nothing is
  left half written: the CSV is written to a temporary file renamed when complete), or when
  --max-altitude-error or --max-nees is exceeded or cannot be checked (no frame with a plane). Status calibration_mismatch: the laser/camera calibration cannot
  explain the trace (vpLaserConicPose::STATUS_CALIBRATION_MISMATCH); when most frames get it, one line on
  stderr names the suspected mistake.
*/
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "vpCommandLine.h"
#include "vpCovarianceCheck.h"
#include "vpCsvTools.h"
#include "vpImageFileCheck.h"
#include "vpLaserFlightFusion.h"
#include "vpLaserOverlay.h"
#include "vpLaserRigIo.h"
#include "vpOutputFile.h"

namespace fs = std::filesystem;

namespace
{
struct Options
{
  std::string camera, cameraName = "Camera", laser, imagesDir, listFile, output, overlays, truth;
  std::string methodName = "GP3", detectorName = "ridge", instructions = "best";
  double threshold = 2.0;
  double maxAltitudeDilution = 5.0;
  double maxAttitudeSdDeg = 5.0;
  unsigned int seed = 0;
  // Detector settings (defaults of vpLaserConicDetector).
  double minContrast = 10.0, noiseFactor = 5.0, minSegment = 50.0, track = 0.0, maxAltitudeError = 0.0, maxNees = 0.0;
  unsigned int maxStripeWidth = 12, saturationLevel = 250, samplingStep = 1;
  bool guided = true;
  double guidedMargin = 12.0, guidedFactor = 3.5;
  unsigned int guidedStep = 1;
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
vpCommandLine commandLine(Options &options, vpLaserFlightFusion &fusion)
{
  vpCommandLine cli(
      "--camera camera.xml [--camera-name Camera] --laser laser.yaml|laser.txt\n"
      "          (--images DIR | --list images.txt) --output results.csv\n"
      "          [--method GP3|PP3|PP5|PLANE_PAIR] [--overlays DIR] [--threshold PX] [--seed N]\n"
      "          [--max-altitude-dilution K] [--max-attitude-sd DEG]\n"
      "          [--detector ridge|hsv] [--min-contrast GREY] [--noise-factor K] [--max-stripe-width PX]\n"
      "          [--saturation-level LEVEL] [--min-segment PX] [--sampling-step N] [--track PX]\n"
      "          [--no-guided] [--guided-margin PX] [--guided-step N] [--guided-factor K]\n"
      "          [--instructions best|avx2|sse2|scalar] [--truth groundtruth.csv] [--max-altitude-error MM]\n"
      "          [--max-nees K] [--covariance-inflation K]\n"
      "          [--imu imu.csv --frame-times times.csv --filtered imu_rate.csv [--imu-rotation R.txt]]",
      "Altitude, roll and pitch of a camera with a circular laser, from the laser trace in each image.");
  cli.addString("--camera", options.camera, "FILE",
                "intrinsics in vpXmlParserCamera format (the model with distortion when the file has it)");
  cli.addString("--camera-name", options.cameraName, "NAME", "camera name in that file (default Camera)");
  cli.addString("--laser", options.laser, "FILE",
                "laser calibration: the YAML of vsp-laser-calibrate, or text 'opening_angle_deg A' then 'cMl' and its "
                "4 rows");
  cli.addString("--images", options.imagesDir, "DIR",
                "folder of images (.png .jpg .jpeg .ppm .pgm), processed in name order");
  cli.addString("--list", options.listFile, "FILE",
                "text file with one image path per line (relative to the list's folder)");
  cli.addString("--output", options.output, "FILE",
                "CSV 'frame,image,points,altitude_m,roll_rad,pitch_rad,inliers,status,sd_altitude_m,sd_roll_rad,"
                "sd_pitch_rad'; never an input");
  cli.addChoice("--method", options.methodName, {"GP3", "PP3", "PP5", "PLANE_PAIR"}, "METHOD",
                "estimator (default GP3)");
  cli.addString("--overlays", options.overlays, "DIR",
                "folder receiving <image>_overlay.png (points, inliers, fitted conic)");
  cli.addDouble("--threshold", options.threshold, "PX", "RANSAC inlier threshold in pixels (default 2)",
                vpCommandLine::POSITIVE);
  cli.addUnsigned("--seed", options.seed, "N", "RANSAC seed (default 0)");
  cli.addDouble("--max-altitude-dilution", options.maxAltitudeDilution, "K",
                "refuse (weak_trace) a trace that fixes the altitude over K times less than the whole ring would "
                "(vpLaserConicPose::setMaxAltitudeDilution(); default 5, 0 disables)",
                vpCommandLine::NON_NEGATIVE);
  cli.addDouble("--max-attitude-sd", options.maxAttitudeSdDeg, "DEG",
                "refuse (no_parallax) an estimate whose attitude's standard deviation exceeds DEG degrees: a "
                "baseline too short for the distance of the ground (vpLaserConicPose::setMaxAttitudeUncertainty(); "
                "default 5, 0 disables)",
                vpCommandLine::NON_NEGATIVE);
  cli.addChoice("--detector", options.detectorName, {"ridge", "hsv"}, "METHOD",
                "trace detector: ridge of R - max(G, B) with a threshold from the image's noise (default), or the "
                "historical fixed HSV thresholds");
  cli.addDouble("--min-contrast", options.minContrast, "GREY",
                "ridge: smallest stripe contrast above its background, grey levels (default 10)",
                vpCommandLine::POSITIVE);
  cli.addDouble("--noise-factor", options.noiseFactor, "K",
                "ridge: the threshold is at least K times the noise estimated in the image (default 5)",
                vpCommandLine::NON_NEGATIVE);
  cli.addUnsigned("--max-stripe-width", options.maxStripeWidth, "PX",
                  "widest stripe (half-maximum width along a scan line), pixels (default 12)", 1);
  cli.addUnsigned("--saturation-level", options.saturationLevel, "LEVEL",
                  "ridge: red level from which a pixel is saturated, 128-255 (default 250)", 128);
  cli.addDouble("--min-segment", options.minSegment, "PX",
                "ridge: shortest chain of points kept, pixels (default 50; 0 keeps all)", vpCommandLine::NON_NEGATIVE);
  cli.addUnsigned("--sampling-step", options.samplingStep, "N", "scan one row/column in N (default 1)", 1);
  cli.addFlag("--no-guided", options.guided,
              "ridge: no second pass along the ellipse of the first pass's points (it finds the dim part of a "
              "ring that fades)",
              false);
  cli.addDouble("--guided-margin", options.guidedMargin, "PX",
                "ridge: the second pass searches within PX pixels across that ellipse (default 12)",
                vpCommandLine::POSITIVE);
  cli.addUnsigned("--guided-step", options.guidedStep, "N",
                  "ridge: the second pass measures a profile on every N-th row or column crossed (default 1)", 1);
  cli.addDouble("--guided-factor", options.guidedFactor, "K",
                "ridge: a profile of the second pass holds a stripe when its matched filter's response exceeds K "
                "times its noise measured along the profile (default 3.5)",
                vpCommandLine::POSITIVE);
  cli.addChoice("--instructions", options.instructions, {"best", "avx2", "sse2", "scalar"}, "SET",
                "ridge: instruction set of the vectorised passes, the same points with each (default best: AVX2 "
                "when the processor has it, else SSE2)");
  cli.addDouble("--track", options.track, "PX",
                "ridge: search within PX pixels of the previous frame's inliers when it had a plane (default 0: "
                "whole image every frame)",
                vpCommandLine::NON_NEGATIVE);
  cli.addString("--truth", options.truth, "FILE",
                "groundtruth.csv (vpLaserRigIo format, images matched by file name): print the errors");
  cli.addDouble("--max-altitude-error", options.maxAltitudeError, "MM",
                "with --truth: exit status 1 when an altitude error exceeds MM millimetres, or when no frame has a "
                "plane to compare (default 0: no check)",
                vpCommandLine::NON_NEGATIVE);
  cli.addDouble("--max-nees", options.maxNees, "K",
                "with --truth: exit status 1 when the median NEES of the per-frame covariance of (altitude, roll, "
                "pitch) exceeds K (2.37 if honest), or when no frame has one (default 0: no check)",
                vpCommandLine::NON_NEGATIVE);
  fusion.addOptions(cli); // IMU-rate output, vpLaserFlightFusion.h
  cli.require({"--camera", "--laser", "--output"});
  return cli;
}

bool hasImageExtension(const fs::path &p)
{
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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

/*!
  Refuses an output (the results CSV, the --filtered CSV) that would overwrite one of the files named on the
  command line (--truth, --frame-times and --camera were overwritten), or the other output, and fusion
  inputs without its output (they were ignored without a word).
*/
bool checkOutputIsNotNamedInput(const Options &options, const vpLaserFlightFusion &fusion, std::string &error)
{
  std::vector<std::string> inputs = fusion.inputs();
  if (!fusion.enabled() && !inputs.empty()) {
    error = "--imu, --frame-times and --imu-rotation are used by --filtered only: give --filtered FILE";
    return false;
  }
  inputs.insert(inputs.end(), {options.camera, options.laser});
  for (const std::string &file : {options.listFile, options.truth})
    if (!file.empty())
      inputs.push_back(file);
  return vpCsvTools::checkOutputs({options.output, fusion.output()}, inputs, error);
}

//! The overlay file of \e image in the folder \e overlays: <image stem>_overlay.png.
std::string overlayFile(const std::string &overlays, const std::string &image)
{
  return (fs::path(overlays) / (fs::path(image).stem().string() + "_overlay.png")).string();
}

//! Refuses outputs that would overwrite an image (results CSV, or overlays in the image folder), and images whose
//! overlays would share a name (a.png and a.jpg, or a.png in two folders of a list: one would overwrite the other).
bool checkOutputsAgainstImages(const Options &options, const std::vector<std::string> &images, std::string &error)
{
  if (!vpCsvTools::checkOutputIsNotInput(options.output, images, error))
    return false;
  if (options.overlays.empty())
    return true;
  std::map<std::string, std::string> imageOfOverlay;
  for (const std::string &image : images) {
    if (vpCsvTools::samePath(options.overlays, fs::path(image).parent_path().string())) {
      error = "--overlays '" + options.overlays + "' is a folder of input images: choose another folder";
      return false;
    }
    const std::string overlay = overlayFile(options.overlays, image);
    const auto [it, added] = imageOfOverlay.emplace(overlay, image);
    if (!added && !vpCsvTools::samePath(it->second, image)) {
      error = "--overlays: images '" + it->second + "' and '" + image + "' would both be drawn in '" + overlay +
              "': rename one of them";
      return false;
    }
  }
  return true;
}

struct FrameResult
{
  double altitude = 0.0, roll = 0.0, pitch = 0.0;
  //! Standard deviations of altitude (m), roll and pitch (rad) from the estimate's covariance; NaN without one.
  double altitudeSd = std::numeric_limits<double>::quiet_NaN(), rollSd = std::numeric_limits<double>::quiet_NaN(),
         pitchSd = std::numeric_limits<double>::quiet_NaN();
  unsigned int inliers = 0;
  size_t points = 0;
  std::vector<vpImagePoint> inlierPoints; //!< for the search region of the next frame (--track)
  std::string status = "ok";
  vpLaserConicPose::vpLaserConicMistake mistake = vpLaserConicPose::MISTAKE_UNKNOWN; //!< calibration_mismatch only
  bool overlayFailed = false; //!< --overlays: its overlay could not be written (the error is on stderr)
};

//! The camera file's image size (0 when it gives none), which every image must have.
struct ImageSize
{
  unsigned int width = 0, height = 0;
};

//! A detector with the settings of the command line. \exception vpLaserConicException on a bad setting.
vpLaserConicDetector makeDetector(const Options &options)
{
  vpLaserConicDetector detector;
  detector.setMethod(options.detectorName == "hsv" ? vpLaserConicDetector::DETECTION_HSV
                                                   : vpLaserConicDetector::DETECTION_RIDGE);
  detector.setMinContrast(options.minContrast);
  detector.setNoiseFactor(options.noiseFactor);
  detector.setMaxStripeWidth(options.maxStripeWidth);
  detector.setSaturationLevel(options.saturationLevel);
  detector.setMinSegmentLength(options.minSegment);
  detector.setSamplingStep(options.samplingStep);
  detector.setGuidedSearch(options.guided);
  detector.setGuidedMargin(options.guidedMargin);
  detector.setGuidedStep(options.guidedStep);
  detector.setGuidedThresholdFactor(options.guidedFactor);
  detector.setInstructionSet(options.instructions == "avx2"     ? vpLaserConicDetector::INSTRUCTIONS_AVX2
                             : options.instructions == "sse2"   ? vpLaserConicDetector::INSTRUCTIONS_SSE2
                             : options.instructions == "scalar" ? vpLaserConicDetector::INSTRUCTIONS_SCALAR
                                                                : vpLaserConicDetector::INSTRUCTIONS_BEST);
  return detector;
}

/*!
  The standard deviations of the estimate in \e result from its covariance (computed on every frame, see
  main()): the square roots of its diagonal, left NaN where the covariance could not be computed (a plane pair
  without a derivative there) or is not finite.
*/
void standardDeviations(const vpLaserConicPose &estimator, FrameResult &result)
{
  const vpMatrix covariance = estimator.getCovarianceMatrix();
  double *const sd[3] = {&result.altitudeSd, &result.rollSd, &result.pitchSd};
  for (unsigned int k = 0; k < 3; ++k)
    if (std::isfinite(covariance[k][k]) && covariance[k][k] >= 0.0)
      *sd[k] = std::sqrt(covariance[k][k]);
}

FrameResult processImage(const std::string &image, const Options &options, const vpCameraParameters &cam,
                         const ImageSize &size, vpLaserConicPose &estimator, vpLaserConicDetector &detector)
{
  FrameResult result;
  vpImage<vpRGBa> I;
  std::string why;
  if (!vpImageFileCheck::read(image, I, why)) {
    std::cerr << image << ": cannot be read as an image (" << why << ")" << std::endl;
    result.status = "unreadable_image";
    return result;
  }
  if (size.width > 0 && (I.getWidth() != size.width || I.getHeight() != size.height)) {
    std::ostringstream msg;
    msg << image << ": image of " << I.getWidth() << "x" << I.getHeight() << " pixels, but --camera '" << options.camera
        << "' is calibrated for " << size.width << "x" << size.height
        << ": intrinsics of another camera or resolution (recalibrate, or scale them)";
    throw vpException(vpException::dimensionError, msg.str());
  }
  const std::vector<vpImagePoint> points = detector.detect(I);
  result.points = points.size();
  vpMatrix conic;
  std::vector<unsigned int> inliers;
  if (points.size() < vpLaserConicPose::getMinimumPointCount(methodId(options.methodName))) {
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
        for (unsigned int index : inliers)
          result.inlierPoints.push_back(points[index]);
        conic = estimator.getImageConic();
        standardDeviations(estimator, result);
      } else {
        const bool mismatch = estimator.getStatus() == vpLaserConicPose::STATUS_CALIBRATION_MISMATCH;
        const bool weak = estimator.getStatus() == vpLaserConicPose::STATUS_WEAK_TRACE;
        const bool noParallax = estimator.getStatus() == vpLaserConicPose::STATUS_NO_PARALLAX;
        result.status = mismatch     ? "calibration_mismatch"
                        : weak       ? "weak_trace"
                        : noParallax ? "no_parallax"
                                     : "no_plane";
        result.mistake = estimator.getSuspectedMistake();
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
    vpLaserOverlay::draw(I, points, inliers, conic, cam, caption);
    // Checked: on a full disk libpng reported its error on the console only, and the run ended as written.
    std::string error;
    if (!vpOutputFile::writeImage(overlayFile(options.overlays, image), I, error)) {
      std::cerr << error << std::endl;
      result.overlayFailed = true;
    }
  }
  return result;
}
/*!
  Reads the camera, the laser calibration and the image list, and checks that no output names an
  input. \return false with \e error naming the file at fault.
*/
bool readInputs(const Options &options, const vpLaserFlightFusion &fusion, vpCameraParameters &cam, ImageSize &size,
                double &openingAngle, vpHomogeneousMatrix &cMl, std::vector<std::string> &images, std::string &error)
{
  // The output is checked against the named files first, so that a wrong command line is refused
  // before the image list is read; then against the images.
  return vpOutputFile::checkWritable(options.output, error) &&
         vpLaserRigIo::readCamera(options.camera, options.cameraName, cam, size.width, size.height, error) &&
         vpLaserRigIo::readLaserCalibration(options.laser, openingAngle, cMl, error) &&
         checkOutputIsNotNamedInput(options, fusion, error) && listImages(options, images, error) &&
         checkOutputsAgainstImages(options, images, error);
}

//! One row of the results CSV; the numbers are "nan" when the frame has no plane.
void writeRow(std::ostream &out, size_t frame, const std::string &image, const FrameResult &r)
{
  out << frame << "," << image << "," << r.points << ",";
  if (r.status == "ok")
    out << vpCsvTools::formatDouble(r.altitude) << "," << vpCsvTools::formatDouble(r.roll) << ","
        << vpCsvTools::formatDouble(r.pitch);
  else
    out << "nan,nan,nan";
  out << "," << r.inliers << "," << r.status;
  for (double sd : {r.altitudeSd, r.rollSd, r.pitchSd}) // NaN ("nan") unless the frame has a plane
    out << "," << vpCsvTools::formatDouble(sd);
  out << "\n";
}

/*!
  One line naming the suspected mistake when most frames with a trace are refused as a calibration
  mismatch (a per-frame row alone would leave the user to guess), nothing otherwise.
*/
void printSequenceDiagnosis(const std::vector<FrameResult> &results, const char *program)
{
  std::map<vpLaserConicPose::vpLaserConicMistake, unsigned int> mistakes;
  unsigned int withTrace = 0, mismatches = 0;
  for (const FrameResult &r : results) {
    if (r.status == "unreadable_image" || r.status == "not_enough_points")
      continue;
    ++withTrace;
    if (r.status == "calibration_mismatch") {
      ++mismatches;
      ++mistakes[r.mistake];
    }
  }
  if (withTrace == 0 || 2 * mismatches <= withTrace)
    return;
  auto likely = std::max_element(mistakes.begin(), mistakes.end(),
                                 [](const auto &a, const auto &b) { return a.second < b.second; });
  std::cerr << program << ": " << mismatches << "/" << withTrace
            << " frames with a trace refused as a calibration mismatch: "
            << (likely->first == vpLaserConicPose::MISTAKE_UNKNOWN
                    ? std::string("check --laser (full opening angle, cMl not lMc) and --camera (intrinsics of this "
                                  "camera at this resolution)")
                    : vpLaserConicPose::getMistakeMessage(likely->first) + " (" + std::to_string(likely->second) +
                          " frames); fix --laser or --camera")
            << "; the planes of the other frames come from the same calibration: do not trust them" << std::endl;
}

//! The program; main() only adds a last-resort error report.
int run(int argc, char **argv)
{
  Options options;
  vpLaserFlightFusion fusion;
  vpCommandLine cli = commandLine(options, fusion);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (cli.given("--images") == cli.given("--list"))
    return cli.fail("give exactly one of --images DIR and --list FILE");
  // Checked here, not at the first frame with a plane, where the detector would refuse it after work done.
  if (options.track > vpLaserConicDetector::getMaxMargin())
    return cli.fail("--track must be at most " +
                    std::to_string(static_cast<long>(vpLaserConicDetector::getMaxMargin())) + " pixels");
  std::string error;
  vpCameraParameters cam;
  double openingAngle = 0.0;
  vpHomogeneousMatrix cMl;
  std::vector<std::string> images;
  ImageSize size;
  // A bound on the errors against a ground truth without one would check nothing: refused, not ignored.
  if (options.truth.empty() && (options.maxAltitudeError > 0.0 || options.maxNees > 0.0)) {
    std::cerr << argv[0] << ": " << (options.maxNees > 0.0 ? "--max-nees" : "--max-altitude-error")
              << " needs --truth (the ground truth the errors are measured against)" << std::endl;
    return EXIT_FAILURE;
  }
  if (!readInputs(options, fusion, cam, size, openingAngle, cMl, images, error)) {
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
  std::vector<vpLaserGroundTruthFrame> truth;
  if (!options.truth.empty() && !vpLaserRigIo::readGroundTruth(options.truth, truth, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  // Written to a temporary file renamed when complete: a failed run leaves an existing file as it was.
  vpOutputFile outFile(options.output);
  if (!outFile.open(error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::ostream &out = outFile.stream();
  vpLaserConicPose estimator;
  vpLaserConicDetector detector;
  try {
    estimator.setCameraParameters(cam);
    estimator.setLaser(openingAngle, cMl);
    estimator.setRansacThreshold(options.threshold);
    estimator.setMaxAltitudeDilution(options.maxAltitudeDilution);
    estimator.setMaxAttitudeUncertainty(vpMath::rad(options.maxAttitudeSdDeg));
    estimator.setRansacSeed(options.seed);
  } catch (const vpException &e) {
    std::cerr << argv[0] << ": " << options.camera << " / " << options.laser << ": " << e.getStringMessage()
              << std::endl;
    return EXIT_FAILURE;
  }
  try {
    detector = makeDetector(options);
  } catch (const vpException &e) {
    std::cerr << argv[0] << ": " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
  if (fusion.enabled() && !fusion.prepare(images.size(), error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  // Every frame's covariance, at the variance scale of --covariance-inflation: its standard deviations are
  // written with the estimate, a filter fuses it (--imu), and with a ground truth its NEES is checked.
  fusion.configure(estimator);
  vpCovarianceCheck covarianceCheck;
  out << "frame,image,points,altitude_m,roll_rad,pitch_rad,inliers,status,sd_altitude_m,sd_roll_rad,sd_pitch_rad\n";
  unsigned int found = 0, compared = 0, overlayFailures = 0;
  double worstAltitude = 0.0, worstRoll = 0.0, worstPitch = 0.0;
  std::vector<FrameResult> results;
  for (size_t k = 0; k < images.size(); ++k) {
    FrameResult r;
    try {
      r = processImage(images[k], options, cam, size, estimator, detector);
    } catch (const vpException &e) {
      if (e.getCode() != vpException::dimensionError)
        throw;
      std::cerr << argv[0] << ": " << e.getStringMessage() << "; nothing written" << std::endl;
      return EXIT_FAILURE;
    }
    writeRow(out, k, images[k], r);
    overlayFailures += r.overlayFailed ? 1 : 0;
    fusion.addFrame(k, r.status == "ok", estimator);
    found += r.status == "ok" ? 1 : 0;
    // Next frame: search near this frame's inliers, or in the whole image after a failure.
    if (options.track > 0.0 && r.status == "ok" && options.detectorName == "ridge")
      detector.setSearchRegion(r.inlierPoints, options.track);
    else
      detector.clearSearchRegion();
    const std::string name = fs::path(images[k]).filename().string();
    for (const vpLaserGroundTruthFrame &t : truth)
      if (r.status == "ok" && fs::path(t.image).filename().string() == name) {
        ++compared;
        worstAltitude = std::max(worstAltitude, std::fabs(r.altitude - t.altitude));
        worstRoll = std::max(worstRoll, std::fabs(r.roll - t.roll));
        worstPitch = std::max(worstPitch, std::fabs(r.pitch - t.pitch));
        vpColVector e(3);
        e[0] = r.altitude - t.altitude;
        e[1] = r.roll - t.roll;
        e[2] = r.pitch - t.pitch;
        covarianceCheck.add(e, estimator.getCovarianceMatrix());
      }
    r.inlierPoints.clear();
    results.push_back(r);
  }
  if (!outFile.commit(error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  printSequenceDiagnosis(results, argv[0]);
  std::string summary;
  if (fusion.enabled() && !fusion.run(summary, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  if (fusion.enabled())
    std::cout << summary << std::endl;
  std::cout << options.methodName << ": " << found << "/" << images.size() << " images with a plane, written to "
            << options.output
            << (options.overlays.empty() || overlayFailures > 0 ? "" : ", overlays in " + options.overlays)
            << std::endl;
  if (overlayFailures > 0) {
    std::cerr << argv[0] << ": " << overlayFailures << " of " << images.size() << " overlays could not be written to "
              << options.overlays << std::endl;
    return EXIT_FAILURE;
  }
  if (!truth.empty() && compared == 0) {
    // Nothing compared is not an error of 0 mm: a bound given cannot pass on it.
    std::cout << "against " << options.truth << ": no frame with a plane and a ground truth" << std::endl;
    if (options.maxAltitudeError > 0.0 || options.maxNees > 0.0) {
      std::ostringstream bound;
      if (options.maxAltitudeError > 0.0)
        bound << "--max-altitude-error " << options.maxAltitudeError << " mm";
      else
        bound << "--max-nees " << options.maxNees;
      std::cerr << argv[0] << ": " << bound.str() << " cannot be checked: no frame with a plane to compare"
                << std::endl;
      return EXIT_FAILURE;
    }
  } else if (!truth.empty()) {
    std::cout << "against " << options.truth << ": " << compared
              << " frames with a plane and a ground truth, worst errors " << 1000.0 * worstAltitude << " mm altitude, "
              << vpMath::deg(worstRoll) << " deg roll, " << vpMath::deg(worstPitch) << " deg pitch" << std::endl;
    std::cout << covarianceCheck.summary(estimator.getCovarianceInflation()) << std::endl;
    if (options.maxNees > 0.0 && !(covarianceCheck.median() <= options.maxNees)) {
      std::cerr << argv[0] << ": median NEES " << covarianceCheck.median() << " > --max-nees " << options.maxNees
                << ": the errors are larger than the per-frame covariance says; it holds the trace's noise only (a "
                   "laser calibration's error adds to the errors, and a variance scale too small for the "
                   "detector and the compression)"
                << std::endl;
      return EXIT_FAILURE;
    }
    if (options.maxAltitudeError > 0.0 && 1000.0 * worstAltitude > options.maxAltitudeError) {
      std::cerr << argv[0] << ": altitude error " << 1000.0 * worstAltitude << " mm > --max-altitude-error "
                << options.maxAltitudeError << " mm" << std::endl;
      return EXIT_FAILURE;
    }
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
