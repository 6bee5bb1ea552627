/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example laser-drift-demo.cpp
  A simulated flight whose laser mount is knocked by 1 degree halfway: GP3 altitudes go wrong, the drift
  monitor (vpLaserConicDriftMonitor) raises "calibration drift suspected", the laser is self-calibrated
  (vpLaserConicSelfCalibration) on the next 60 frames with the previous calibration's apex held,
  handed to the estimator, and the errors come back down. Every alarm is followed so: a false alarm of the
  monitor before the knock recalibrates the laser as it is, and the knock is still caught after it. Writes
  two PNG plots (altitude errors, drift statistic) and a CSV of the frames; --write-sequence also writes the
  inputs of vsp-laser-calibrate --from-sequence (camera, previous calibration, points of the frames after the
  knock).

  \verbatim
  laser-drift-demo [--output DIR] [--frames N] [--knock-frame K] [--knock-deg D] [--seed N] [--write-sequence DIR]
                   [--check]
  \endverbatim
  --check: exit 1 unless the knock is detected within 30 frames, the first self-calibration on frames all
  taken after it puts the axis within 3 of its standard deviations
  (vpLaserConicSelfCalibration::getAxisStdDeviation()) of the knocked laser's, and the altitude error after
  it is under half that of the knocked frames. (Its altitude error follows the axis's, about 126 mm per
  degree over this flight: over seeds 1-40 the axis came out 0.0002-0.024 degree off for a standard
  deviation of 0.0096, the altitude 0.39-3.09 mm RMS against 0.42-0.67 before the knock and 8.8-12.9
  knocked; a bound of 3 times the error before the knock failed seeds 2 and 16. Seeds 30 and 31 have a
  false alarm before the knock, seed 1 one after its recalibration.)
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

//! What the drift loop did: its alarms, its self-calibrations and the calibration in use.
struct Recalibrations
{
  std::vector<int> alarms; //!< frames where a drift was suspected and frames started to be collected
  std::vector<int> done;   //!< frames where a self-calibration was handed to the estimator
  int collectedFrom = -1;  //!< first frame of the collection under way (-1: none)
  int afterKnock = -1;     //!< the first self-calibration on frames all taken after the knock
  double angle = 0.0;      //!< opening angle in use
  vpHomogeneousMatrix cMl; //!< laser pose in use
  double axisError = std::numeric_limits<double>::quiet_NaN(), axisStd = std::numeric_limits<double>::quiet_NaN();
};

//! "44, 120", or "none".
std::string listOrNone(const std::vector<int> &frames)
{
  std::string text;
  for (int f : frames)
    text += (text.empty() ? "" : ", ") + std::to_string(f);
  return text.empty() ? "none" : text;
}

