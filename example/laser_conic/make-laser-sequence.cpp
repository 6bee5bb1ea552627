/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example make-laser-sequence.cpp
  Generates data/laser_sequence, a simulated counterpart of the hand-held Vicon experiment of
  Boutteau et al. (JMIV 2018, Sec. 7.2): a 1600x1200 camera and a 34 deg circular laser (rig of
  laserRigSetup.h) moved along a smooth hand-held-like trajectory at 0.5-1.5 m with roll and pitch
  within +-20 deg over a dark floor, rendered by vpLaserConicSimulator::render().

  Writes camera.xml, laser.txt (the laser pose calibrated with vpLaserConicCalibration from simulated
  grid views, as in the paper), laser_true.txt (the pose used for rendering), groundtruth.csv and
  images/frame_XXX.jpg. The output depends only on the seed and the options (deterministic).
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicCalibration.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "laserRigSetup.h"
#include "vpCommandLine.h"
#include "vpLaserRigIo.h"

namespace
{
struct Options
{
  std::string output = std::string(VSP_DATA_DIR) + "/laser_sequence";
  unsigned int frames = 100;
  unsigned int seed = 2018;
  int quality = 60;
  double sensorNoise = 1.0;
  double stripeWidth = 3.0;
};

//! Attitude and position of the rig at one instant.
struct RigState
{
  double altitude, roll, pitch, yaw, x, y;
};

/*!
  A smooth signal: a slow sine plus a faster, smaller one standing for the hand's wobble, with seeded
  random phases so that the trajectory is not a textbook curve.
*/
class SmoothSignal
{
public:
  SmoothSignal(std::mt19937 &rng, double mean, double slowAmplitude, double slowCycles, double wobbleAmplitude,
               double wobbleCycles)
    : m_mean(mean), m_slowAmplitude(slowAmplitude), m_slowCycles(slowCycles), m_wobbleAmplitude(wobbleAmplitude),
      m_wobbleCycles(wobbleCycles)
  {
    std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
    m_slowPhase = phase(rng);
    m_wobblePhase = phase(rng);
  }
  //! Value at normalised time \e t in [0, 1].
  double operator()(double t) const
  {
    return m_mean + m_slowAmplitude * std::sin(2.0 * M_PI * m_slowCycles * t + m_slowPhase) +
           m_wobbleAmplitude * std::sin(2.0 * M_PI * m_wobbleCycles * t + m_wobblePhase);
  }

private:
  double m_mean, m_slowAmplitude, m_slowCycles, m_wobbleAmplitude, m_wobbleCycles;
  double m_slowPhase = 0.0, m_wobblePhase = 0.0;
};

std::vector<RigState> trajectory(unsigned int frames, unsigned int seed)
{
  std::mt19937 rng(seed);
  // Amplitudes keep the altitude in [0.55, 1.45] m and the tilts within +-(15 + 3) deg.
  const SmoothSignal altitude(rng, 1.0, 0.38, 1.3, 0.05, 5.0);
  const SmoothSignal roll(rng, 0.0, vpMath::rad(15.0), 1.7, vpMath::rad(3.0), 6.5);
  const SmoothSignal pitch(rng, 0.0, vpMath::rad(14.0), 1.1, vpMath::rad(3.0), 7.3);
  const SmoothSignal yaw(rng, 0.0, vpMath::rad(40.0), 0.6, vpMath::rad(2.0), 4.0);
  const SmoothSignal x(rng, 0.0, 1.0, 0.5, 0.02, 6.0);
  const SmoothSignal y(rng, 0.0, 0.6, 0.8, 0.02, 5.5);
  std::vector<RigState> states;
  for (unsigned int k = 0; k < frames; ++k) {
    const double t = frames > 1 ? k / static_cast<double>(frames - 1) : 0.0;
    states.push_back({altitude(t), roll(t), pitch(t), yaw(t), x(t), y(t)});
  }
  return states;
}

/*!
  A dark, low-detail floor (the paper's experiments run in a dark room over a dark floor): smooth
  value noise around grey level 30 with a faint warm tint. Low detail keeps the JPEG files small;
  the laser detector must not depend on the floor anyway.
*/
vpImage<vpRGBa> darkFloorTexture(unsigned int seed)
{
  const unsigned int cells = 24, size = 512;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> grid((cells + 1) * (cells + 1));
  for (double &g : grid) {
    g = value(rng);
  }
  vpImage<vpRGBa> texture(size, size);
  for (unsigned int i = 0; i < size; ++i) {
    for (unsigned int j = 0; j < size; ++j) {
      // Bilinear interpolation of the coarse grid with a smoothstep weight: no visible cell edges.
      const double y = i * cells / static_cast<double>(size), x = j * cells / static_cast<double>(size);
      const unsigned int gy = static_cast<unsigned int>(y), gx = static_cast<unsigned int>(x);
      double fy = y - gy, fx = x - gx;
      fy = fy * fy * (3.0 - 2.0 * fy);
      fx = fx * fx * (3.0 - 2.0 * fx);
      const double top = grid[gy * (cells + 1) + gx] * (1.0 - fx) + grid[gy * (cells + 1) + gx + 1] * fx;
      const double bottom =
          grid[(gy + 1) * (cells + 1) + gx] * (1.0 - fx) + grid[(gy + 1) * (cells + 1) + gx + 1] * fx;
      const double grey = 30.0 + 12.0 * (top * (1.0 - fy) + bottom * fy);
      texture[i][j] = vpRGBa(static_cast<unsigned char>(grey + 3.0), static_cast<unsigned char>(grey),
                             static_cast<unsigned char>(grey - 2.0), 255);
    }
  }
  return texture;
}

/*!
  Simulates the paper's calibration session (Sec. 6 and 7.2: 16 views of a planar grid with the
  laser trace on it, a rough initial guess of the laser pose) and runs vpLaserConicCalibration, so that
  laser.txt carries a realistic calibration error instead of the true pose. The grid poses given to
  the calibration are perturbed (1 mm, 0.1 deg) as a pose from grid corners would be, and the trace
  points have 0.5 pixel noise.
*/
vpHomogeneousMatrix calibrateLaser(const vpCameraParameters &cam, double openingAngle, const vpHomogeneousMatrix &cMl,
                                   unsigned int seed, double &rms)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> distance(0.6, 1.2), tilt(vpMath::rad(-25.0), vpMath::rad(25.0)),
      yaw(-M_PI, M_PI);
  std::normal_distribution<double> gridTranslationError(0.0, 1e-3), gridRotationError(0.0, vpMath::rad(0.1));
  vpLaserConicSimulator sim;
  sim.setCamera(cam, vspLaserRig::kWidth, vspLaserRig::kHeight);
  sim.setLaser(openingAngle, cMl);
  sim.setSeed(seed);
  vpLaserConicCalibration calibration;
  calibration.setCameraParameters(cam);
  calibration.setOpeningAngle(openingAngle);
  // "Measured roughly": 1-2 cm and a few degrees away from the truth.
  calibration.setInitialGuess(vpHomogeneousMatrix(0.13, 0.0, 0.01, 0.0, vpMath::rad(-4.0), 0.0));
  for (unsigned int v = 0; v < 16; ++v) {
    const vpHomogeneousMatrix cMg = vspLaserRig::groundPose(distance(rng), tilt(rng), tilt(rng), yaw(rng));
    sim.setGroundPose(cMg);
    const std::vector<vpImagePoint> points = sim.addNoise(sim.tracePoints(180), 0.5);
    const vpHomogeneousMatrix gridError(gridTranslationError(rng), gridTranslationError(rng),
                                        gridTranslationError(rng), gridRotationError(rng), gridRotationError(rng),
                                        gridRotationError(rng));
    calibration.addView(cMg * gridError, points);
  }
  vpHomogeneousMatrix calibrated;
  rms = calibration.calibrate(calibrated);
  return calibrated;
}

