/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example laser-sequence-eval.cpp
  Runs the red-trace detector and the PP5, PP3 and GP3 estimators over the simulated hand-held
  sequence of data/laser_sequence and prints the errors against the ground truth in the layout of
  Table 2 of Boutteau et al. (JMIV 2018): altitude (mm), pitch and roll (deg), mean +- standard
  deviation per method. Per-frame results go to a CSV file and the altitude / attitude curves to PNG.
  With --check-against-first-pass the sequence is also run with the detector's first pass alone
  (vpLaserConicDetector::setGuidedSearch(false)) and GP-3's errors of the two are compared frame by frame.
  With --track the sequence is run as in flight: each frame is searched along the image conic of the
  previous frame's GP-3 estimate (vpLaserConicDetector::setSearchRegion(const vpMatrix &, double)), over
  the whole image when that gives GP-3 no plane; --check-against-whole-frame compares its GP-3 errors with
  those of a whole-frame detection of every frame.
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include "laserRigSetup.h"
#include "vpCommandLine.h"
#include "vpLaserRigIo.h"
#include "vpOutputFile.h"
#include "vpPngPlot.h"

namespace
{
struct Options
{
  std::string data = std::string(VSP_DATA_DIR) + "/laser_sequence";
  std::string output = "laser-sequence-results";
  double threshold = 2.0;
  int ransacTrials = 1000;
  bool check = false;
  bool verbose = false;
  bool localOptimisation = true;
  bool againstFirstPass = false;  //!< also run the first pass alone and compare GP-3's errors frame by frame
  double trackMargin = 0.0;       //!< > 0: search each frame along the previous frame's conic, this margin (px)
  unsigned int trackingStep = 0;  //!< vpLaserConicDetector::setTrackingStep() when > 0
  bool againstWholeFrame = false; //!< with --track: also detect every frame over the whole image and compare
  std::string laserFile;          //!< overrides DIR/laser.txt when set
};

struct Method
{
  vpLaserConicPose::vpLaserConicMethod id;
  std::string name;
  vpColor color;
};

const std::vector<Method> &methods()
{
  static const std::vector<Method> list = {{vpLaserConicPose::PP5, "PP-5", vpColor::red},
                                           {vpLaserConicPose::PP3, "PP-3", vpColor::blue},
                                           {vpLaserConicPose::GP3, "GP-3", vpColor::darkGreen}};
  return list;
}

//! Absolute errors of one method over the sequence (successful frames only), and its estimates.
struct MethodResult
{
  std::vector<double> altitudeMm, pitchDeg, rollDeg;
  std::vector<double> estAltitude, estRoll, estPitch; //!< per frame, NaN on failure
  int failures = 0;
};

struct MeanStd
{
  double mean = 0.0, std = 0.0;
};

MeanStd meanStd(const std::vector<double> &v)
{
  MeanStd m;
  if (v.empty()) {
    m.mean = m.std = std::nan("");
    return m;
  }
  for (double x : v) {
    m.mean += x;
  }
  m.mean /= v.size();
  for (double x : v) {
    m.std += (x - m.mean) * (x - m.mean);
  }
  m.std = v.size() > 1 ? std::sqrt(m.std / (v.size() - 1)) : 0.0;
  return m;
}

std::string cell(const std::vector<double> &v)
{
  const MeanStd m = meanStd(v);
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(2) << m.mean << " ± " << m.std;
  return ss.str();
}

/*!
  Distances (pixels) of detected points to the exact image of the trace, from the true laser pose and
  the true ground plane: the detection error that the estimators see, used to justify the bounds.
*/
void detectionResiduals(const std::vector<vpImagePoint> &points, const vpCameraParameters &cam, double openingAngle,
                        const vpHomogeneousMatrix &cMlTrue, const vpPlane &plane, std::vector<double> &residuals)
{
  vpLaserSolvers::LaserCone cone;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      cone.cRl(i, j) = cMlTrue[i][j];
    }
    cone.apex(i) = cMlTrue[i][3];
  }
  cone.halfAngle = 0.5 * openingAngle;
  const Eigen::Vector4d pi(plane.getA(), plane.getB(), plane.getC(), plane.getD());
  const Eigen::Matrix3d conic = vpLaserSolvers::conicFromPlane(pi, cone);
  const double focal = 0.5 * (cam.get_px() + cam.get_py());
  for (const vpImagePoint &ip : points) {
    const Eigen::Vector2d x((ip.get_u() - cam.get_u0()) / cam.get_px(), (ip.get_v() - cam.get_v0()) / cam.get_py());
    residuals.push_back(focal * vpLaserSolvers::sampsonDistance(conic, x));
  }
}