/*!
  The loop a user writes around the drift monitor, for frame \e k: an alarm starts a collection of frames,
  a full collection is self-calibrated from the calibration in use (its apex held) and, if it succeeds, handed
  to the estimator and the monitor restarted. Every alarm is followed: the monitor's false alarms (0.4 % of
  its windows, vpLaserConicDriftMonitor) only recalibrate the laser it has, and a knock after one is still
  caught. Returns true when frame \e k recalibrated.
*/
bool followDrift(const Options &o, unsigned int k, const std::vector<vpImagePoint> &points, bool alarm,
                 const vpHomogeneousMatrix &knocked, vpLaserConicSelfCalibration &selfcal, vpLaserConicPose &estimator,
                 vpLaserConicDriftMonitor &monitor, Recalibrations &r)
{
  if (alarm && r.collectedFrom < 0) {
    r.alarms.push_back(static_cast<int>(k));
    r.collectedFrom = static_cast<int>(k);
    selfcal.clearFrames();
  }
  if (r.collectedFrom < 0)
    return false;
  if (points.size() >= 5)
    selfcal.addFrame(points);
  if (selfcal.getNbFrames() < o.calibrationFrames)
    return false;
  const bool afterTheKnock = r.collectedFrom >= static_cast<int>(o.knockFrame);
  r.collectedFrom = -1;
  selfcal.setLaser(r.angle, r.cMl); // the calibration in use is the initial guess
  vpHomogeneousMatrix cMl;
  double angle = 0.0;
  if (!selfcal.compute(cMl, angle)) {
    std::cout << "frame " << k
              << ": self-calibration failed: " << vpLaserConicSelfCalibration::getStatusMessage(selfcal.getStatus())
              << " (" << selfcal.getStatusDetails() << ")" << std::endl;
    return false;
  }
  estimator.setLaser(angle, cMl);
  monitor.reset();
  r.angle = angle;
  r.cMl = cMl;
  r.done.push_back(static_cast<int>(k));
  const double offKnocked = std::acos(
      std::min(1.0, vpColVector::dotProd(cMl.getRotationMatrix().getCol(2), knocked.getRotationMatrix().getCol(2))));
  std::cout << "frame " << k << ": self-calibrated on " << o.calibrationFrames << " frames"
            << (afterTheKnock ? "" : " (not all after the knock)") << ", axis off the knocked laser by "
            << vpMath::deg(offKnocked) << " deg (its standard deviation " << vpMath::deg(selfcal.getAxisStdDeviation())
            << " deg)" << std::endl;
  if (afterTheKnock && r.afterKnock < 0) {
    r.afterKnock = static_cast<int>(k);
    r.axisError = offKnocked;
    r.axisStd = selfcal.getAxisStdDeviation();
  }
  return true;
}

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
  Recalibrations r;
  r.angle = A;
  r.cMl = calibrated;
  for (unsigned int k = 0; k < o.frames; ++k) {
    double h, roll, pitch;
    attitude(k, h, roll, pitch);
    sim.setLaser(A, k < o.knockFrame ? calibrated : knocked);
    sim.setGroundPose(vspLaserRig::groundPose(h, roll, pitch));
    const std::vector<vpImagePoint> points = sim.addNoise(sim.tracePoints(300), 0.5);
    if (k >= o.knockFrame)
      afterKnock.push_back(points);
    vpPlane plane;
    if (points.size() >= 5) {
      // Every frame goes to the monitor: one refused as a calibration mismatch counts too.
      if (estimator.computePlane(points, vpLaserConicPose::GP3, plane))
        records[k].error = 1000.0 * (estimator.getAltitude() - sim.getGroundPlane().getD());
      monitor.addFrame(estimator);
      records[k].statistic = monitor.getStatistic();
    }
    records[k].alarm = monitor.getStatus() == vpLaserConicDriftMonitor::DRIFT_SUSPECTED;
    records[k].recalibrated = followDrift(o, k, points, records[k].alarm, knocked, selfcal, estimator, monitor, r);
  }

  // Summaries: RMS altitude error before the knock, between knock and the recalibration after it, after that.
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
  int detected = -1; // the monitor's first alarm after the knock, collecting or not
  for (unsigned int k = o.knockFrame; k < o.frames && detected < 0; ++k)
    detected = records[k].alarm ? static_cast<int>(k) : -1;
  const double before = rms(0, o.knockFrame);
  const double during = rms(o.knockFrame, r.afterKnock >= 0 ? r.afterKnock + 1 : o.frames);
  const double after = r.afterKnock >= 0 ? rms(r.afterKnock + 1, o.frames) : std::numeric_limits<double>::quiet_NaN();
  std::cout << "knock at frame " << o.knockFrame << " (" << o.knockDeg << " deg); drift suspected at frames "
            << listOrNone(r.alarms) << "; recalibrated at frames " << listOrNone(r.done) << std::endl;
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
    const bool ok = detected >= 0 && detected < static_cast<int>(o.knockFrame + 30) && r.afterKnock >= 0 &&
                    r.axisError <= 3.0 * r.axisStd && during > 2.0 * after;
    std::cout << (ok ? "check passed" : "check FAILED") << std::endl;
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