//! Distance between the apexes (m) and angle between the cone axes (rad) of two laser poses.
void laserPoseError(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &apexError, double &axisError)
{
  apexError = std::sqrt(vpMath::sqr(a[0][3] - b[0][3]) + vpMath::sqr(a[1][3] - b[1][3]) + vpMath::sqr(a[2][3] - b[2][3]));
  const double dot = a[0][2] * b[0][2] + a[1][2] * b[1][2] + a[2][2] * b[2][2];
  axisError = std::acos(std::max(-1.0, std::min(1.0, dot)));
}

//! Declares the options of the program; \e opt receives their values.
vpCommandLine commandLine(Options &opt)
{
  vpCommandLine cli("[--output DIR] [--frames N] [--seed S] [--quality Q] [--sensor-noise GREY]",
                    "Writes the simulated hand-held laser sequence (camera.xml, laser.txt, groundtruth.csv, images/).");
  cli.addString("--output", opt.output, "DIR", "default " VSP_DATA_DIR "/laser_sequence");
  cli.addUnsigned("--frames", opt.frames, "N", "number of frames (default 100)", 1);
  cli.addUnsigned("--seed", opt.seed, "S", "trajectory and rendering seed (default 2018)");
  cli.addInt("--quality", opt.quality, "Q", "JPEG quality (default 60)", 1, 100);
  cli.addDouble("--sensor-noise", opt.sensorNoise, "GREY", "sensor noise standard deviation, grey levels (default 1)",
                vpCommandLine::NON_NEGATIVE);
  return cli;
}
} // namespace

