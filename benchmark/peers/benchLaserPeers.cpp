/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchLaserPeers.cpp
  \brief Laser-conic estimators on 1000-point frames (PLANE_PAIR, PP-5, PP-3, GP-3 at 0-75 %
  outliers) against an OpenCV ellipse fit + plane pair, and the whole 1600x1200 frame (detection +
  GP-3) against one cv::cvtColor BGR->HSV pass.

  The point frames come from an independent generator (vspLaserScene.h); the rendered frames from
  vpLaserConicSimulator. Without the laser_conic library (VSP_HAVE_LASER_CONIC undefined) only the
  OpenCV passes are timed.
*/
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpPlane.h>

#ifdef VSP_HAVE_LASER_CONIC
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>
#include <visp3/laser_conic/vpLaserConicSolvers.h>
#endif

#include "benchTable.h"
#include "vspBenchUtils.h"
#include "vspLaserScene.h"

namespace
{
//! One 1000-point frame and its ground truth, in the types of every method.
struct LaserFrame
{
  Eigen::Vector4d truth;
  std::vector<vpImagePoint> points;
  std::vector<cv::Point2f> cvPoints;
};

std::vector<LaserFrame> makeFrames(const vspBench::LaserRig &rig, unsigned int seed, int count, double outlierRatio,
                                   int points = 1000)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> altitude(0.8, 3.0), tilt(-15.0 * M_PI / 180.0, 15.0 * M_PI / 180.0);
  std::vector<LaserFrame> frames;
  while (static_cast<int>(frames.size()) < count) {
    LaserFrame f;
    f.truth = vspBench::groundPlane(altitude(rng), tilt(rng), tilt(rng));
    const std::vector<Eigen::Vector2d> uv = vspBench::traceFrame(rig, f.truth, points, 0.5, outlierRatio, rng);
    if (static_cast<int>(uv.size()) < points) {
      continue;
    }
    for (const Eigen::Vector2d &p : uv) {
      f.points.emplace_back(p.y(), p.x());
      f.cvPoints.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
    frames.push_back(f);
  }
  return frames;
}

//! The success criterion of the benchmark: altitude within 1 cm and normal within 1 deg.
bool planeIsGood(const Eigen::Vector4d &estimate, const Eigen::Vector4d &truth)
{
  double angle = 0.0, offset = 0.0;
  vspBench::planeErrors(estimate, truth, angle, offset);
  return std::isfinite(angle) && std::isfinite(offset) && angle < M_PI / 180.0 && offset < 0.01;
}

/*!
  Symmetric pixel conic of an OpenCV rotated rectangle (full axes \e size, angle in degrees),
  scaled so that its largest coefficient is of order one.
*/
Eigen::Matrix3d conicOfRotatedRect(const cv::RotatedRect &box)
{
  const double a = 0.5 * box.size.width, b = 0.5 * box.size.height, theta = box.angle * M_PI / 180.0;
  const Eigen::Matrix2d Rot = Eigen::Rotation2Dd(theta).toRotationMatrix();
  const Eigen::Matrix2d A = Rot * Eigen::Vector2d(1.0 / (a * a), 1.0 / (b * b)).asDiagonal() * Rot.transpose();
  const Eigen::Vector2d c(box.center.x, box.center.y);
  Eigen::Matrix3d C;
  C.topLeftCorner<2, 2>() = A;
  C.topRightCorner<2, 1>() = -A * c;
  C.bottomLeftCorner<1, 2>() = (-A * c).transpose();
  C(2, 2) = c.dot(A * c) - 1.0;
  return C;
}

[[maybe_unused]] double timeFitEllipseOnly(const std::vector<LaserFrame> &frames, bool direct)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        const cv::RotatedRect box = direct ? cv::fitEllipseDirect(frames[i].cvPoints)
                                           : cv::fitEllipse(frames[i].cvPoints);
        vspBench::consume(box.size.width);
      },
      static_cast<int>(frames.size()), 9, 0.2);
}

