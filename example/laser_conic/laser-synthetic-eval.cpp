/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example laser-synthetic-eval.cpp
  Synthetic evaluation of the circular-laser estimators PP-5, PP-3 and GP-3 (Sec. 7.1 of Boutteau et
  al., JMIV 2018): mean altitude / roll / pitch errors versus image noise (Fig. 7), intrinsic noise
  (Fig. 9), baseline noise (Fig. 10) and ground roughness (Fig. 11), and the outlier break-down
  ratio of each method (Table 1). Curves are written as CSV and PNG in the output directory.

  Each trial draws an altitude in [0.5, 1.5] m, roll and pitch in [-20, 20] deg and a yaw in
  [-180, 180] deg, simulates the trace with vpLaserConicSimulator (see laserRigSetup.h for the rig),
  perturbs one quantity, and runs the three estimators on the same points.
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "laserRigSetup.h"
#include "vpCommandLine.h"
#include "vpPngPlot.h"
#include "vpProgress.h"

namespace
{
//! Command line settings.
struct Options
{
  int trials = 1000;
  int outlierTrials = -1; //!< -1: same as trials
  unsigned int points = 360;
  unsigned int seed = 1;
  int ransacTrials = 1000;
  std::string output = "laser-synthetic-results";
  std::string only;
  bool quick = false;
  bool check = false;
  bool localOptimisation = true;
  double threshold = 2.0;           //!< minimum RANSAC threshold, pixels
  double calibrationNoise = 0.5;    //!< image noise (px) of the calibration-error studies (Fig. 9, 10)
  bool scaleAdaptive = true;        //!< vpLaserConicPose::setScaleAdaptive()
  std::string finalFit = "default"; //!< vpLaserConicPose::setFinalFit(): default, free, constrained, select
};

//! The methods compared by the paper, with their minimal sample size and plot colour.
struct Method
{
  vpLaserConicPose::vpLaserConicMethod id;
  std::string name;
  int sampleSize;
  vpColor color;
};

const std::vector<Method> &methods()
{
  static const std::vector<Method> list = {{vpLaserConicPose::PP5, "PP5", 5, vpColor::red},
                                           {vpLaserConicPose::PP3, "PP3", 3, vpColor::blue},
                                           {vpLaserConicPose::GP3, "GP3", 3, vpColor::darkGreen}};
  return list;
}

//! What the estimators are given in one trial.
struct TrialInput
{
  std::vector<vpImagePoint> points;
  vpCameraParameters cam;
  vpHomogeneousMatrix cMl;
  double threshold = 2.0; //!< RANSAC threshold, pixels
};

//! Errors of one estimate against the ground truth.
struct TrialError
{
  bool success = false;
  double altitude = 0.0; //!< metres, absolute
  double roll = 0.0;     //!< radians, absolute
  double pitch = 0.0;    //!< radians, absolute
  double normal = 0.0;   //!< angle between the estimated and true normals, radians
};

//! Ground truth of one trial.
struct Scenario
{
  vpPlane plane;
  double altitude = 0.0, roll = 0.0, pitch = 0.0;
};

double angleDifference(double a, double b) { return std::fabs(std::remainder(a - b, 2.0 * M_PI)); }

Scenario drawScenario(std::mt19937 &rng, vpLaserConicSimulator &sim)
{
  std::uniform_real_distribution<double> altitude(0.5, 1.5), tilt(vpMath::rad(-20.0), vpMath::rad(20.0)),
      yaw(-M_PI, M_PI);
  const double h = altitude(rng), roll = tilt(rng), pitch = tilt(rng);
  sim.setGroundPose(vspLaserRig::groundPose(h, roll, pitch, yaw(rng)));
  Scenario s;
  s.plane = sim.getGroundPlane();
  vpLaserConicPose::computeAltitudeRollPitch(s.plane, s.altitude, s.roll, s.pitch);
  return s;
}

TrialError evaluate(const Method &method, const TrialInput &input, const Scenario &truth, const Options &opt,
                    unsigned int ransacSeed)
{
  TrialError e;
  vpLaserConicPose estimator;
  estimator.setCameraParameters(input.cam);
  estimator.setLaser(vpMath::rad(vspLaserRig::kOpeningAngleDeg), input.cMl);
  estimator.setRansacThreshold(input.threshold);
  estimator.setRansacMaxTrials(opt.ransacTrials);
  estimator.setLocalOptimisation(opt.localOptimisation);
  estimator.setRansacSeed(ransacSeed);
  estimator.setScaleAdaptive(opt.scaleAdaptive);
  if (method.id == vpLaserConicPose::PP5) {
    // PP-5 has no constrained fit of its own: it stays the free-conic reference.
  } else if (opt.finalFit == "free") {
    estimator.setFinalFit(vpLaserConicPose::FINAL_FIT_FREE);
  } else if (opt.finalFit == "constrained") {
    estimator.setFinalFit(vpLaserConicPose::FINAL_FIT_CONSTRAINED);
  } else if (opt.finalFit == "select") {
    estimator.setFinalFit(vpLaserConicPose::FINAL_FIT_SELECT);
  } else if (opt.finalFit == "legacy") {
    // The estimators before the scale-adaptive stage: PP-3 ended with a free conic fit, GP-3 with the plane refit.
    estimator.setFinalFit(method.id == vpLaserConicPose::GP3 ? vpLaserConicPose::FINAL_FIT_CONSTRAINED
                                                             : vpLaserConicPose::FINAL_FIT_FREE);
    estimator.setArcCoverageThreshold(0.0);
  }
  vpPlane plane;
  try {
    if (!estimator.computePlane(input.points, method.id, plane)) {
      return e;
    }
  } catch (const vpException &) {
    return e; // e.g. too few points left in the image: counted as a failure
  }
  e.success = true;
  e.altitude = std::fabs(estimator.getAltitude() - truth.altitude);
  e.roll = angleDifference(estimator.getRoll(), truth.roll);
  e.pitch = angleDifference(estimator.getPitch(), truth.pitch);
  const double dot =
      plane.getA() * truth.plane.getA() + plane.getB() * truth.plane.getB() + plane.getC() * truth.plane.getC();
  const double norm =
      std::sqrt(plane.getA() * plane.getA() + plane.getB() * plane.getB() + plane.getC() * plane.getC());
  e.normal = std::acos(std::max(-1.0, std::min(1.0, dot / norm)));
  return e;
}

//! Mean errors of one method at one level of a curve study.
struct CurvePoint
{
  int trials = 0, failures = 0;
  double altitudeMm = 0.0, rollDeg = 0.0, pitchDeg = 0.0;
  double medianAltitudeMm = 0.0;
  double medianNormalDeg = 0.0; //!< median angle between the estimated and true ground normals
};

//! A curve study: the perturbation applied at each level, and the curves obtained.
struct CurveStudy
{
  std::string name;   //!< noise, intrinsics, baseline, roughness
  std::string figure; //!< paper figure
  std::string xLabel;
  std::vector<double> levels;
  //! Builds the estimator input of a trial at the given level (the ground pose is already set).
  std::function<TrialInput(double, vpLaserConicSimulator &, std::mt19937 &)> perturb;
  std::map<std::string, std::vector<CurvePoint> > curves; //!< per method, one entry per level
};

TrialInput exactInput(vpLaserConicSimulator &sim, unsigned int points, double roughness, double threshold)
{
  TrialInput in;
  in.threshold = threshold;
  in.points = sim.tracePoints(points, roughness);
  in.cam = vspLaserRig::camera();
  in.cMl = vspLaserRig::laserPose();
  return in;
}

//! The trace of the calibration studies (Fig. 9, 10): \e noise px of image noise on every point.
TrialInput calibrationStudyInput(vpLaserConicSimulator &sim, unsigned int points, double noise, double threshold)
{
  TrialInput in = exactInput(sim, points, 0.0, threshold);
  in.points = sim.addNoise(in.points, noise);
  return in;
}

//! The laser apex moved to \e apex (camera frame, metres), its orientation kept.
void moveApex(TrialInput &in, const vpTranslationVector &apex) { in.cMl.buildFrom(apex, in.cMl.getRotationMatrix()); }

std::vector<double> range(double first, double last, double step)
{
  std::vector<double> v;
  for (double x = first; x <= last + 1e-9; x += step) {
    v.push_back(x);
  }
  return v;
}

//! A study without its curves: \e quickLevels with --quick, \e levels otherwise.
CurveStudy makeStudy(const Options &opt, const std::string &name, const std::string &figure, const std::string &xLabel,
                     const std::vector<double> &quickLevels, const std::vector<double> &levels)
{
  CurveStudy study;
  study.name = name;
  study.figure = figure;
  study.xLabel = xLabel;
  study.levels = opt.quick ? quickLevels : levels;
  return study;
}

//! The apex moved by a study: move(apex, err), err() drawing one error in metres.
typedef std::function<vpTranslationVector(const vpTranslationVector &, const std::function<double()> &)> ApexMove;

/*!
  A laser-position study of the Fig. 9 and 10 protocol: the apex moved by \e move, err() drawing a
  normal error of the level's standard deviation (mm).
*/
CurveStudy apexStudy(const Options &opt, const std::string &name, const std::string &figure, const std::string &xLabel,
                     const ApexMove &move)
{
  CurveStudy study = makeStudy(opt, name, figure, xLabel, {0.0, 5.0, 10.0}, range(0.0, 10.0, 1.0));
  const unsigned int n = opt.points;
  const double threshold = opt.threshold, noise = opt.calibrationNoise;
  study.perturb = [n, threshold, noise, move](double sigmaMm, vpLaserConicSimulator &sim, std::mt19937 &rng) {
    TrialInput in = calibrationStudyInput(sim, n, noise, threshold);
    std::normal_distribution<double> err(0.0, sigmaMm * 1e-3);
    moveApex(in, move(in.cMl.getTranslationVector(), [&err, &rng]() { return err(rng); }));
    return in;
  };
  return study;
}

std::vector<CurveStudy> curveStudies(const Options &opt)
{
  const unsigned int n = opt.points;
  const double minThreshold = opt.threshold;
  std::vector<CurveStudy> studies;

  CurveStudy noise = makeStudy(opt, "noise", "Fig. 7", "image noise sigma (px)", {0.0, 1.0, 3.0}, range(0.0, 3.0, 0.5));
  noise.perturb = [n, minThreshold](double sigma, vpLaserConicSimulator &sim, std::mt19937 &) {
    TrialInput in = exactInput(sim, n, 0.0, minThreshold);
    in.points = sim.addNoise(in.points, sigma);
    // Perpendicular residuals of Gaussian noise stay within 3 sigma 99.7 % of the time.
    in.threshold = std::max(minThreshold, 3.0 * sigma);
    return in;
  };
  studies.push_back(noise);

  // Fig. 9 and 10 protocol: the points carry calibrationNoise px of image noise, the threshold stays opt.threshold.
  const double calibrationNoise = opt.calibrationNoise;
  CurveStudy intrinsics = makeStudy(opt, "intrinsics", "Fig. 9", "sigma of fx, fy, u0, v0 errors (px)",
                                    {0.0, 5.0, 20.0}, range(0.0, 20.0, 2.5));
  intrinsics.perturb = [n, minThreshold, calibrationNoise](double sigma, vpLaserConicSimulator &sim,
                                                           std::mt19937 &rng) {
    TrialInput in = calibrationStudyInput(sim, n, calibrationNoise, minThreshold);
    std::normal_distribution<double> err(0.0, 1.0);
    in.cam = vpCameraParameters(in.cam.get_px() + sigma * err(rng), in.cam.get_py() + sigma * err(rng),
                                in.cam.get_u0() + sigma * err(rng), in.cam.get_v0() + sigma * err(rng));
    return in;
  };
  studies.push_back(intrinsics);

  studies.push_back(apexStudy(opt, "baseline", "Fig. 10 (3 axes)", "sigma of the laser position error (mm)",
                              [](const vpTranslationVector &t, const std::function<double()> &err) {
                                return vpTranslationVector(t[0] + err(), t[1] + err(), t[2] + err());
                              }));
  // The paper's Fig. 10: noise on the extent of the baseline only (the apex moves along the baseline).
  studies.push_back(apexStudy(opt, "extent", "Fig. 10", "sigma of the baseline length error (mm)",
                              [](const vpTranslationVector &t, const std::function<double()> &err) {
                                const double length = t.frobeniusNorm();
                                const double scale = (length + err()) / length;
                                return vpTranslationVector(t[0] * scale, t[1] * scale, t[2] * scale);
                              }));

  CurveStudy roughness =
      makeStudy(opt, "roughness", "Fig. 11", "ground roughness sigma (mm)", {0.0, 5.0, 20.0}, range(0.0, 20.0, 2.5));
  roughness.perturb = [n, minThreshold](double sigmaMm, vpLaserConicSimulator &sim, std::mt19937 &) {
    return exactInput(sim, n, sigmaMm * 1e-3, minThreshold);
  };
  studies.push_back(roughness);
  return studies;
}

double median(std::vector<double> v)
{
  if (v.empty()) {
    return std::nan("");
  }
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void runCurveStudy(CurveStudy &study, const Options &opt)
{
  vpLaserConicSimulator sim;
  sim.setCamera(vspLaserRig::camera(), vspLaserRig::kWidth, vspLaserRig::kHeight);
  sim.setLaser(vpMath::rad(vspLaserRig::kOpeningAngleDeg), vspLaserRig::laserPose());
  vpProgress progress("laser-synthetic-eval: " + study.name + " trials",
                      study.levels.size() * static_cast<std::size_t>(opt.trials));
  for (size_t l = 0; l < study.levels.size(); ++l) {
    // One seed per (study, level): any level can be reproduced alone.
    const unsigned int levelSeed = opt.seed * 1000003u + static_cast<unsigned int>(l) * 7919u;
    std::mt19937 rng(levelSeed);
    sim.setSeed(levelSeed);
    std::map<std::string, std::vector<TrialError> > errors;
    for (int t = 0; t < opt.trials; ++t) {
      progress.update(l * static_cast<std::size_t>(opt.trials) + static_cast<std::size_t>(t));
      const Scenario truth = drawScenario(rng, sim);
      const TrialInput input = study.perturb(study.levels[l], sim, rng);
      for (const Method &m : methods()) {
        errors[m.name].push_back(evaluate(m, input, truth, opt, levelSeed + static_cast<unsigned int>(t)));
      }
    }
    for (const Method &m : methods()) {
      CurvePoint p;
      std::vector<double> altitudes, normals;
      for (const TrialError &e : errors[m.name]) {
        ++p.trials;
        if (!e.success) {
          ++p.failures;
          continue;
        }
        altitudes.push_back(e.altitude * 1e3);
        normals.push_back(vpMath::deg(e.normal));
        p.altitudeMm += e.altitude * 1e3;
        p.rollDeg += vpMath::deg(e.roll);
        p.pitchDeg += vpMath::deg(e.pitch);
      }
      const double ok = static_cast<double>(std::max<size_t>(1, altitudes.size()));
      p.altitudeMm /= ok;
      p.rollDeg /= ok;
      p.pitchDeg /= ok;
      p.medianAltitudeMm = median(altitudes);
      p.medianNormalDeg = median(normals);
      study.curves[m.name].push_back(p);
    }
    std::cout << "  " << study.name << " " << study.levels[l] << ":";
    for (const Method &m : methods()) {
      const CurvePoint &p = study.curves[m.name].back();
      std::cout << "  " << m.name << " alt " << std::setprecision(3) << p.altitudeMm << " mm, roll " << p.rollDeg
                << " deg, pitch " << p.pitchDeg << " deg, median normal " << p.medianNormalDeg << " deg, failures "
                << p.failures;
    }
    std::cout << std::endl;
  }
}

void writeCurveStudy(const CurveStudy &study, const Options &opt)
{
  const std::string csv = opt.output + "/" + study.name + ".csv";
  std::ofstream out(csv.c_str());
  out << "level,method,trials,failures,mean_altitude_error_mm,mean_roll_error_deg,mean_pitch_error_deg,"
         "median_altitude_error_mm,median_normal_error_deg\n";
  for (size_t l = 0; l < study.levels.size(); ++l) {
    for (const Method &m : methods()) {
      const CurvePoint &p = study.curves.at(m.name)[l];
      out << study.levels[l] << "," << m.name << "," << p.trials << "," << p.failures << "," << p.altitudeMm << ","
          << p.rollDeg << "," << p.pitchDeg << "," << p.medianAltitudeMm << "," << p.medianNormalDeg << "\n";
    }
  }
  const char *quantities[] = {"altitude", "roll", "pitch"};
  const char *units[] = {"mean altitude error (mm)", "mean roll error (deg)", "mean pitch error (deg)"};
  for (int q = 0; q < 3; ++q) {
    vpPngPlot plot(study.figure + ": " + quantities[q] + " error vs " + study.name, study.xLabel, units[q]);
    for (const Method &m : methods()) {
      std::vector<double> ys;
      for (const CurvePoint &p : study.curves.at(m.name)) {
        ys.push_back(q == 0 ? p.altitudeMm : (q == 1 ? p.rollDeg : p.pitchDeg));
      }
      plot.addCurve(m.name, study.levels, ys, m.color);
    }
    plot.write(opt.output + "/" + study.name + "_" + quantities[q] + ".png");
  }
  std::cout << "  wrote " << csv << " and " << study.name << "_{altitude,roll,pitch}.png" << std::endl;
}

// ---- Outlier break-down (Table 1) -----------------------------------------------------------------

//! Failure criterion of the break-down study (inliers are exact, so a correct estimate is exact).
const double kMaxAltitudeError = 0.01;       // metres
const double kMaxNormalError = M_PI / 180.0; // 1 degree
//! A method breaks down at the first outlier ratio where fewer than half of the trials succeed.
const double kBreakdownSuccessRate = 0.5;

struct OutlierStudy
{
  std::map<std::string, std::map<int, double> > successRate; //!< method -> outlier percent -> rate
  std::map<std::string, int> breakdown;                      //!< method -> first percent below 50 %, -1 if none
};

double successRate(const Method &m, int percent, const Options &opt)
{
  vpLaserConicSimulator sim;
  sim.setCamera(vspLaserRig::camera(), vspLaserRig::kWidth, vspLaserRig::kHeight);
  sim.setLaser(vpMath::rad(vspLaserRig::kOpeningAngleDeg), vspLaserRig::laserPose());
  // Same scenarios for every method at a given ratio.
  const unsigned int seed = opt.seed * 2000003u + static_cast<unsigned int>(percent) * 104729u;
  std::mt19937 rng(seed);
  sim.setSeed(seed);
  int successes = 0;
  for (int t = 0; t < opt.outlierTrials; ++t) {
    const Scenario truth = drawScenario(rng, sim);
    TrialInput in = exactInput(sim, opt.points, 0.0, opt.threshold);
    in.points = sim.addOutliers(in.points, percent / 100.0);
    const TrialError e = evaluate(m, in, truth, opt, seed + static_cast<unsigned int>(t));
    if (e.success && e.altitude <= kMaxAltitudeError && e.normal <= kMaxNormalError) {
      ++successes;
    }
  }
  return successes / static_cast<double>(opt.outlierTrials);
}

/*! Success probability predicted when the budget is the only limit: at least one of N samples of s
    points is outlier-free (a clean minimal sample gives the exact plane). */
double predictedRate(int sampleSize, int percent, int budget)
{
  const double w = 1.0 - percent / 100.0;
  return 1.0 - std::pow(1.0 - std::pow(w, sampleSize), budget);
}

OutlierStudy runOutlierStudy(const Options &opt)
{
  OutlierStudy study;
  for (const Method &m : methods()) {
    std::map<int, double> &rates = study.successRate[m.name];
    int coarseBreak = -1, bracketStart = 0;
    const int step = opt.quick ? 10 : 5;
    std::vector<int> coarse;
    for (int percent = 0; percent <= 95; percent += step) {
      coarse.push_back(percent);
    }
    if (coarse.back() != 95) {
      coarse.push_back(95);
    }
    int previous = 0;
    for (int percent : coarse) {
      rates[percent] = successRate(m, percent, opt);
      std::cout << "  outliers " << percent << " %: " << m.name << " success " << rates[percent] << " (predicted "
                << std::setprecision(3) << predictedRate(m.sampleSize, percent, opt.ransacTrials) << ")" << std::endl;
      if (coarseBreak < 0 && rates[percent] < kBreakdownSuccessRate) {
        coarseBreak = percent;
        bracketStart = previous;
      }
      previous = percent;
    }
    int breakdown = coarseBreak;
    // Refine to 1 % inside the bracket where the success rate crosses 50 %.
    if (coarseBreak > 0) {
      for (int percent = bracketStart + 1; percent < coarseBreak; ++percent) {
        rates[percent] = successRate(m, percent, opt);
        std::cout << "  outliers " << percent << " %: " << m.name << " success " << rates[percent] << std::endl;
        if (rates[percent] < kBreakdownSuccessRate) {
          breakdown = percent;
          break;
        }
      }
    }
    study.breakdown[m.name] = breakdown;
  }
  return study;
}

void writeOutlierStudy(const OutlierStudy &study, const Options &opt)
{
  std::ofstream out((opt.output + "/outliers.csv").c_str());
  out << "outlier_percent,method,success_rate,predicted_rate\n";
  vpPngPlot plot("Table 1: success rate vs outlier ratio (" + std::to_string(opt.ransacTrials) + " samples)",
                 "outlier ratio (%)", "success rate");
  plot.setYRange(0.0, 1.05);
  for (const Method &m : methods()) {
    std::vector<double> xs, ys, predicted;
    for (const auto &kv : study.successRate.at(m.name)) {
      out << kv.first << "," << m.name << "," << kv.second << ","
          << predictedRate(m.sampleSize, kv.first, opt.ransacTrials) << "\n";
      xs.push_back(kv.first);
      ys.push_back(kv.second);
      predicted.push_back(predictedRate(m.sampleSize, kv.first, opt.ransacTrials));
    }
    plot.addCurve(m.name, xs, ys, m.color);
    plot.addPoints(m.name + " predicted", xs, predicted, m.color);
  }
  plot.write(opt.output + "/outliers.png");

  std::cout << "\nTable 1: outlier ratio at which each method starts failing\n"
            << "(failure: no plane, altitude error > 1 cm or normal error > 1 deg; breakdown: first ratio whose\n"
            << " success rate over " << opt.outlierTrials << " trials is below 50 %; " << opt.points
            << " trace points, exact inliers, outliers uniform in the image,\n RANSAC budget " << opt.ransacTrials
            << " samples with the adaptive stop at p = 0.99, threshold " << opt.threshold << " px"
            << (opt.localOptimisation ? "" : ", no refit") << ")\n\n";
  std::cout << "| Method | Breakdown outlier ratio |\n|---|---|\n";
  for (const Method &m : methods()) {
    const int b = study.breakdown.at(m.name);
    std::cout << "| " << m.name << " | " << (b < 0 ? std::string("> 95") : std::to_string(b)) << " % |\n";
  }
  std::cout << "\nPublished (Table 1 of the paper): PP-5 75 %, PP-3 86 %, GP-3 85 %." << std::endl;
}

// ---- Checks (--check) ----------------------------------------------------------------------------

int checkFailures = 0;
void expect(bool condition, const std::string &what)
{
  std::cout << (condition ? "  [ok]   " : "  [FAIL] ") << what << std::endl;
  if (!condition) {
    ++checkFailures;
  }
}

std::string fmt(double x)
{
  std::ostringstream ss;
  ss << std::setprecision(3) << x;
  return ss.str();
}

bool isCalibrationStudy(const CurveStudy &study)
{
  return study.name == "intrinsics" || study.name == "baseline" || study.name == "extent";
}

void checkCurveStudy(const CurveStudy &study, const Options &opt)
{
  const bool noisyLevelZero = isCalibrationStudy(study) && opt.calibrationNoise > 0.0;
  for (const Method &m : methods()) {
    const std::vector<CurvePoint> &c = study.curves.at(m.name);
    // Level 0 is exact data with exact calibration: the solvers are exact up to rounding (the
    // calibration studies add image noise at every level: there level 0 is the noise floor).
    if (!noisyLevelZero) {
      expect(c.front().failures == 0 && c.front().altitudeMm < 1e-3,
             study.name + " " + m.name + ": exact at level 0 (" + fmt(c.front().altitudeMm) + " mm)");
    }
    // The error must grow with the perturbation: the last level is worse than the first non-zero one.
    expect(c.back().altitudeMm > c[1].altitudeMm && c[1].altitudeMm > c.front().altitudeMm,
           study.name + " " + m.name + ": altitude error increases (" + fmt(c.front().altitudeMm) + " < " +
               fmt(c[1].altitudeMm) + " < " + fmt(c.back().altitudeMm) + " mm)");
    // An error on the baseline length alone scales the reconstruction: it moves the altitude, hardly
    // the attitude (the paper's Fig. 10), which stays at the noise floor.
    if (study.name != "extent") {
      expect(c.back().rollDeg + c.back().pitchDeg > c.front().rollDeg + c.front().pitchDeg,
             study.name + " " + m.name + ": attitude error increases");
    }
  }
  if (isCalibrationStudy(study)) {
    // With the scale-adaptive final fit, the 3-point methods tolerate calibration errors as well as
    // PP5 does (the paper's finding): their median normal error stays within 1.5 times PP5's.
    for (size_t l = 1; l < study.levels.size(); ++l) {
      const double pp5 = study.curves.at("PP5")[l].medianNormalDeg;
      for (const std::string name : {"PP3", "GP3"}) {
        const double e = study.curves.at(name)[l].medianNormalDeg;
        expect(e <= 1.5 * pp5, study.name + " " + fmt(study.levels[l]) + ": " + name + " median normal error " +
                                   fmt(e) + " deg <= 1.5 x PP5's " + fmt(pp5) + " deg");
      }
    }
  }
  if (study.name == "noise") {
    // At 1 px the paper's errors are a few mm and a fraction of a degree; 2 cm / 1 deg catches a broken solver.
    for (const Method &m : methods()) {
      const CurvePoint &p = study.curves.at(m.name)[1];
      expect(p.altitudeMm < 20.0 && p.rollDeg < 1.0 && p.pitchDeg < 1.0,
             "noise " + m.name + " at " + fmt(study.levels[1]) + " px: alt " + fmt(p.altitudeMm) + " mm < 20, roll " +
                 fmt(p.rollDeg) + ", pitch " + fmt(p.pitchDeg) + " deg < 1");
    }
  }
}

void checkOutlierStudy(const OutlierStudy &study)
{
  for (const Method &m : methods()) {
    expect(study.successRate.at(m.name).at(0) == 1.0, m.name + ": every trial succeeds without outliers");
  }
  // With 1000 samples a clean 3-point sample is drawn at 50 % outliers with probability 1 - 0.875^1000.
  for (const std::string name : {"PP3", "GP3"}) {
    const double rate = study.successRate.at(name).at(50);
    expect(rate >= 0.9, name + " survives 50 % outliers (success " + fmt(rate) + " >= 0.9)");
  }
  // Needing 5 clean points, PP5 must break down before the 3-point methods.
  expect(study.breakdown.at("PP5") >= 0 && study.breakdown.at("PP5") < study.breakdown.at("GP3") &&
             study.breakdown.at("PP5") < study.breakdown.at("PP3"),
         "PP5 breaks down before PP3 and GP3");
}

//! Declares the options of the program; \e opt receives their values.
vpCommandLine commandLine(Options &opt)
{
  vpCommandLine cli("[--trials N] [--outlier-trials N] [--points N] [--seed S] [--ransac-trials N] [--threshold PX]\n"
                    "       [--output DIR] [--only noise|outliers|intrinsics|baseline|extent|roughness]\n"
                    "       [--no-local-optimisation] [--quick] [--check]",
                    "Synthetic evaluation of PP5, PP3 and GP3 (Boutteau et al. 2018, Sec. 7.1).");
  cli.addInt("--trials", opt.trials, "N", "trials per level of the error curves (default 1000)", 1);
  cli.addInt("--outlier-trials", opt.outlierTrials, "N", "trials per outlier ratio (default: --trials)", 1);
  cli.addUnsigned("--points", opt.points, "N", "laser rays per frame, at least 20 (default 360, one per degree)", 20);
  cli.addUnsigned("--seed", opt.seed, "S", "random seed (default 1)");
  cli.addInt("--ransac-trials", opt.ransacTrials, "N", "RANSAC sample budget (default 1000)", 1);
  vspLaserRig::addEstimatorOptions(cli, opt.threshold, opt.localOptimisation,
                                   "; the noise study uses max(PX, 3 sigma of the noise)");
  cli.addDouble("--calibration-noise", opt.calibrationNoise, "PX",
                "image noise of the intrinsics / baseline / extent studies (default 0.5, the paper's)",
                vpCommandLine::NON_NEGATIVE);
  cli.addFlag("--no-scale-adaptive", opt.scaleAdaptive,
              "final fit on the RANSAC inliers at the fixed threshold (vpLaserConicPose::setScaleAdaptive(false))",
              false);
  cli.addChoice("--final-fit", opt.finalFit, {"default", "free", "constrained", "select", "legacy"}, "FIT",
                "final fit of PP3 and GP3 (vpLaserConicPose::setFinalFit(); legacy: PP3 free, GP3 constrained, "
                "no arc test)");
  cli.addString("--output", opt.output, "DIR",
                "directory of the CSV and PNG results (default laser-synthetic-results)");
  cli.addChoice("--only", opt.only, {"noise", "outliers", "intrinsics", "baseline", "extent", "roughness"}, "STUDY",
                "run one study");
  cli.addFlag("--quick", opt.quick, "30 trials per point, 3 levels per curve, outlier ratios by 10 % (for ctest)");
  cli.addFlag("--check", opt.check, "exit non-zero when a sanity assertion fails");
  return cli;
}

//! Trial counts implied by --quick and by an absent --outlier-trials.
void resolveTrialCounts(const vpCommandLine &cli, Options &opt)
{
  if (opt.quick) {
    opt.trials = cli.given("--trials") ? opt.trials : 30;
    opt.outlierTrials = cli.given("--outlier-trials") ? opt.outlierTrials : 30;
  }
  if (opt.outlierTrials < 0) {
    opt.outlierTrials = opt.trials;
  }
}
//! The program's work once its options are read; returns its exit status.
int run(Options &opt, const vpCommandLine &cli)
{
  resolveTrialCounts(cli, opt);
  try {
    vpIoTools::makeDirectory(opt.output);
    std::cout << "Rig: " << vspLaserRig::kWidth << "x" << vspLaserRig::kHeight << " camera, f = " << vspLaserRig::kFocal
              << " px; laser " << vspLaserRig::kOpeningAngleDeg << " deg, apex (0.15, 0.02, 0) m, axis tilted 8 deg;\n"
              << "altitude U[0.5, 1.5] m, roll and pitch U[-20, 20] deg; " << opt.points << " rays per frame; "
              << opt.trials << " trials per curve level; seed " << opt.seed << ";\nRANSAC: " << opt.ransacTrials
              << " samples at most, adaptive stop p = 0.99, threshold max(" << opt.threshold
              << " px, 3 sigma of the image noise), "
              << (opt.localOptimisation ? "least-squares refit on the inliers" : "no refit on the inliers")
              << std::endl;

    std::vector<CurveStudy> studies = curveStudies(opt);
    for (CurveStudy &study : studies) {
      if (!opt.only.empty() && opt.only != study.name) {
        continue;
      }
      std::cout << "\n" << study.figure << ": " << study.name << std::endl;
      runCurveStudy(study, opt);
      writeCurveStudy(study, opt);
      if (opt.check) {
        checkCurveStudy(study, opt);
      }
    }
    if (opt.only.empty() || opt.only == "outliers") {
      std::cout << "\nTable 1: outlier break-down" << std::endl;
      const OutlierStudy study = runOutlierStudy(opt);
      writeOutlierStudy(study, opt);
      if (opt.check) {
        checkOutlierStudy(study);
      }
    }
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  if (opt.check) {
    std::cout << (checkFailures ? "\nCHECK FAILED: " : "\nAll checks passed (") << checkFailures
              << (checkFailures ? " assertion(s)" : " failures)") << std::endl;
    return checkFailures ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpRunProgram(argc, argv, commandLine, run); }
