/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example laser-drift-demo.cpp
  A simulated flight whose laser mount is knocked by 1 degree halfway: GP3 altitudes go wrong, the drift
  monitor (vpLaserConicDriftMonitor) raises "calibration drift suspected", the laser is self-calibrated
  (vpLaserConicSelfCalibration) on the next 60 frames with the previous calibration's apex held,
  handed to the estimator, and the errors come back down. Writes two PNG plots (altitude errors, drift
  statistic) and a CSV of the frames; --write-sequence also writes the inputs of
  vsp-laser-calibrate --from-sequence (camera, previous calibration, points of the frames after the knock).

  \verbatim
  laser-drift-demo [--output DIR] [--frames N] [--knock-frame K] [--knock-deg D] [--seed N] [--write-sequence DIR]
                   [--check]
  \endverbatim
  --check: exit 1 unless the knock is detected within 30 frames, the self-calibrated axis lies within 3 of
  its standard deviations (vpLaserConicSelfCalibration::getAxisStdDeviation()) of the knocked laser's, and
  the altitude error after the self-calibration is under half that of the knocked frames. (Its altitude
  error follows the axis's, about 126 mm per degree over this flight: over seeds 1-20 the axis came out
  0.0004-0.024 degree off for a standard deviation of 0.0096, the altitude 0.39-3.09 mm RMS against 0.44-0.57
  before the knock and 9.0-9.1 knocked; a bound of 3 times the error before the knock failed seeds 2 and 16.)
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpLaserConicDriftMonitor.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "laserRigSetup.h"
#include "vpCommandLine.h"
#include "vpLaserRigIo.h"
#include "vpPngPlot.h"