#ifdef VSP_HAVE_LASER_CONIC
vpHomogeneousMatrix toHomogeneous(const Eigen::Matrix3d &R, const Eigen::Vector3d &t)
{
  vpHomogeneousMatrix M;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      M[r][c] = R(r, c);
    }
    M[r][3] = t(r);
  }
  return M;
}

vpLaserSolvers::LaserCone coneOf(const vspBench::LaserRig &rig)
{
  vpLaserSolvers::LaserCone cone;
  cone.cRl = rig.cRl;
  cone.apex = rig.apex;
  cone.halfAngle = rig.halfAngle;
  return cone;
}

vpLaserConicPose makeEstimator(const vspBench::LaserRig &rig)
{
  vpLaserConicPose estimator;
  estimator.setCameraParameters(vpCameraParameters(rig.px, rig.py, rig.u0, rig.v0));
  estimator.setLaser(2.0 * rig.halfAngle, toHomogeneous(rig.cRl, rig.apex));
  return estimator;
}

Eigen::Vector4d toEigen(const vpPlane &p) { return Eigen::Vector4d(p.getA(), p.getB(), p.getC(), p.getD()); }

//! Median time of GP-3 per frame with the given estimator settings.
double timeGp3(vpLaserConicPose &estimator, const std::vector<LaserFrame> &frames)
{
  return vspBench::medianNsPerCall(
      [&](int i) {
        vpPlane plane;
        estimator.computePlane(frames[i].points, vpLaserConicPose::GP3, plane);
        vspBench::consume(plane.getD());
      },
      static_cast<int>(frames.size()), 5, 0.2);
}

//! OpenCV ellipse fit, conic mapped to normalized coordinates (c_n = K^T c_px K), then our plane pair.
bool baselinePlane(const vspBench::LaserRig &rig, const LaserFrame &f, bool direct, Eigen::Vector4d &plane)
{
  const cv::RotatedRect box = direct ? cv::fitEllipseDirect(f.cvPoints) : cv::fitEllipse(f.cvPoints);
  if (!(box.size.width > 0.0f && box.size.height > 0.0f)) {
    return false;
  }
  Eigen::Matrix3d K;
  K << rig.px, 0.0, rig.u0, 0.0, rig.py, rig.v0, 0.0, 0.0, 1.0;
  const Eigen::Matrix3d c = K.transpose() * conicOfRotatedRect(box) * K;
  return vpLaserSolvers::planePair(c / c.norm(), coneOf(rig), plane);
}

const char *methodName(vpLaserConicPose::vpLaserConicMethod m)
{
  switch (m) {
  case vpLaserConicPose::PLANE_PAIR:
    return "PLANE_PAIR";
  case vpLaserConicPose::PP5:
    return "PP-5";
  case vpLaserConicPose::PP3:
    return "PP-3";
  default:
    return "GP-3";
  }
}

void renderFrames(const vspBench::LaserRig &rig, unsigned int seed, int count,
                  const vpLaserConicSimulator::vpRenderSettings &settings, std::vector<vpImage<vpRGBa> > &images,
                  std::vector<Eigen::Vector4d> &truths)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> altitude(1.0, 2.5), tilt(-10.0 * M_PI / 180.0, 10.0 * M_PI / 180.0);
  vpLaserConicSimulator simulator;
  simulator.setCamera(vpCameraParameters(rig.px, rig.py, rig.u0, rig.v0), rig.width, rig.height);
  simulator.setLaser(2.0 * rig.halfAngle, toHomogeneous(rig.cRl, rig.apex));
  simulator.setSeed(seed);
  for (int i = 0; i < count; ++i) {
    const double h = altitude(rng), roll = tilt(rng), pitch = tilt(rng);
    // Ground frame: Z up towards the camera, the camera at height h, then the rig tilted by roll/pitch.
    const Eigen::Matrix3d tiltR =
        (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    const Eigen::Matrix3d flip = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    simulator.setGroundPose(toHomogeneous(tiltR * flip, tiltR * Eigen::Vector3d(0.0, 0.0, h)));
    vpImage<vpRGBa> I;
    simulator.render(I, settings);
    images.push_back(I);
    truths.push_back(vspBench::groundPlane(h, roll, pitch));
  }
}

