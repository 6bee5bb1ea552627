/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
//! \example tutorial-laser-servo-landing.cpp
//! A closed ViSP servo loop on the circular-laser altimeter: vpSimulatorCamera flies; every frame is
//! rendered by vpLaserConicSimulator, the trace found by vpLaserConicDetector (search region from the
//! previous frame), the plane estimated by vpLaserConicPose (GP-3) and fused with a simulated 200 Hz IMU
//! by vpLaserConicFilter; vpServo drives the camera with a vpFeatureLaserPlane (altitude, roll, pitch)
//! and a vpFeaturePoint on the landing pad (x, y), from 2 m down to 0.3 m.
#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpXmlParserCamera.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpFeatureLaserPlane.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicFilter.h>
#include <visp3/laser_conic/vpLaserConicImuSimulator.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

#include "vpPngPlot.h"
#include "vpTutorialCommon.h"

namespace
{
const double kImuRate = 200.0, kFrameRate = 30.0, kLatency = 0.03, kGravity = 9.80665;

//! [Scene]
//! World frame: z up, the floor z = 0, the landing pad at the origin; a 20 cm box beside the pad, whose
//! edge the ring crosses in the last part of the descent, and a red cable on the floor.
struct Scene
{
  double boxX0 = 0.12, boxX1 = 0.8, boxY0 = -0.6, boxY1 = 0.6, boxTop = 0.2;
  vpLaserConicSimulator::vpDistractor cable = vpLaserConicSimulator::vpDistractor::line(-0.6, 0.35, 0.7, 0.12, 0.015);
};
//! [Scene]

//! [Rig]
struct Rig
{
  unsigned int width = 640, height = 480;
  vpCameraParameters cam = vpCameraParameters(500, 500, 320, 240, -0.06, 0.06); // kud, kdu: barrel distortion
  double openingAngle = vpMath::rad(34);
  vpHomogeneousMatrix cMl = vpHomogeneousMatrix(0.08, 0, 0, 0, vpMath::rad(2), 0);
};
//! [Rig]

//! [Vehicle]
/*!
  The flying camera: vpSimulatorCamera integrates the camera velocity, which follows the servo's command
  with a second-order lag, as a drone's velocity follows its set-point. The true IMU readings (gyro,
  specific force, camera frame) come from that motion.
*/
class Vehicle
{
public:
  Vehicle(const vpHomogeneousMatrix &wMc0, double dt) : m_v(6, 0.0), m_a(6, 0.0), m_dt(dt), m_verticalSpeed(0.0)
  {
    m_robot.setSamplingTime(dt);
    m_robot.setMaxTranslationVelocity(2.0); // above what step() commands: its own limit applies
    m_robot.setMaxRotationVelocity(vpMath::rad(180));
    m_robot.setPosition(wMc0);
  }
  //! One IMU period under the command \e vCommand; \e w and \e f receive the true IMU readings at its end.
  void step(const vpColVector &vCommand, double w[3], double f[3])
  {
    // Speed limit of the vehicle (0.6 m/s), keeping the direction of the command.
    const double speed = std::sqrt(vCommand[0] * vCommand[0] + vCommand[1] * vCommand[1] + vCommand[2] * vCommand[2]);
    const double limit = speed > 0.6 ? 0.6 / speed : 1.0;
    // Second-order response (time constants 0.15 s and 0.05 s): the acceleration is continuous, as a
    // vehicle's is, so that the IMU samples it at each instant.
    const vpColVector aNext = m_a + (m_dt / 0.05) * ((limit * vCommand - m_v) / 0.15 - m_a);
    const vpColVector vMid = m_v + (m_dt / 6.0) * (2.0 * m_a + aNext); // mean velocity over the period
    m_robot.setVelocity(vpRobot::CAMERA_FRAME, vMid);                  // the twist of this period
    m_v += (0.5 * m_dt) * (m_a + aNext);
    m_a = aNext;
    // In the rotating camera frame the acceleration is omega x v + dv/dt; the accelerometer adds the
    // reaction to gravity.
    const vpRotationMatrix wRc = pose().getRotationMatrix();
    vpColVector up(3, 0.0);
    up[2] = kGravity;
    const vpColVector upCamera = static_cast<vpMatrix>(wRc.t()) * up;
    const double *v = m_v.data, *om = m_v.data + 3;
    const double cross[3] = {om[1] * v[2] - om[2] * v[1], om[2] * v[0] - om[0] * v[2], om[0] * v[1] - om[1] * v[0]};
    for (unsigned int i = 0; i < 3; ++i) {
      w[i] = om[i];
      f[i] = cross[i] + m_a[i] + upCamera[i];
    }
    const vpColVector worldLinear = static_cast<vpMatrix>(wRc) * vpColVector({v[0], v[1], v[2]});
    m_verticalSpeed = worldLinear[2];
  }
  vpHomogeneousMatrix pose() const { return m_robot.getPosition(); }
  double verticalSpeed() const { return m_verticalSpeed; }

private:
  vpSimulatorCamera m_robot;
  vpColVector m_v, m_a; //!< camera velocity (twist) and its rate of change, camera frame
  double m_dt;
  double m_verticalSpeed; //!< world z of the camera velocity, m/s
};
//! [Vehicle]

//! Truth seen from the camera at wMc: altitude over the floor z = 0, roll, pitch (vpLaserConicPose's convention).
void truthOf(const vpHomogeneousMatrix &wMc, double &h, double &roll, double &pitch)
{
  // The floor n_w . X_w = 0 with n_w = (0, 0, 1) in the camera frame: (wRc^T n_w) . X_c + n_w . wTc = 0.
  const vpPlane cPlane(wMc[2][0], wMc[2][1], wMc[2][2], wMc[2][3]);
  vpLaserConicPose::computeAltitudeRollPitch(cPlane, h, roll, pitch);
}

//! [Render]
/*!
  Renders the frame seen from wMc: the floor (with the cable), and where the camera sees the box, the
  box top (a second render of a ground 20 cm higher) and its side walls (dark). \e distractor adds the
  cable. Returns true when the box is in view.
*/
bool renderFrame(vpLaserConicSimulator &sim, const Rig &rig, const Scene &scene, const vpHomogeneousMatrix &wMc,
                 bool distractor, vpImage<vpRGBa> &I)
{
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.sceneSeed = 11; // the same floor in every frame, new sensor noise
  settings.bloom = 0.2;
  settings.whiteCore = 0.5;
  settings.blur = 0.8;
  if (distractor)
    settings.distractors.push_back(scene.cable);
  const vpHomogeneousMatrix cMw = wMc.inverse();
  sim.setGroundPose(cMw);
  sim.render(I, settings);
  const vpHomogeneousMatrix wMtop(0, 0, scene.boxTop, 0, 0, 0);
  vpImage<vpRGBa> top;
  bool topRendered = false;
  const vpRotationMatrix wRc = wMc.getRotationMatrix();
  for (unsigned int v = 0; v < I.getHeight(); ++v)
    for (unsigned int u = 0; u < I.getWidth(); ++u) {
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(rig.cam, u, v, x, y);
      const double dx = wRc[0][0] * x + wRc[0][1] * y + wRc[0][2], dy = wRc[1][0] * x + wRc[1][1] * y + wRc[1][2],
                   dz = wRc[2][0] * x + wRc[2][1] * y + wRc[2][2];
      if (!(dz < 0.0))
        continue;
      const auto inBox = [&](double z, double &X, double &Y) {
        const double s = (z - wMc[2][3]) / dz;
        X = wMc[0][3] + s * dx;
        Y = wMc[1][3] + s * dy;
        return X >= scene.boxX0 && X <= scene.boxX1 && Y >= scene.boxY0 && Y <= scene.boxY1;
      };
      double X, Y;
      if (inBox(scene.boxTop, X, Y)) {
        if (!topRendered) {
          sim.setGroundPose(cMw * wMtop);
          sim.render(top, settings);
          topRendered = true;
        }
        I[v][u] = top[v][u];
      } else if (inBox(0.0, X, Y))
        I[v][u] = vpRGBa(40, 36, 34, 255); // a side wall
    }
  return topRendered;
}
//! [Render]

//! [Export]
/*!
  Writes the flight as a data set for vsp-laser-altimeter (`--export DIR`): the frames as JPEG, the IMU
  stream as CSV (vpImuGravity's layout, nanoseconds), the exposure time of each frame, the camera and
  laser files, and the true altitude, roll and pitch of each frame.
*/
class FlightExport
{
public:
  FlightExport(const std::string &dir, const Rig &rig) : m_dir(dir)
  {
    if (dir.empty())
      return;
    vpIoTools::makeDirectory(vpIoTools::createFilePath(dir, "images"));
    vpXmlParserCamera xml;
    xml.save(rig.cam, vpIoTools::createFilePath(dir, "camera.xml"), "Camera", rig.width, rig.height);
    std::ofstream laser(vpIoTools::createFilePath(dir, "laser.txt"));
    laser << "opening_angle_deg " << vpMath::deg(rig.openingAngle) << "\ncMl\n" << std::setprecision(17);
    for (unsigned int i = 0; i < 4; ++i)
      laser << rig.cMl[i][0] << " " << rig.cMl[i][1] << " " << rig.cMl[i][2] << " " << rig.cMl[i][3] << "\n";
    m_imu.open(vpIoTools::createFilePath(dir, "imu.csv"));
    m_imu << "#timestamp [ns],w_x [rad s^-1],w_y [rad s^-1],w_z [rad s^-1],a_x [m s^-2],a_y [m s^-2],a_z [m s^-2]\n"
          << std::setprecision(17);
    m_times.open(vpIoTools::createFilePath(dir, "frame_times.csv"));
    m_times << "image,timestamp_ns\n";
    m_truth.open(vpIoTools::createFilePath(dir, "truth.csv"));
    m_truth << "image,timestamp_ns,altitude_m,roll_rad,pitch_rad\n" << std::setprecision(17);
  }
  bool enabled() const { return !m_dir.empty(); }
  void imu(double t, const double gyro[3], const double acc[3])
  {
    if (!enabled())
      return;
    m_imu << ns(t);
    for (int i = 0; i < 3; ++i)
      m_imu << "," << gyro[i];
    for (int i = 0; i < 3; ++i)
      m_imu << "," << acc[i];
    m_imu << "\n";
  }
  //! A frame (\e I empty for a lost frame, written black so that every exposure has its image).
  void frame(double t, const vpImage<vpRGBa> &I, const Rig &rig, double h, double roll, double pitch)
  {
    if (!enabled())
      return;
    char name[32];
    std::snprintf(name, sizeof(name), "images/frame_%04d.jpg", m_count++);
    vpImage<vpRGBa> out = I;
    if (out.getSize() == 0)
      out.resize(rig.height, rig.width, vpRGBa(0, 0, 0, 255));
    vpImageIo::write(out, vpIoTools::createFilePath(m_dir, name));
    m_times << name << "," << ns(t) << "\n";
    m_truth << name << "," << ns(t) << "," << h << "," << roll << "," << pitch << "\n";
  }
  //! True when every file was written.
  bool good() const { return !enabled() || (m_imu.good() && m_times.good() && m_truth.good()); }

private:
  static long long ns(double t) { return static_cast<long long>(std::llround(t * 1e9)); }
  std::string m_dir;
  std::ofstream m_imu, m_times, m_truth;
  int m_count = 0;
};
//! [Export]

//! One frame's estimate waiting for its latency.
struct PendingFrame
{
  double t;
  bool found;
  double h, roll, pitch;
  vpMatrix covariance;
};

//! The time series the plots show.
struct Record
{
  std::vector<double> t, hTrue, hEst, hLow, hHigh, vzTrue, vzEst, rollTrue, rollEst, pitchTrue, pitchEst, servoError;
  std::vector<double> errH, err3s, errM3s;
  std::vector<double> frameT, frameH;
};

//! [Frame]
//! Detects and estimates one rendered frame; the search region follows the previous frame's trace.
bool estimateFrame(const vpImage<vpRGBa> &I, vpLaserConicDetector &detector, vpLaserConicPose &pose)
{
  const std::vector<vpImagePoint> points = detector.detect(I);
  vpPlane cPlane;
  const bool found = points.size() >= 20 && pose.computePlane(points, vpLaserConicPose::GP3, cPlane);
  if (found)
    detector.setSearchRegion(pose.getRansacInliers(), 20.0);
  else
    detector.clearSearchRegion(); // search the whole image at the next frame
  return found;
}
//! [Frame]

//! A curve of the flight record: its legend, its values at the record's times and its colour.
struct Curve
{
  std::string name;
  const std::vector<double> *values;
  vpColor color;
};

//! A plot of curves of the flight record against time, at the size of every plot of this tutorial.
vpPngPlot timePlot(const std::string &title, const std::string &yLabel, const std::vector<double> &t,
                   const std::vector<Curve> &curves)
{
  vpPngPlot plot(title, "time (s)", yLabel, 800, 420);
  for (const Curve &c : curves)
    plot.addCurve(c.name, t, *c.values, c.color);
  return plot;
}

void writePlots(const Record &r, const std::string &dir)
{
  vpPngPlot altitude = timePlot("Altitude: truth and filter (200 Hz), GP-3 per frame", "altitude (m)", r.t,
                                {{"truth", &r.hTrue, vpColor::black}, {"filter", &r.hEst, vpColor::red}});
  altitude.addPoints("GP-3 frames", r.frameT, r.frameH, vpColor::blue);
  altitude.write(vpIoTools::createFilePath(dir, "laser-servo-landing-altitude.png"));

  vpPngPlot error = timePlot("Altitude error of the filter and its 3-sigma band", "error (mm)", r.t,
                             {{"filter - truth", &r.errH, vpColor::red},
                              {"+3 sigma", &r.err3s, vpColor::gray},
                              {"-3 sigma", &r.errM3s, vpColor::gray}});
  error.setYRange(-15, 15);
  error.write(vpIoTools::createFilePath(dir, "laser-servo-landing-altitude-error.png"));

  timePlot("Vertical speed", "speed (m/s)", r.t,
           {{"truth", &r.vzTrue, vpColor::black}, {"filter", &r.vzEst, vpColor::red}})
      .write(vpIoTools::createFilePath(dir, "laser-servo-landing-speed.png"));

  timePlot("Attitude", "angle (deg)", r.t,
           {{"roll truth", &r.rollTrue, vpColor::black},
            {"roll filter", &r.rollEst, vpColor::red},
            {"pitch truth", &r.pitchTrue, vpColor::gray},
            {"pitch filter", &r.pitchEst, vpColor::blue}})
      .write(vpIoTools::createFilePath(dir, "laser-servo-landing-attitude.png"));

  vpPngPlot servo = timePlot("Servo error |s - s*|", "error", r.t, {{"task error", &r.servoError, vpColor::red}});
  servo.setLogY(true);
  servo.write(vpIoTools::createFilePath(dir, "laser-servo-landing-servo-error.png"));
}

//! Normalized coordinates and depth of the pad (world origin) seen from wMc, with 0.5 px of noise.
void padFeature(const vpHomogeneousMatrix &wMc, const Rig &rig, std::mt19937 &rng, double &x, double &y, double &Z)
{
  const vpHomogeneousMatrix cMw = wMc.inverse();
  std::normal_distribution<double> noise(0.0, 0.5 / rig.cam.get_px());
  Z = cMw[2][3];
  x = cMw[0][3] / Z + noise(rng);
  y = cMw[1][3] / Z + noise(rng);
}

//! Statistics of the run that the checks use.
struct Summary
{
  int frames = 0, dropped = 0, noPlane = 0, rejected = 0, steps = 0, diverged = 0, distractorFrames = 0;
  int boxFrames = 0;
  double frameNeesSum = 0.0;
  int frameNeesCount = 0;
  double inside3Sigma = 0.0, samples = 0.0;
};

//! NEES of one clean frame's GP-3 estimate (no box, no cable) against the truth, with its covariance.
void addFrameNees(const vpLaserConicPose &pose, double h, double roll, double pitch, Summary &sum)
{
  vpMatrix C = pose.getCovarianceMatrix();
  vpColVector e(3);
  e[0] = pose.getAltitude() - h;
  e[1] = pose.getRoll() - roll;
  e[2] = pose.getPitch() - pitch;
  // Normalised first: vpMatrix's inverse refuses determinants as small as these (1e-28).
  for (unsigned int i = 0; i < 3; ++i) {
    const double si = std::sqrt(C[i][i]);
    e[i] /= si;
    for (unsigned int j = 0; j < 3; ++j)
      C[i][j] /= si * std::sqrt(C[j][j]);
  }
  const double nees = e.t() * C.inverseByLU() * e;
  if (std::isfinite(nees)) {
    sum.frameNeesSum += nees;
    ++sum.frameNeesCount;
  }
}

//! Prints the outcome and, when \e check, checks it against the bounds of a whole landing.
bool report(const vpHomogeneousMatrix &wMc, const Summary &sum, bool check)
{
  double h, roll, pitch;
  truthOf(wMc, h, roll, pitch);
  const double lateral = std::hypot(wMc[0][3], wMc[1][3]);
  const double frameNees = sum.frameNeesCount ? sum.frameNeesSum / sum.frameNeesCount : NAN;
  std::cout << std::fixed << std::setprecision(4) << sum.frames << " frames: " << sum.dropped << " dropped, "
            << sum.noPlane << " without plane, " << sum.distractorFrames << " with the red cable, " << sum.boxFrames
            << " with the box edge; " << sum.rejected << " rejected by the filter, " << sum.steps << " ground steps"
            << std::endl
            << "per-frame GP-3 mean NEES on the frames without box or cable " << std::setprecision(2) << frameNees
            << " (3 if its covariance is honest)" << std::endl
            << "filter altitude inside 3 sigma: " << 100.0 * sum.inside3Sigma / std::max(1.0, sum.samples) << " %"
            << std::endl
            << std::setprecision(4) << "final: altitude " << h << " m, roll " << vpMath::deg(roll) << " deg, pitch "
            << vpMath::deg(pitch) << " deg, " << 1e3 * lateral << " mm from the pad" << std::endl;
  if (!check) {
    std::cout << "flight shorter than 10 s: the landing bounds are not checked" << std::endl;
    return true;
  }
  // Bounds: the servo error decays as exp(-0.7 t) after the 0.6 m/s descent; after 12 s what is left
  // is the estimate's error (a fraction of a millimetre, a few hundredths of a degree). The filter's
  // altitude is inside its 3 sigma in 88 % of the samples, not 99.7 %: the frames' errors are correlated
  // from frame to frame (the same floor, a slowly changing view; GP-3's pitch is biased by up to 0.4 deg
  // between 1.5 m and 0.5 m), which no per-frame covariance contains and the filter averages as if
  // independent. The bound 80 % catches a filter that loses the altitude (a few per cent inside).
  return vpTutorialCheck(std::abs(h - 0.3) < 0.01, "final altitude not within 1 cm of 0.3 m") &&
         vpTutorialCheck(std::abs(vpMath::deg(roll)) < 0.5 && std::abs(vpMath::deg(pitch)) < 0.5,
                         "final roll or pitch above 0.5 deg") &&
         vpTutorialCheck(lateral < 0.02, "final position more than 2 cm from the pad") &&
         vpTutorialCheck(sum.diverged == 0, "the filter diverged") &&
         vpTutorialCheck(sum.inside3Sigma >= 0.80 * sum.samples, "filter altitude outside its 3 sigma too often");
}

//! [Loop]
bool runServoLanding(double duration, unsigned int seed, const std::string &outputDir, bool display,
                     const std::string &exportDir)
{
  const Rig rig;
  FlightExport exporter(exportDir, rig);
  const Scene scene;
  vpLaserConicSimulator sim;
  sim.setCamera(rig.cam, rig.width, rig.height);
  sim.setLaser(rig.openingAngle, rig.cMl);
  vpLaserConicDetector detector;
  vpLaserConicPose pose;
  pose.setCameraParameters(rig.cam);
  pose.setLaser(rig.openingAngle, rig.cMl);
  pose.setCovarianceComputation(true);
  // The detector's errors are correlated along the trace: its covariance needs this variance scale to
  // be honest (measured on rendered JPEG frames, testLaserConicCovarianceRendered).
  pose.setCovarianceInflation(vpLaserConicPose::recommendedDetectorInflation());
  vpLaserConicFilter filter;
  vpLaserConicImuSimulator imu; // ADIS16448 noise densities and bias walks
  imu.setSeed(21);
  imu.drawInitialBias(0.002, 0.02);

  const double dt = 1.0 / kImuRate;
  Vehicle vehicle(vpHomogeneousMatrix(-0.5, 0.3, 2.0, M_PI, 0, 0) *
                      vpHomogeneousMatrix(0, 0, 0, vpMath::rad(6), vpMath::rad(-4), 0.2),
                  dt);

  vpFeatureLaserPlane s, sd;
  sd.buildFrom(0.3, 0.0, 0.0); // 30 cm over the ground, level
  vpFeaturePoint p, pd;
  pd.buildFrom(0.0, 0.0, 0.3); // the pad on the optical axis
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.7);
  task.addFeature(s, sd);
  task.addFeature(p, pd);