std::string fmt(double x)
{
  std::ostringstream ss;
  ss << std::setprecision(3) << x;
  return ss.str();
}

double angleDifference(double a, double b) { return std::fabs(std::remainder(a - b, 2.0 * M_PI)); }

//! Declares the options of the program; \e opt receives their values.
vpCommandLine commandLine(Options &opt)
{
  vpCommandLine cli("[--data DIR] [--output DIR] [--threshold PX] [--laser FILE] [--no-local-optimisation]\n"
                    "       [--verbose] [--check] [--check-against-first-pass]\n"
                    "       [--track PX [--tracking-step N] [--check-against-whole-frame]]",
                    "Detection + PP-5 / PP-3 / GP-3 over a laser sequence, errors in the layout of Table 2.");
  cli.addString("--data", opt.data, "DIR", "dataset directory (default " VSP_DATA_DIR "/laser_sequence)");
  cli.addString("--output", opt.output, "DIR", "per-frame CSV and PNG curves (default laser-sequence-results)");
  cli.addString("--laser", opt.laserFile, "FILE",
                "laser calibration to use instead of DIR/laser.txt (e.g. DIR/laser_true.txt)");
  vspLaserRig::addEstimatorOptions(cli, opt.threshold, opt.localOptimisation, "");
  cli.addFlag("--verbose", opt.verbose, "print the estimate, inlier count and RANSAC samples of every frame");
  cli.addFlag("--check", opt.check, "exit non-zero when an error exceeds the bounds justified in the source");
  cli.addFlag("--check-against-first-pass", opt.againstFirstPass,
              "also run the detector's first pass alone (no guided second pass) and exit non-zero when GP-3's mean "
              "altitude, roll or pitch error of the default detector exceeds that of the first pass by more than "
              "two standard errors of their frame-by-frame difference");
  cli.addDouble("--track", opt.trackMargin, "PX",
                "tracking, as in flight: each frame is searched along the image conic of the previous frame's GP-3 "
                "estimate within PX pixels, over the whole image again when that gives GP-3 no plane",
                vpCommandLine::POSITIVE);
  cli.addUnsigned("--tracking-step", opt.trackingStep, "N",
                  "with --track: a profile every N image lines (vpLaserConicDetector::setTrackingStep; default: the "
                  "detector's)",
                  1);
  cli.addFlag("--check-against-whole-frame", opt.againstWholeFrame,
              "with --track: also detect every frame over the whole image and exit non-zero when tracking's GP-3 "
              "mean altitude, roll or pitch error exceeds the whole frame's by more than two standard errors of "
              "their frame-by-frame difference");
  return cli;
}