//! The floors of the whole-frame benchmark: the simulator's dark tiles, a bright grey floor, a colourful mosaic.
std::vector<std::pair<std::string, vpLaserConicSimulator::vpRenderSettings> > benchFloors()
{
  vpLaserConicSimulator::vpRenderSettings dark, grey, mosaic;
  grey.floor = vpLaserConicSimulator::FLOOR_BRIGHT_GREY;
  grey.laserPower = 150.0;
  mosaic.floor = vpLaserConicSimulator::FLOOR_MOSAIC;
  mosaic.laserPower = 200.0;
  return {{"dark floor", dark}, {"bright grey floor", grey}, {"colourful floor", mosaic}};
}

//! Margin of the search regions of the ROI and tracking rows (pixels around the predicted trace).
constexpr double kRegionMargin = 20.0;

/*!
  \e detector with the previous frame's image conic as its search region, set before every frame as a
  tracking loop does. A zero matrix stands for a frame where GP-3 found no plane (zeros rather than an
  empty vpMatrix, which ViSP 3.5 copies from a null pointer) and leaves the whole frame searched.
*/
vpLaserConicDetector &withPreviousConic(vpLaserConicDetector &detector, const vpMatrix &conic)
{
  if (conic.frobeniusNorm() > 0.0)
    detector.setSearchRegion(conic, kRegionMargin);
  return detector;
}
#endif

constexpr auto row = benchRow; // the shared builder of benchTable.h
} // namespace

int runLaserProfileLoop(const std::string &methodName, double outlierRatio, int frames, int points, unsigned int seed,
                        bool oneFrame)
{
#ifdef VSP_HAVE_LASER_CONIC
  const vspBench::LaserRig rig = vspBench::defaultRig();
  const bool tracking = methodName.compare(0, 6, "track-") == 0;
  if (methodName.compare(0, 7, "detect-") == 0 || tracking) {
    // Detection + GP-3 on the whole-frame benchmark's frames; track-: with the image conic of each frame's
    // GP-3 estimate as the search region (the tracking rows).
    std::vector<std::pair<std::string, vpLaserConicSimulator::vpRenderSettings> > floors = benchFloors();
    const std::string floorName = methodName.substr(tracking ? 6 : 7);
    const size_t f = floorName == "dark" ? 0 : (floorName == "grey" ? 1 : 2);
    std::vector<vpImage<vpRGBa> > images;
    std::vector<Eigen::Vector4d> truths;
    renderFrames(rig, seed + 7, 6, floors[f].second, images, truths);
    std::vector<vpLaserConicDetector> detectors(images.size());
    std::vector<vpMatrix> conics(images.size(), vpMatrix(3, 3, 0.0)); // see withPreviousConic()
    vpLaserConicPose estimator = makeEstimator(rig);
    for (size_t i = 0; i < images.size() && tracking; ++i) {
      vpPlane plane;
      if (estimator.computePlane(detectors[i].detect(images[i]), vpLaserConicPose::GP3, plane))
        conics[i] = estimator.getImageConic();
    }
    int good = 0;
    size_t detected = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < frames; ++k) {
      // oneFrame: the first frame over and over, its profiles' pixels then stay in cache (the time without the
      // waits for memory that the frames in turn have).
      const size_t i = oneFrame ? 0 : static_cast<size_t>(k) % images.size();
      const std::vector<vpImagePoint> trace = withPreviousConic(detectors[i], conics[i]).detect(images[i]);
      detected += trace.size();
      vpPlane plane;
      try {
        good += estimator.computePlane(trace, vpLaserConicPose::GP3, plane) && planeIsGood(toEigen(plane), truths[i]);
      } catch (const vpException &) {
      }
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s, %s%s: %d/%d frames good, %.0f points per frame, %.3f ms per frame (wall clock)\n",
                methodName.c_str(), floors[f].first.c_str(), oneFrame ? ", one frame repeated" : "", good, frames,
                static_cast<double>(detected) / frames, ms / frames);
    return 0;
  }
  const std::vector<LaserFrame> data = makeFrames(rig, seed, frames, outlierRatio, points);
  vpLaserConicPose estimator = makeEstimator(rig);
  const vpLaserConicPose::vpLaserConicMethod method =
      methodName == "pp3"
          ? vpLaserConicPose::PP3
          : (methodName == "pp5" ? vpLaserConicPose::PP5
                                 : (methodName == "planepair" ? vpLaserConicPose::PLANE_PAIR : vpLaserConicPose::GP3));
  int good = 0;
  long trials = 0;
  for (const LaserFrame &f : data) {
    vpPlane plane;
    good += estimator.computePlane(f.points, method, plane) && planeIsGood(toEigen(plane), f.truth) ? 1 : 0;
    trials += estimator.getRansacTrials();
  }
  std::printf("%s at %.0f %% outliers: %d/%d frames good, %.1f RANSAC trials per frame\n", methodName.c_str(),
              100.0 * outlierRatio, good, frames, static_cast<double>(trials) / frames);
  return 0;