int main(int argc, char **argv)
{
  Options opt;
  vpCommandLine cli = commandLine(opt);
  if (!cli.parse(argc, argv)) {
    return cli.exitStatus();
  }
  try {
    vpIoTools::makeDirectory(opt.output + "/images");
    const vpCameraParameters cam = vspLaserRig::camera();
    const double openingAngle = vpMath::rad(vspLaserRig::kOpeningAngleDeg);
    const vpHomogeneousMatrix cMl = vspLaserRig::laserPose();
    double rms = 0.0, apexError = 0.0, axisError = 0.0;
    const vpHomogeneousMatrix cMlCalibrated = calibrateLaser(cam, openingAngle, cMl, opt.seed, rms);
    laserPoseError(cMlCalibrated, cMl, apexError, axisError);
    std::cout << "Laser calibration from 16 simulated grid views: RMS " << rms * 1e3 << " mm, apex error "
              << apexError * 1e3 << " mm, axis error " << vpMath::deg(axisError) << " deg" << std::endl;
    std::string error;
    if (!vpLaserRigIo::writeCamera(opt.output + "/camera.xml", cam, vspLaserRig::kWidth, vspLaserRig::kHeight,
                                   error) ||
        !vpLaserRigIo::writeLaserCalibration(opt.output + "/laser.txt", openingAngle, cMlCalibrated, error) ||
        !vpLaserRigIo::writeLaserCalibration(opt.output + "/laser_true.txt", openingAngle, cMl, error)) {
      std::cerr << error << std::endl;
      return EXIT_FAILURE;
    }

    const vpImage<vpRGBa> floor = darkFloorTexture(opt.seed);
    vpLaserConicSimulator sim;
    sim.setCamera(cam, vspLaserRig::kWidth, vspLaserRig::kHeight);
    sim.setLaser(openingAngle, cMl);
    std::vector<vpLaserGroundTruthFrame> frames;
    const std::vector<RigState> states = trajectory(opt.frames, opt.seed);
    for (unsigned int k = 0; k < states.size(); ++k) {
      const RigState &s = states[k];
      sim.setGroundPose(vspLaserRig::groundPose(s.altitude, s.roll, s.pitch, s.yaw, s.x, s.y));
      // Reseeding per frame makes each image reproducible on its own.
      sim.setSeed(opt.seed + k);
      vpImage<vpRGBa> I;
      sim.render(I, floor, opt.stripeWidth, opt.sensorNoise);

      vpLaserGroundTruthFrame f;
      f.frame = k;
      std::ostringstream name;
      name << "images/frame_" << std::setw(3) << std::setfill('0') << k << ".jpg";
      f.image = name.str();
      f.plane = sim.getGroundPlane();
      vpLaserConicPose::computeAltitudeRollPitch(f.plane, f.altitude, f.roll, f.pitch);
      // The trajectory is defined with the estimator's attitude convention: they must agree.
      if (std::fabs(f.altitude - s.altitude) > 1e-9 || std::fabs(f.roll - s.roll) > 1e-9 ||
          std::fabs(f.pitch - s.pitch) > 1e-9) {
        std::cerr << "Frame " << k << ": the ground truth convention disagrees with vpLaserConicPose ("
                  << f.altitude << ", " << f.roll << ", " << f.pitch << " vs " << s.altitude << ", " << s.roll << ", "
                  << s.pitch << ")" << std::endl;
        return EXIT_FAILURE;
      }
      vpImageIo::writeJPEG(I, opt.output + "/" + f.image, vpImageIo::IO_DEFAULT_BACKEND, opt.quality);
      frames.push_back(f);
      std::cout << f.image << ": altitude " << std::setprecision(4) << f.altitude << " m, roll "
                << vpMath::deg(f.roll) << " deg, pitch " << vpMath::deg(f.pitch) << " deg" << std::endl;
    }
    if (!vpLaserRigIo::writeGroundTruth(opt.output + "/groundtruth.csv", frames, error)) {
      std::cerr << error << std::endl;
      return EXIT_FAILURE;
    }
    std::cout << "Wrote " << frames.size() << " frames to " << opt.output << std::endl;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