namespace
{
struct Options
{
  std::string output = "laser-drift-demo", sequence;
  unsigned int frames = 240, knockFrame = 120, calibrationFrames = 60;
  double knockDeg = 1.0;
  unsigned int seed = 1;
  bool check = false;
};

//! The flight: smooth roll, pitch (+-12, +-10 degrees) and altitude (0.75-1.25 m).
void attitude(unsigned int k, double &altitude, double &roll, double &pitch)
{
  altitude = 1.0 + 0.25 * std::sin(2.0 * M_PI * k / 80.0);
  roll = vpMath::rad(12.0) * std::sin(2.0 * M_PI * k / 60.0);
  pitch = vpMath::rad(10.0) * std::sin(2.0 * M_PI * k / 45.0 + 1.0);
}

struct Record
{
  double error = std::numeric_limits<double>::quiet_NaN(); // GP3 altitude error, mm
  double statistic = std::numeric_limits<double>::quiet_NaN();
  bool alarm = false, recalibrated = false;
};

int run(int argc, char **argv)
{
  Options o;
  vpCommandLine cli("[--output DIR] [--frames N] [--knock-frame K] [--knock-deg D] [--seed N] [--write-sequence DIR] "
                    "[--check]",
                    "A flight whose laser mount is knocked halfway: drift detected, laser self-calibrated, errors "
                    "restored.");
  cli.addString("--output", o.output, "DIR", "folder of the plots and the CSV (default laser-drift-demo)");
  cli.addUnsigned("--frames", o.frames, "N", "frames of the flight (default 240)", 100, 100000);
  cli.addUnsigned("--knock-frame", o.knockFrame, "K", "frame of the knock (default 120)", 30);
  cli.addDouble("--knock-deg", o.knockDeg, "D", "rotation of the laser by the knock, degrees (default 1)");
  cli.addUnsigned("--seed", o.seed, "N", "seed of the trace points' noise (default 1)", 0, 4294967295u);
  cli.addString("--write-sequence", o.sequence, "DIR", "also write camera.xml, laser_previous.yaml, points.csv");
  cli.addFlag("--check", o.check, "exit 1 unless the knock is detected and the errors restored");
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (o.knockFrame + o.calibrationFrames + 20 > o.frames)
    return cli.fail("--knock-frame leaves too few frames after the knock");

  const vpCameraParameters cam =
      vpLaserConicSimulator::fitInverseDistortion(vpCameraParameters(vspLaserRig::kFocal, vspLaserRig::kFocal,
                                                                     vspLaserRig::kWidth / 2.0,
                                                                     vspLaserRig::kHeight / 2.0, 0.0, 0.1),
                                                  vspLaserRig::kWidth, vspLaserRig::kHeight);
  const double A = vpMath::rad(vspLaserRig::kOpeningAngleDeg);
  const vpHomogeneousMatrix calibrated = vspLaserRig::laserPose();
  const vpHomogeneousMatrix knocked = calibrated * vpHomogeneousMatrix(0, 0, 0, vpMath::rad(o.knockDeg), 0, 0);
  vpLaserConicSimulator sim;
  sim.setCamera(cam, vspLaserRig::kWidth, vspLaserRig::kHeight);
  sim.setSeed(o.seed);
  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);
  estimator.setLaser(A, calibrated);
  vpLaserConicDriftMonitor monitor;
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(cam);
  // A knock turns the mount: the previous apex is kept (it is also the scale) and the axis re-estimated.
  selfcal.setApexHeld(true);
  std::vector<Record> records(o.frames);
  std::vector<std::vector<vpImagePoint> > afterKnock;
  int detected = -1, recalibrated = -1;
  double axisError = std::numeric_limits<double>::quiet_NaN(), axisStd = std::numeric_limits<double>::quiet_NaN();
  bool collecting = false;
  for (unsigned int k = 0; k < o.frames; ++k) {
    double h, roll, pitch;
    attitude(k, h, roll, pitch);
    sim.setLaser(A, k < o.knockFrame ? calibrated : knocked);
    sim.setGroundPose(vspLaserRig::groundPose(h, roll, pitch));
    const std::vector<vpImagePoint> points = sim.addNoise(sim.tracePoints(300), 0.5);
    if (k >= o.knockFrame)
      afterKnock.push_back(points);
    vpPlane plane;
    if (points.size() >= 5 && estimator.computePlane(points, vpLaserConicPose::GP3, plane)) {
      records[k].error = 1000.0 * (estimator.getAltitude() - sim.getGroundPlane().getD());
      monitor.addFrame(estimator);
      records[k].statistic = monitor.getStatistic();
    }
    records[k].alarm = monitor.getStatus() == vpLaserConicDriftMonitor::DRIFT_SUSPECTED;
    if (records[k].alarm && !collecting && recalibrated < 0) {
      if (detected < 0)
        detected = static_cast<int>(k);
      collecting = true;
      selfcal.clearFrames();
    }
    if (collecting && points.size() >= 5)
      selfcal.addFrame(points);
    if (collecting && selfcal.getNbFrames() == o.calibrationFrames) {
      collecting = false;
      selfcal.setLaser(A, calibrated); // the previous calibration is the initial guess
      vpHomogeneousMatrix cMl;
      double angle = 0.0;
      if (selfcal.compute(cMl, angle)) {
        estimator.setLaser(angle, cMl);
        monitor.reset();
        recalibrated = static_cast<int>(k);
        records[k].recalibrated = true;
        axisError = std::acos(std::min(1.0, vpColVector::dotProd(cMl.getRotationMatrix().getCol(2),
                                                                 knocked.getRotationMatrix().getCol(2))));
        axisStd = selfcal.getAxisStdDeviation();
        std::cout << "frame " << k << ": self-calibrated on " << o.calibrationFrames << " frames, axis off the knocked "
                  << "laser by " << vpMath::deg(axisError) << " deg (its standard deviation " << vpMath::deg(axisStd)
                  << " deg)" << std::endl;
      } else {
        std::cout << "frame " << k
                  << ": self-calibration failed: " << vpLaserConicSelfCalibration::getStatusMessage(selfcal.getStatus())
                  << " (" << selfcal.getStatusDetails() << ")" << std::endl;
      }
    }
  }