  std::mt19937 rng(seed); // which frames are lost, the pad's pixel noise
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::deque<PendingFrame> pending;
  Record rec;
  Summary sum;
  vpTutorialViewer viewer(display, "Laser servo landing");
  double padX = 0, padY = 0, padZ = 2.0, nextFrame = 0.0; // padZ: the true depth, unused by the servo
  vpColVector v(6, 0.0);
  vpImage<vpRGBa> I;
  const int steps = static_cast<int>(duration * kImuRate);
  for (int k = 0; k <= steps; ++k) {
    const double t = k * dt;
    double wTrue[3], fTrue[3], gyro[3], acc[3];
    vehicle.step(v, wTrue, fTrue);
    imu.measure(dt, wTrue, fTrue, gyro, acc);
    filter.addImu(t, gyro, acc);
    exporter.imu(t, gyro, acc);
    const vpHomogeneousMatrix wMc = vehicle.pose();
    double hTrue, rollTrue, pitchTrue;
    truthOf(wMc, hTrue, rollTrue, pitchTrue);

    if (t + 1e-9 >= nextFrame) { // exposure of a frame
      ++sum.frames;
      nextFrame += 1.0 / kFrameRate;
      PendingFrame f{t, false, 0, 0, 0, vpMatrix()};
      if (u01(rng) < 0.10) {
        ++sum.dropped; // a lost frame: no image at all
        exporter.frame(t, vpImage<vpRGBa>(), rig, hTrue, rollTrue, pitchTrue);
      } else {
        const bool distractor = sum.frames % 10 < 3; // the red cable in 3 frames of 10
        sum.distractorFrames += distractor;
        const bool box = renderFrame(sim, rig, scene, wMc, distractor, I);
        sum.boxFrames += box;
        exporter.frame(t, I, rig, hTrue, rollTrue, pitchTrue);
        f.found = estimateFrame(I, detector, pose);
        if (f.found) {
          if (!box && !distractor)
            addFrameNees(pose, hTrue, rollTrue, pitchTrue, sum);
          f.h = pose.getAltitude();
          f.roll = pose.getRoll();
          f.pitch = pose.getPitch();
          f.covariance = pose.getCovarianceMatrix();
          rec.frameT.push_back(t);
          rec.frameH.push_back(f.h);
        } else
          ++sum.noPlane;
        viewer.show(I);
        viewer.flush(1);
      }
      padFeature(wMc, rig, rng, padX, padY, padZ);
      pending.push_back(f);
    }
    while (!pending.empty() && pending.front().t + kLatency <= t + 1e-9) { // delivered after the latency
      const PendingFrame &f = pending.front();
      const vpLaserConicFilter::vpFrameStatus st = f.found ? filter.addFrame(f.t, f.h, f.roll, f.pitch, f.covariance)
                                                           : filter.addMissingFrame(f.t);
      sum.rejected += st == vpLaserConicFilter::FRAME_REJECTED;
      pending.pop_front();
    }
    if (!filter.isInitialised())
      continue;
    sum.diverged += filter.getStatus() == vpLaserConicFilter::STATUS_DIVERGED;

    //! [Servo]
    s.buildFrom(filter.getAltitude(), filter.getRoll(), filter.getPitch());
    p.buildFrom(padX, padY, filter.getAltitude()); // depth of the pad ~ altitude (near level)
    v = task.computeControlLaw();
    //! [Servo]

    const vpMatrix P = filter.getCovarianceMatrix();
    const double sigma = std::sqrt(P[0][0]);
    rec.t.push_back(t);
    rec.hTrue.push_back(hTrue);
    rec.hEst.push_back(filter.getAltitude());
    rec.errH.push_back(1e3 * (filter.getAltitude() - hTrue));
    rec.err3s.push_back(3e3 * sigma);
    rec.errM3s.push_back(-3e3 * sigma);
    rec.vzTrue.push_back(vehicle.verticalSpeed());
    rec.vzEst.push_back(filter.getVerticalSpeed());
    rec.rollTrue.push_back(vpMath::deg(rollTrue));
    rec.rollEst.push_back(vpMath::deg(filter.getRoll()));
    rec.pitchTrue.push_back(vpMath::deg(pitchTrue));
    rec.pitchEst.push_back(vpMath::deg(filter.getPitch()));
    rec.servoError.push_back(std::max(1e-6, task.getError().frobeniusNorm()));
    sum.inside3Sigma += std::abs(filter.getAltitude() - hTrue) <= 3.0 * sigma;
    sum.samples += 1.0;
  }
  task.kill();
  viewer.waitClick();
  writePlots(rec, outputDir);
  std::cout << "Plots written to " << outputDir
            << "/laser-servo-landing-{altitude,altitude-error,speed,attitude,servo-error}.png" << std::endl;
  sum.steps = static_cast<int>(filter.getGroundStepCount());
  if (!exporter.good()) {
    std::cerr << "cannot write the data set in " << exportDir << std::endl;
    return false;
  }
  return report(vehicle.pose(), sum, duration >= 10.0);
}
//! [Loop]
} // namespace

int main(int argc, char **argv)
{
  int seconds = 12, seed = 5;
  std::string exportDir;
  vpTutorialProgram program("[--seconds N] [--seed N] [--export DIR]",
                            "Closed-loop landing on a circular laser fused with an IMU (vpLaserConicFilter, "
                            "vpFeatureLaserPlane, vpServo); writes laser-servo-landing-*.png.");
  program.addOption("--seconds", seconds, 2, "duration of the flight");
  program.addOption("--seed", seed, 0, "seed of the frame losses and of the pad's pixel noise (default 5)");
  program.addString("--export", exportDir, "DIR",
                    "write the flight as a data set (JPEG frames, imu.csv, frame_times.csv, camera.xml, laser.txt, "
                    "truth.csv) for vsp-laser-altimeter");
  return program.run(argc, argv, [&](const std::string &outputDir) {
    return runServoLanding(seconds, static_cast<unsigned int>(seed), outputDir, program.display(), exportDir);
  });
}