void writeResults(const Options &opt, const vpLaserDataset &dataset, const std::vector<MethodResult> &results,
                  const std::vector<unsigned int> &detected)
{
  vpOutputFile file(opt.output + "/sequence.csv");
  std::string error;
  if (!file.open(error))
    throw vpException(vpException::ioError, "%s", error.c_str());
  std::ostream &out = file.stream();
  out << "frame,detected_points,gt_altitude_m,gt_roll_deg,gt_pitch_deg";
  for (const Method &m : methods()) {
    out << "," << m.name << "_altitude_m," << m.name << "_roll_deg," << m.name << "_pitch_deg";
  }
  out << "\n" << std::setprecision(10);
  std::vector<double> frameIndex, gtAltitude, gtRoll, gtPitch;
  for (size_t k = 0; k < dataset.frames.size(); ++k) {
    const vpLaserGroundTruthFrame &f = dataset.frames[k];
    out << f.frame << "," << detected[k] << "," << f.altitude << "," << vpMath::deg(f.roll) << ","
        << vpMath::deg(f.pitch);
    for (const MethodResult &r : results) {
      out << "," << r.estAltitude[k] << "," << vpMath::deg(r.estRoll[k]) << "," << vpMath::deg(r.estPitch[k]);
    }
    out << "\n";
    frameIndex.push_back(f.frame);
    gtAltitude.push_back(f.altitude);
    gtRoll.push_back(vpMath::deg(f.roll));
    gtPitch.push_back(vpMath::deg(f.pitch));
  }
  if (!file.commit(error))
    throw vpException(vpException::ioError, "%s", error.c_str());

  const char *names[] = {"altitude", "roll", "pitch"};
  const char *units[] = {"altitude (m)", "roll (deg)", "pitch (deg)"};
  const std::vector<double> *truth[] = {&gtAltitude, &gtRoll, &gtPitch};
  for (int q = 0; q < 3; ++q) {
    vpPngPlot plot(std::string("Simulated hand-held sequence: ") + names[q], "frame", units[q]);
    plot.addCurve("ground truth", frameIndex, *truth[q], vpColor::black);
    for (size_t i = 0; i < methods().size(); ++i) {
      std::vector<double> ys = q == 0 ? results[i].estAltitude : (q == 1 ? results[i].estRoll : results[i].estPitch);
      if (q > 0) {
        for (double &y : ys) {
          y = vpMath::deg(y);
        }
      }
      plot.addPoints(methods()[i].name, frameIndex, ys, methods()[i].color);
    }
    plot.write(opt.output + "/sequence_" + names[q] + ".png");
  }
}
//! The rendering pose of the laser, when the dataset ships it (laser_true.txt): it measures the detection error.
struct TrueLaser
{
  bool known = false;
  double openingAngle = 0.0;
  vpHomogeneousMatrix cMl;
};

//! One run of the sequence: the estimators' results, the points detected per frame, the points' distances
//! to the exact trace (when the true laser is known), and how the frames were searched.
struct SequenceRun
{
  std::vector<MethodResult> results; //!< per method of methods()
  std::vector<unsigned int> detected;
  std::vector<double> residuals;
  int tracked = 0;    //!< frames searched along the previous frame's conic
  int wholeAgain = 0; //!< of those, frames searched again over the whole image (GP-3 found no plane)
};

//! GP-3 on \e points, false when it finds no plane or throws (the frame's message printed).
bool gp3Plane(vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points, unsigned int frame)
{
  vpPlane plane;
  try {
    return estimator.computePlane(points, vpLaserConicPose::GP3, plane);
  } catch (const vpException &e) {
    std::cerr << "frame " << frame << " GP-3: " << e.getMessage() << std::endl;
  }
  return false;
}

/*!
  The points of frame I. With a search region (tracking: the previous frame's conic) the detector searches
  along it, and over the whole image again when GP-3 finds no plane in what it returns (the ring left the
  band, or tracking followed something else), as a tracking loop does.
*/
std::vector<vpImagePoint> detectFrame(const vpImage<vpRGBa> &I, unsigned int frame, vpLaserConicDetector &detector,
                                      vpLaserConicPose &estimator, SequenceRun &run)
{
  std::vector<vpImagePoint> points = detector.detect(I);
  if (!detector.hasSearchRegion())
    return points;
  ++run.tracked;
  estimator.setRansacSeed(frame);
  if (gp3Plane(estimator, points, frame))
    return points;
  ++run.wholeAgain;
  detector.clearSearchRegion();
  return detector.detect(I);
}