  // Summaries: RMS altitude error before the knock, between knock and recalibration, after it.
  auto rms = [&](unsigned int from, unsigned int to) {
    double s = 0.0;
    unsigned int n = 0;
    for (unsigned int k = from; k < to && k < o.frames; ++k)
      if (std::isfinite(records[k].error)) {
        s += records[k].error * records[k].error;
        ++n;
      }
    return n ? std::sqrt(s / n) : std::numeric_limits<double>::quiet_NaN();
  };
  const double before = rms(0, o.knockFrame);
  const double during = rms(o.knockFrame, recalibrated > 0 ? recalibrated + 1 : o.frames);
  const double after = recalibrated > 0 ? rms(recalibrated + 1, o.frames) : std::numeric_limits<double>::quiet_NaN();
  std::cout << "knock at frame " << o.knockFrame << " (" << o.knockDeg << " deg); drift suspected at frame " << detected
            << "; recalibrated at frame " << recalibrated << std::endl;
  std::cout << "GP3 altitude RMS error: before the knock " << before << " mm, knocked " << during
            << " mm, after the self-calibration " << after << " mm" << std::endl;

  vpIoTools::makeDirectory(o.output);
  std::ofstream csv((o.output + "/frames.csv").c_str());
  csv << "frame,altitude_error_mm,drift_statistic,drift_suspected,recalibrated\n";
  std::vector<double> x, e, xs, st, thr, xa, ya;
  for (unsigned int k = 0; k < o.frames; ++k) {
    csv << k << "," << records[k].error << "," << records[k].statistic << "," << records[k].alarm << ","
        << records[k].recalibrated << "\n";
    if (std::isfinite(records[k].error)) {
      x.push_back(k);
      e.push_back(records[k].error);
    }
    if (std::isfinite(records[k].statistic) && records[k].statistic > 0.0) {
      xs.push_back(k);
      st.push_back(records[k].statistic);
      thr.push_back(monitor.getThreshold());
    }
    if (records[k].alarm) {
      xa.push_back(k);
      ya.push_back(0.0);
    }
  }
  if (!csv) {
    std::cerr << argv[0] << ": " << o.output << "/frames.csv cannot be written" << std::endl;
    return EXIT_FAILURE;
  }
  vpPngPlot errors("GP3 altitude error; mount knocked by " + std::to_string(o.knockDeg).substr(0, 4) +
                       " deg at frame " + std::to_string(o.knockFrame),
                   "frame", "altitude error (mm)");
  errors.addCurve("altitude error", x, e, vpColor::blue);
  errors.addPoints("drift suspected", xa, ya, vpColor::red);
  errors.write(o.output + "/drift-demo-errors.png");
  vpPngPlot statistic("Drift statistic over a window of 20 frames", "frame", "statistic (log)");
  statistic.setLogY(true);
  statistic.addCurve("window statistic", xs, st, vpColor::blue);
  statistic.addCurve("threshold (0.1 % false alarms)", xs, thr, vpColor::red);
  statistic.write(o.output + "/drift-demo-statistic.png");
  std::cout << "written " << o.output << "/drift-demo-errors.png, drift-demo-statistic.png, frames.csv" << std::endl;

  if (!o.sequence.empty()) {
    vpIoTools::makeDirectory(o.sequence);
    std::string error;
    vpLaserCalibrationData previous;
    previous.openingAngle = A;
    previous.cMl = calibrated;
    vpLaserCalibrationData truth = previous;
    truth.cMl = knocked;
    std::ofstream points((o.sequence + "/points.csv").c_str());
    points << "frame,u,v\n";
    for (size_t f = 0; f < afterKnock.size(); ++f)
      for (const vpImagePoint &p : afterKnock[f])
        points << f << "," << p.get_u() << "," << p.get_v() << "\n";
    if (!points ||
        !vpLaserRigIo::writeCamera(o.sequence + "/camera.xml", cam, vspLaserRig::kWidth, vspLaserRig::kHeight, error) ||
        !vpLaserRigIo::writeLaserCalibrationYaml(o.sequence + "/laser_previous.yaml", previous, error) ||
        !vpLaserRigIo::writeLaserCalibrationYaml(o.sequence + "/laser_knocked_truth.yaml", truth, error)) {
      std::cerr << argv[0] << ": " << (error.empty() ? o.sequence + "/points.csv cannot be written" : error)
                << std::endl;
      return EXIT_FAILURE;
    }
  }
  if (o.check) {
    const bool ok = detected >= 0 && detected < static_cast<int>(o.knockFrame + 30) && recalibrated > 0 &&
                    axisError <= 3.0 * axisStd && during > 2.0 * after;
    std::cout << (ok ? "check passed" : "check FAILED") << std::endl;
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