#else
  (void)methodName, (void)outlierRatio, (void)frames, (void)points, (void)seed, (void)oneFrame;
  return 1;
#endif
}

void runLaserBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick)
{
  const vspBench::LaserRig rig = vspBench::defaultRig();
  const int nFrames = quick ? 10 : 50;

  BenchTable table;
  table.title = "Circular laser: 1000-point frame";
  table.note = "1000 trace points (0.5 px noise) per frame, " + std::to_string(nFrames) +
               " seeded frames per outlier ratio (altitude 0.8-3 m, roll and pitch within 15 deg); "
               "time = median over repetitions of the mean time per frame; success = altitude error < 1 cm and "
               "normal error < 1 deg. Default settings (2 px threshold, 1000 trials max, p = 0.99). "
               "Ratio to GP-3 of the same outlier ratio.";
  for (double ratio : {0.0, 0.25, 0.5, 0.75}) {
    const std::vector<LaserFrame> frames =
        makeFrames(rig, seed + static_cast<unsigned int>(100 * ratio), nFrames, ratio);
    const std::string problem = std::to_string(static_cast<int>(100 * ratio)) + " % outliers";
    double referenceNs = 0.0;
    std::vector<BenchRow> group;
#ifdef VSP_HAVE_LASER_CONIC
    for (vpLaserConicPose::vpLaserConicMethod method :
         {vpLaserConicPose::GP3, vpLaserConicPose::PP3, vpLaserConicPose::PP5, vpLaserConicPose::PLANE_PAIR}) {
      vpLaserConicPose estimator = makeEstimator(rig);
      int good = 0;
      for (const LaserFrame &f : frames) {
        vpPlane plane;
        try {
          if (estimator.computePlane(f.points, method, plane) && planeIsGood(toEigen(plane), f.truth)) {
            ++good;
          }
        } catch (const vpException &) {
        }
      }
      const double ns = vspBench::medianNsPerCall(
          [&](int i) {
            vpPlane plane;
            try {
              estimator.computePlane(frames[i].points, method, plane);
            } catch (const vpException &) {
            }
            vspBench::consume(plane.getD());
          },
          static_cast<int>(frames.size()), 5, 0.2);
      if (method == vpLaserConicPose::GP3) {
        referenceNs = ns;
        if (ratio == 0.5) {
          targets.gp3At50 = ns;
        }
      }
      group.push_back(row(problem, std::string("ours ") + methodName(method), ns, 0.0, true,
                          static_cast<double>(good) / frames.size()));
    }
    for (bool direct : {false, true}) {
      int good = 0;
      for (const LaserFrame &f : frames) {
        Eigen::Vector4d plane;
        good += baselinePlane(rig, f, direct, plane) && planeIsGood(plane, f.truth) ? 1 : 0;
      }
      const double ns = vspBench::medianNsPerCall(
          [&](int i) {
            Eigen::Vector4d plane = Eigen::Vector4d::Zero();
            baselinePlane(rig, frames[i], direct, plane);
            vspBench::consume(plane(3));
          },
          static_cast<int>(frames.size()), 9, 0.2);
      group.push_back(row(problem,
                          direct ? "OpenCV fitEllipseDirect + our plane pair" : "OpenCV fitEllipse + our plane pair",
                          ns, 0.0, false, static_cast<double>(good) / frames.size()));
    }
#else
    group.push_back(row(problem, "OpenCV fitEllipse (fit only)", timeFitEllipseOnly(frames, false), 0.0, false, -1.0));
    group.push_back(
        row(problem, "OpenCV fitEllipseDirect (fit only)", timeFitEllipseOnly(frames, true), 0.0, false, -1.0));
#endif
    for (BenchRow &r : group) {
      r.referenceNs = referenceNs;
      table.rows.push_back(r);
    }
  }
#ifdef VSP_HAVE_LASER_CONIC
  {
    // The speed target: GP-3, robust, on a 1000-point trace with 1000 outliers (2000 points, 50 %),
    // against one non-robust cv::fitEllipse on the same 2000 points.
    const std::vector<LaserFrame> frames = makeFrames(rig, seed + 500, nFrames, 0.5, 2000);
    const std::string problem = "1000-point trace + 1000 outliers";
    vpLaserConicPose estimator = makeEstimator(rig);
    int good = 0;
    for (const LaserFrame &f : frames) {
      vpPlane plane;
      good += estimator.computePlane(f.points, vpLaserConicPose::GP3, plane) && planeIsGood(toEigen(plane), f.truth);
    }
    const double gp3 = timeGp3(estimator, frames);
    // The same without the scale-adaptive final stage (fixed-threshold final refit), for its cost.
    vpLaserConicPose fixed = makeEstimator(rig);
    fixed.setScaleAdaptive(false);
    const double gp3Fixed = timeGp3(fixed, frames);
    const double fit = timeFitEllipseOnly(frames, false);
    targets.gp3Vs2000FitEllipse = gp3 / fit;
    table.rows.push_back(row(problem, "ours GP3", gp3, gp3, true, static_cast<double>(good) / frames.size()));
    table.rows.push_back(row(problem, "ours GP3, fixed-threshold final refit", gp3Fixed, gp3, true, -1.0));
    table.rows.push_back(row(problem, "OpenCV fitEllipse (fit only, not robust)", fit, gp3, false, -1.0));
  }
#endif
  tables.push_back(table);

  runLaserFrameBenchmarks(tables, targets, seed, quick);
}

void runLaserFrameBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick)
{
  const vspBench::LaserRig rig = vspBench::defaultRig();
  BenchTable frame;
  frame.title = "Circular laser: whole 1600x1200 frame";
  frame.note = "Colour frames rendered by vpLaserConicSimulator (3 px stripe, noise 2, altitude 1-2.5 m) on three "
               "floors; ratio to one cv::cvtColor BGR->HSV pass over the same frame (already a cv::Mat), one "
               "thread; success = GP-3 altitude error < 1 cm and attitude error < 1 deg. ROI: search region of "
               "20 px around the trace detected in the same frame (as from the previous frame of a sequence). "
               "Previous conic: the image conic of the frame's GP-3 estimate as the search region, searched by "
               "the guided pass alone (tracking); each frame sets it (setSearchRegion), as a tracking loop does. "
               "Detection includes the conic-guided second pass (default). The two frame targets: ours and "
               "cvtColor timed in interleaved rounds over the same frames, the worst floor's median ratio with its "
               "quartiles (the medians of this table are taken seconds apart).";
  frame.ratioHeader = "Ratio to cvtColor";
#ifdef VSP_HAVE_LASER_CONIC
  for (const auto &floor : benchFloors()) {
    std::vector<vpImage<vpRGBa> > images;
    std::vector<Eigen::Vector4d> truths;
    renderFrames(rig, seed + 7, quick ? 2 : 6, floor.second, images, truths);
    std::vector<cv::Mat> bgr(images.size());
    for (size_t i = 0; i < images.size(); ++i) {
      vpImageConvert::convert(images[i], bgr[i]);
    }
    const int nImages = static_cast<int>(images.size());
    auto hsv = [&](int i) {
      cv::Mat converted;
      cv::cvtColor(bgr[i], converted, cv::COLOR_BGR2HSV);
      vspBench::consume(converted.at<cv::Vec3b>(0, 0)[0]);
    };
    const double cvtNs = vspBench::medianNsPerCall(hsv, nImages, 15, 0.5);
    vpLaserConicDetector detector;
    vpLaserConicPose estimator = makeEstimator(rig);
    const double detectNs = vspBench::medianNsPerCall(
        [&](int i) { vspBench::consume(static_cast<double>(detector.detect(images[i]).size())); }, nImages, 9, 0.5);
    // Full-frame detections: success rate, and the search regions of the ROI mode.
    int good = 0;
    std::vector<std::vector<vpImagePoint> > traces(images.size());
    for (int i = 0; i < nImages; ++i) {
      traces[i] = detector.detect(images[i]);
      vpPlane plane;
      try {
        good += estimator.computePlane(traces[i], vpLaserConicPose::GP3, plane) &&
                        planeIsGood(toEigen(plane), truths[i])
                    ? 1
                    : 0;
      } catch (const vpException &) {
      }
    }
    auto wholeOf = [&](vpLaserConicDetector &d, const vpImage<vpRGBa> &I) {
      vpPlane plane;
      try {
        estimator.computePlane(d.detect(I), vpLaserConicPose::GP3, plane);
      } catch (const vpException &) { // no ring: too few points
      }
      vspBench::consume(plane.getD());
    };
    auto whole = [&](vpLaserConicDetector &d, int i) { wholeOf(d, images[i]); };
    const double wholeNs = vspBench::medianNsPerCall([&](int i) { whole(detector, i); }, nImages, 9, 0.5);
    std::vector<vpLaserConicDetector> roi(images.size());
    for (int i = 0; i < nImages; ++i)
      if (!traces[i].empty())
        roi[i].setSearchRegion(traces[i], kRegionMargin);
    const double roiNs = vspBench::medianNsPerCall([&](int i) { whole(roi[i], i); }, nImages, 9, 0.5);
    // Tracking: the image conic of the frame's GP-3 estimate (as the previous frame's) is the prediction of
    // the guided pass, every line or every 3rd.
    std::vector<vpLaserConicDetector> tracked(images.size()), trackedSparse(images.size());
    std::vector<vpMatrix> conics(images.size(), vpMatrix(3, 3, 0.0)); // see withPreviousConic()
    for (int i = 0; i < nImages; ++i) {
      vpPlane plane;
      try {
        if (!traces[i].empty() && estimator.computePlane(traces[i], vpLaserConicPose::GP3, plane))
          conics[i] = estimator.getImageConic();
      } catch (const vpException &) {
      }
      trackedSparse[i].setTrackingStep(3);
    }
    // A tracked frame: the previous conic set as the search region, as a tracking loop does every frame.
    auto predicted = [&](vpLaserConicDetector &d, int i) -> vpLaserConicDetector & {
      return withPreviousConic(d, conics[i]);
    };
    const double trackNs =
        vspBench::medianNsPerCall([&](int i) { whole(predicted(tracked[i], i), i); }, nImages, 9, 0.5);
    const double trackSparseNs =
        vspBench::medianNsPerCall([&](int i) { whole(predicted(trackedSparse[i], i), i); }, nImages, 9, 0.5);
    // The tracking rows' two stages apart: the guided pass alone, and GP-3 alone on the points it returns.
    std::vector<std::vector<vpImagePoint> > trackedPoints(images.size());
    for (int i = 0; i < nImages; ++i)
      trackedPoints[i] = predicted(tracked[i], i).detect(images[i]);
    const double trackDetectNs = vspBench::medianNsPerCall(
        [&](int i) { vspBench::consume(static_cast<double>(predicted(tracked[i], i).detect(images[i]).size())); },
        nImages, 9, 0.5);
    const double trackGp3Ns = vspBench::medianNsPerCall(
        [&](int i) {
          vpPlane plane;
          try {
            estimator.computePlane(trackedPoints[i], vpLaserConicPose::GP3, plane);
          } catch (const vpException &) {
          }
          vspBench::consume(plane.getD());
        },
        nImages, 9, 0.5);
    // The same floor with the laser off (between pulses, out of range) and small red patches on it, as the hard
    // sequence's frames without the laser: no ring is located, and every search runs (the sample of rows, the
    // whole image, its retry with short chains).
    vpLaserConicSimulator::vpRenderSettings laserOff = floor.second;
    laserOff.laserOn = false;
    laserOff.clutter = 120;
    laserOff.clutterRadius = 2.5;
    std::vector<vpImage<vpRGBa> > offImages;
    std::vector<Eigen::Vector4d> offTruths;
    renderFrames(rig, seed + 7, nImages, laserOff, offImages, offTruths);
    vpLaserConicDetector offDetector;
    const double offNs = vspBench::medianNsPerCall([&](int i) { wholeOf(offDetector, offImages[i]); }, nImages, 9, 0.5);
    const std::string problem = "1600x1200, " + floor.first;
    frame.rows.push_back(row(problem, "OpenCV cvtColor BGR->HSV", cvtNs, cvtNs, false, -1.0));
    frame.rows.push_back(row(problem, "ours vpLaserConicDetector::detect", detectNs, cvtNs, true, -1.0));
    frame.rows.push_back(row(problem, "ours detect + GP-3", wholeNs, cvtNs, true, static_cast<double>(good) / nImages));
    frame.rows.push_back(row(problem, "ours detect (ROI 20 px) + GP-3", roiNs, cvtNs, true, -1.0));
    frame.rows.push_back(row(problem, "ours detect (previous conic, 20 px) + GP-3", trackNs, cvtNs, true, -1.0));
    frame.rows.push_back(
        row(problem, "ours detect (previous conic, 20 px, every 3rd line) + GP-3", trackSparseNs, cvtNs, true, -1.0));
    frame.rows.push_back(row(problem, "ours detect alone (previous conic, 20 px)", trackDetectNs, cvtNs, true, -1.0));
    frame.rows.push_back(row(problem, "ours GP-3 alone (previous conic's points)", trackGp3Ns, cvtNs, true, -1.0));
    frame.rows.push_back(row(problem, "ours detect + GP-3, laser off (120 red patches)", offNs, cvtNs, true, -1.0));
    // The targets: ours against cvtColor over the same frames in interleaved rounds (the tables' medians are
    // taken seconds apart, and their ratio moved by a third from run to run on a shared machine).
    const auto allFrames = [nImages](auto &&call) {
      return [nImages, &call]() {
        for (int i = 0; i < nImages; ++i)
          call(i);
      };
    };
    const auto againstCvtColor = [&](auto &&ours, double oursNs) {
      return vspBench::interleavedRatio(allFrames(ours), allFrames(hsv), quick ? 7 : 21,
                                        static_cast<int>(std::lround(cvtNs / oursNs)));
    };
    const auto worstOf = [](const vspBench::RatioRounds &a, const vspBench::RatioRounds &b) {
      return b.median > a.median ? b : a;
    };
    targets.wholeFrame = worstOf(targets.wholeFrame, againstCvtColor([&](int i) { whole(detector, i); }, wholeNs));
    targets.trackingFrame =
        worstOf(targets.trackingFrame, againstCvtColor([&](int i) { whole(predicted(tracked[i], i), i); }, trackNs));
    targets.laserOffFrame =
        worstOf(targets.laserOffFrame, againstCvtColor([&](int i) { wholeOf(offDetector, offImages[i]); }, offNs));
  }
  tables.push_back(frame);
#else
  (void)rig, (void)targets, (void)seed, (void)quick;
  tables.push_back(frame);
#endif
}