//! Detection with \e detector and the three estimators on every frame of \e dataset, each frame searched along
//! the previous one's GP-3 conic within \e trackMargin pixels when it is positive. Throws vpException when an
//! image cannot be read.
SequenceRun runSequence(const Options &opt, const vpLaserDataset &dataset, vpLaserConicDetector &detector,
                        const TrueLaser &truth, double trackMargin)
{
  SequenceRun run;
  run.results.assign(methods().size(), MethodResult());
  vpLaserConicPose estimator;
  estimator.setCameraParameters(dataset.cam);
  estimator.setLaser(dataset.openingAngle, dataset.cMl);
  estimator.setRansacThreshold(opt.threshold);
  estimator.setRansacMaxTrials(opt.ransacTrials);
  estimator.setLocalOptimisation(opt.localOptimisation);
  for (const vpLaserGroundTruthFrame &f : dataset.frames) {
    vpImage<vpRGBa> I;
    vpImageIo::read(I, dataset.imagePath(f));
    const std::vector<vpImagePoint> points = detectFrame(I, f.frame, detector, estimator, run);
    run.detected.push_back(static_cast<unsigned int>(points.size()));
    if (truth.known) {
      detectionResiduals(points, dataset.cam, truth.openingAngle, truth.cMl, f.plane, run.residuals);
    }
    detector.clearSearchRegion();
    for (size_t i = 0; i < methods().size(); ++i) {
      MethodResult &r = run.results[i];
      estimator.setRansacSeed(f.frame);
      vpPlane plane;
      bool ok = false;
      try {
        ok = estimator.computePlane(points, methods()[i].id, plane);
      } catch (const vpException &e) {
        std::cerr << "frame " << f.frame << " " << methods()[i].name << ": " << e.getMessage() << std::endl;
      }
      if (!ok) {
        ++r.failures;
        r.estAltitude.push_back(std::nan(""));
        r.estRoll.push_back(std::nan(""));
        r.estPitch.push_back(std::nan(""));
        continue;
      }
      if (trackMargin > 0.0 && methods()[i].id == vpLaserConicPose::GP3)
        detector.setSearchRegion(estimator.getImageConic(), trackMargin);
      if (opt.verbose) {
        std::cout << "frame " << f.frame << " " << methods()[i].name << ": altitude error "
                  << 1e3 * (estimator.getAltitude() - f.altitude) << " mm, roll error "
                  << vpMath::deg(estimator.getRoll() - f.roll) << " deg, pitch error "
                  << vpMath::deg(estimator.getPitch() - f.pitch) << " deg, inliers " << estimator.getInliers().size()
                  << "/" << points.size() << ", samples " << estimator.getRansacTrials() << std::endl;
      }
      r.estAltitude.push_back(estimator.getAltitude());
      r.estRoll.push_back(estimator.getRoll());
      r.estPitch.push_back(estimator.getPitch());
      r.altitudeMm.push_back(1e3 * std::fabs(estimator.getAltitude() - f.altitude));
      r.rollDeg.push_back(vpMath::deg(angleDifference(estimator.getRoll(), f.roll)));
      r.pitchDeg.push_back(vpMath::deg(angleDifference(estimator.getPitch(), f.pitch)));
    }
  }
  return run;
}

//! What compareErrors() compares: the two runs in words.
struct Comparison
{
  std::string title;     //!< the heading line, ending with "frame by frame:"
  std::string candidate; //!< column heading of the run under test
  std::string reference; //!< column heading of the run it must be no worse than
  std::string failure;   //!< printed when it is worse
  std::string success;   //!< printed when it is not
  //! Frames where the candidate gives a plane and the reference none fail the comparison (a frame without
  //! the laser that a whole-frame detection finds empty must not give tracking a plane).
  bool noPlaneWithoutReference = false;
};

/*!
  GP-3's errors of \e candidate and \e reference over the frames where both give a plane: prints them with
  their frame-by-frame difference, and returns how many of altitude, roll and pitch have a mean difference
  above two standard errors of that difference (the candidate worse than the reference beyond the frames'
  spread).
*/
int compareErrors(const vpLaserDataset &dataset, const MethodResult &candidate, const MethodResult &reference,
                  const Comparison &words)
{
  std::cout << "\n"
            << words.title << "\n| | " << words.candidate << ": mean ± std, median | " << words.reference
            << " | difference: mean (standard error) | frames better / worse |\n|---|---|---|---|---|\n";
  const char *names[] = {"Altitude error (mm)", "Roll error (deg)", "Pitch error (deg)"};
  int failed = 0;
  for (int q = 0; q < 3; ++q) {
    std::vector<double> a, b, d;
    for (size_t k = 0; k < dataset.frames.size(); ++k) {
      const vpLaserGroundTruthFrame &f = dataset.frames[k];
      auto error = [&](const MethodResult &r) {
        return q == 0 ? 1e3 * std::fabs(r.estAltitude[k] - f.altitude)
                      : vpMath::deg(q == 1 ? angleDifference(r.estRoll[k], f.roll)
                                           : angleDifference(r.estPitch[k], f.pitch));
      };
      const double ea = error(candidate), eb = error(reference);
      if (std::isfinite(ea) && std::isfinite(eb)) {
        a.push_back(ea);
        b.push_back(eb);
        d.push_back(ea - eb);
      }
    }
    if (d.size() < 2) {
      std::cout << "| " << names[q] << " | fewer than 2 frames with a plane from both |\n";
      ++failed;
      continue;
    }
    const MeanStd diff = meanStd(d);
    const double standardError = diff.std / std::sqrt(static_cast<double>(d.size()));
    const long better = std::count_if(d.begin(), d.end(), [](double x) { return x < 0.0; });
    const long worse = std::count_if(d.begin(), d.end(), [](double x) { return x > 0.0; });
    std::ostringstream row;
    row << std::fixed << std::setprecision(q == 0 ? 2 : 3) << "| " << names[q] << " | " << meanStd(a).mean << " ± "
        << meanStd(a).std << ", " << vpMath::getMedian(a) << " | " << meanStd(b).mean << " ± " << meanStd(b).std << ", "
        << vpMath::getMedian(b) << " | " << std::showpos << diff.mean << std::noshowpos << " (" << standardError
        << ") | " << better << " / " << worse << " |";
    std::cout << row.str() << std::endl;
    failed += diff.mean > 2.0 * standardError ? 1 : 0;
  }
  if (words.noPlaneWithoutReference) {
    std::vector<unsigned int> extra;
    for (size_t k = 0; k < dataset.frames.size(); ++k)
      if (std::isfinite(candidate.estAltitude[k]) && !std::isfinite(reference.estAltitude[k]))
        extra.push_back(dataset.frames[k].frame);
    std::cout << "Frames with a plane from " << words.candidate << " and none from " << words.reference << ": "
              << extra.size();
    for (unsigned int frame : extra)
      std::cout << " " << frame;
    std::cout << std::endl;
    failed += extra.empty() ? 0 : 1;
  }
  std::cout << (failed ? words.failure : words.success) << std::endl;
  return failed;
}

int compareWithFirstPass(const vpLaserDataset &dataset, const MethodResult &guided, const MethodResult &firstPass)
{
  return compareErrors(dataset, guided, firstPass,
                       {"GP-3 with the default detector against its first pass alone (setGuidedSearch(false)), frame "
                        "by frame:",
                        "default", "first pass alone",
                        "CHECK FAILED: the default detector's GP-3 errors exceed the first pass's",
                        "The default detector's GP-3 errors are no worse than the first pass's (within two standard "
                        "errors of the difference)"});
}

int compareWithWholeFrame(const vpLaserDataset &dataset, const MethodResult &tracked, const MethodResult &whole)
{
  return compareErrors(dataset, tracked, whole,
                       {"GP-3 with tracking (the previous frame's conic as the search region) against a whole-frame "
                        "detection of every frame, frame by frame:",
                        "tracking", "whole frame",
                        "CHECK FAILED: tracking's GP-3 errors exceed the whole frame's, or it gives planes the whole "
                        "frame does not",
                        "Tracking's GP-3 errors are no worse than the whole frame's (within two standard errors of the "
                        "difference)",
                        true});
}

//! The program's work once its options are read; returns its exit status.
int run(Options &opt, const vpCommandLine &)
{
  if (opt.trackMargin <= 0.0 && (opt.trackingStep > 0 || opt.againstWholeFrame)) {
    std::cerr << "--tracking-step and --check-against-whole-frame need --track PX" << std::endl;
    return EXIT_FAILURE;
  }
  vpLaserDataset dataset;
  std::string error;
  if (!vpLaserRigIo::readDataset(opt.data, dataset, error)) {
    std::cerr << error << std::endl;
    return EXIT_FAILURE;
  }
  if (!opt.laserFile.empty() &&
      !vpLaserRigIo::readLaserCalibration(opt.laserFile, dataset.openingAngle, dataset.cMl, error)) {
    std::cerr << error << std::endl;
    return EXIT_FAILURE;
  }
  TrueLaser truth;
  std::string ignored;
  truth.known =
      vpLaserRigIo::readLaserCalibration(opt.data + "/laser_true.txt", truth.openingAngle, truth.cMl, ignored);
  SequenceRun main, firstPass, wholeFrame;
  try {
    vpIoTools::makeDirectory(opt.output);
    vpLaserConicDetector detector;
    if (opt.trackingStep > 0)
      detector.setTrackingStep(opt.trackingStep);
    main = runSequence(opt, dataset, detector, truth, opt.trackMargin);
    if (opt.againstFirstPass) {
      vpLaserConicDetector firstPassDetector;
      firstPassDetector.setGuidedSearch(false);
      firstPass = runSequence(opt, dataset, firstPassDetector, truth, 0.0);
    }
    if (opt.againstWholeFrame) {
      vpLaserConicDetector wholeFrameDetector;
      wholeFrame = runSequence(opt, dataset, wholeFrameDetector, truth, 0.0);
    }
    writeResults(opt, dataset, main.results, main.detected);
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  const std::vector<MethodResult> &results = main.results;
  std::vector<double> &residuals = main.residuals;
  const unsigned int minDetected = *std::min_element(main.detected.begin(), main.detected.end());
  std::cout << dataset.frames.size() << " frames of " << opt.data << ", " << minDetected << " to "
            << *std::max_element(main.detected.begin(), main.detected.end()) << " trace points detected per frame, "
            << "laser " << (opt.laserFile.empty() ? opt.data + "/laser.txt" : opt.laserFile) << ", RANSAC threshold "
            << opt.threshold << " px, " << (opt.localOptimisation ? "least-squares refit on the inliers" : "no refit")
            << "\nPer-frame results: " << opt.output << "/sequence.csv, curves: " << opt.output
            << "/sequence_{altitude,roll,pitch}.png\n";
  if (opt.trackMargin > 0.0)
    std::cout << "Tracking: " << main.tracked << " frames searched along the previous frame's GP-3 conic (margin "
              << opt.trackMargin << " px, a profile every "
              << (opt.trackingStep > 0 ? opt.trackingStep : vpLaserConicDetector().getTrackingStep()) << " lines), "
              << main.wholeAgain << " of them again over the whole image (GP-3 found no plane)\n";
  std::cout << "\n";
  double rmsResidual = 0.0, outlierFraction = 0.0;
  if (!residuals.empty()) {
    for (double r : residuals) {
      rmsResidual += r * r;
      outlierFraction += r > 2.0 ? 1.0 : 0.0;
    }
    rmsResidual = std::sqrt(rmsResidual / residuals.size());
    outlierFraction /= residuals.size();
    std::sort(residuals.begin(), residuals.end());
    std::cout << "Detection error against the exact trace (laser_true.txt): RMS " << rmsResidual << " px, median "
              << residuals[residuals.size() / 2] << " px, " << 100.0 * outlierFraction
              << " % of points beyond 2 px\n\n";
  }
  std::cout << "| | PP-5 | PP-3 | GP-3 |\n|---|---|---|---|\n";
  std::cout << "| Altitude error (mm) | " << cell(results[0].altitudeMm) << " | " << cell(results[1].altitudeMm)
            << " | " << cell(results[2].altitudeMm) << " |\n";
  std::cout << "| Pitch error (deg) | " << cell(results[0].pitchDeg) << " | " << cell(results[1].pitchDeg) << " | "
            << cell(results[2].pitchDeg) << " |\n";
  std::cout << "| Roll error (deg) | " << cell(results[0].rollDeg) << " | " << cell(results[1].rollDeg) << " | "
            << cell(results[2].rollDeg) << " |\n";
  std::cout << "| Failed frames | " << results[0].failures << " | " << results[1].failures << " | "
            << results[2].failures << " |\n\n";
  std::cout << "Published (Table 2, real hand-held sequence of 106 frames):\n"
               "| | PP-5 | PP-3 | GP-3 |\n|---|---|---|---|\n"
               "| Altitude error (mm) | 11.28 ± 5.91 | 7.90 ± 4.51 | 7.52 ± 4.12 |\n"
               "| Pitch error (deg) | 1.19 ± 0.86 | 0.67 ± 0.39 | 0.66 ± 0.37 |\n"
               "| Roll error (deg) | 1.25 ± 0.89 | 0.78 ± 0.41 | 0.76 ± 0.36 |\n";

  const int comparisonFailed =
      (opt.againstFirstPass ? compareWithFirstPass(dataset, results[2], firstPass.results[2]) : 0) +
      (opt.againstWholeFrame ? compareWithWholeFrame(dataset, results[2], wholeFrame.results[2]) : 0);
  if (!opt.check) {
    return comparisonFailed ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  // Bounds, from the error budget of the simulated sequence:
  // - detection: the stripe (3 px FWHM, 0.7 px blur, 1 grey-level noise, JPEG) is located with an RMS
  //   error of about 0.1 px (printed above); the synthetic study gives 1.5 mm and 0.25 deg at 0.5 px
  //   with 360 points, which scales to about 0.15 mm and 0.03 deg at 0.1 px with ~1800 points;
  // - calibration: laser.txt comes from vpLaserConicCalibration on simulated grid views (apex and
  //   axis errors of about 0.1 mm and 0.01 deg), which adds a sub-millimetre altitude bias.
  // Mean errors are therefore below 1 mm and 0.05 deg with the refit; without it (the best minimal
  // sample only) a few millimetres and 0.5 deg. The bounds keep a margin of about 3 over the latter, so
  // they hold for both settings, and stay under the published errors of the real sequence: a biased
  // detector, a convention error or a broken estimator exceeds them.
  const double maxMeanAltitudeMm = opt.localOptimisation ? 3.0 : 8.0;
  const double maxMeanAngleDeg = opt.localOptimisation ? 0.2 : 1.5;
  const double maxDetectionRmsPx = 0.5;
  int failed = 0;
  auto expect = [&failed](bool condition, const std::string &what) {
    std::cout << (condition ? "  [ok]   " : "  [FAIL] ") << what << std::endl;
    failed += condition ? 0 : 1;
  };
  if (truth.known) {
    expect(rmsResidual < maxDetectionRmsPx,
           "detection RMS error " + fmt(rmsResidual) + " px < " + fmt(maxDetectionRmsPx));
  }
  expect(minDetected >= 100, "at least 100 trace points detected in every frame (" + std::to_string(minDetected) + ")");
  for (size_t i = 0; i < methods().size(); ++i) {
    const MethodResult &r = results[i];
    const std::string name = methods()[i].name;
    expect(r.failures == 0, name + ": an estimate for every frame (" + std::to_string(r.failures) + " failures)");
    expect(meanStd(r.altitudeMm).mean < maxMeanAltitudeMm,
           name + ": mean altitude error " + cell(r.altitudeMm) + " mm < " + fmt(maxMeanAltitudeMm));
    expect(meanStd(r.pitchDeg).mean < maxMeanAngleDeg && meanStd(r.rollDeg).mean < maxMeanAngleDeg,
           name + ": mean pitch " + cell(r.pitchDeg) + " and roll " + cell(r.rollDeg) + " deg < " +
               fmt(maxMeanAngleDeg));
  }
  std::cout << (failed ? "CHECK FAILED" : "All checks passed") << std::endl;
  return failed || comparisonFailed ? EXIT_FAILURE : EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpRunProgram(argc, argv, commandLine, run); }
