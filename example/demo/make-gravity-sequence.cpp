/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example make-gravity-sequence.cpp
  Generates the simulated gravity-aided pose sequence shipped in data/gravity_sequence/: a camera
  with an IMU circles around an object that carries its own IMU; per frame the program writes the
  two measured gravity vectors and the 2D/3D correspondences (points.csv, the input format of
  vsp-gravity-pose) and the true pose cMo (groundtruth.csv, the output format of vsp-gravity-pose).

  Every random draw comes from one seeded Mersenne twister turned into Gaussian samples by
  Box-Muller here (not std::normal_distribution, whose algorithm differs between standard
  libraries), so the files are the same on every platform for a given seed.

  \verbatim
  vsp-make-gravity-sequence --output data/gravity_sequence [--seed 2013] [--frames 60]
  \endverbatim
*/
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>

#include "vpCommandLine.h"
#include "vpGravityPointsIo.h"

namespace
{
// Simulated sensors. Camera: 640x480 pixels, focal length 800 px, principal point at the centre.
const double kFocalPx = 800.0;
const double kWidthPx = 640.0;
const double kHeightPx = 480.0;
const double kPixelNoisePx = 0.5;      // image noise, standard deviation per coordinate
const double kGravityNoiseDeg = 0.3;   // IMU tilt noise, standard deviation per axis
const unsigned int kOutlierPeriod = 6; // one mismatched point in every 6th frame (frames 5, 11, ...)

//! Seeded Gaussian samples from a Mersenne twister (Box-Muller, portable across standard libraries).
class SeededGaussian
{
public:
  explicit SeededGaussian(unsigned int seed) : m_rng(seed) {}
  //! Uniform sample in (0, 1).
  double uniform() { return (static_cast<double>(m_rng()) + 0.5) / 4294967296.0; }
  //! Gaussian sample of standard deviation sigma.
  double gaussian(double sigma)
  {
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    return sigma * r * std::cos(2.0 * M_PI * uniform());
  }

private:
  std::mt19937 m_rng;
};

//! The object: 8 points spread in 3D (the first three, used by P3P, are never outliers).
std::vector<vpPoint> objectPoints()
{
  const double coords[8][3] = {{-0.15, -0.10, 0.0}, {0.15, -0.10, 0.0},  {0.15, 0.10, 0.0},   {-0.15, 0.10, 0.0},
                               {0.0, 0.0, 0.08},    {-0.08, 0.05, 0.12}, {0.10, -0.04, 0.05}, {0.05, 0.07, -0.06}};
  std::vector<vpPoint> points;
  for (const auto &c : coords)
    points.push_back(vpPoint(c[0], c[1], c[2]));
  return points;
}

//! Camera pose in the world (Z up) looking at \e target from \e position, rolled by \e roll about its optical axis.
vpHomogeneousMatrix lookAt(const vpColVector &position, const vpColVector &target, double roll)
{
  vpColVector z = target - position;
  z.normalize();
  const vpColVector down({0.0, 0.0, -1.0});
  vpColVector y = down - (vpColVector::dotProd(down, z)) * z; // image y axis points down
  y.normalize();
  const vpColVector x = vpColVector::crossProd(y, z);
  vpRotationMatrix wRc;
  for (unsigned int i = 0; i < 3; ++i) {
    wRc[i][0] = x[i];
    wRc[i][1] = y[i];
    wRc[i][2] = z[i];
  }
  const vpRotationMatrix rollAboutZ(vpThetaUVector(0.0, 0.0, roll));
  return vpHomogeneousMatrix(vpTranslationVector(position[0], position[1], position[2]), wRc * rollAboutZ);
}

//! The unit vector \e g rotated by a small random rotation (IMU tilt error).
vpColVector noisyDirection(const vpColVector &g, SeededGaussian &random)
{
  const double s = vpMath::rad(kGravityNoiseDeg);
  const vpRotationMatrix error(vpThetaUVector(random.gaussian(s), random.gaussian(s), random.gaussian(s)));
  return error * g;
}

vpGravityFrame simulateFrame(unsigned int k, unsigned int frames, const vpHomogeneousMatrix &wMo,
                             SeededGaussian &random, vpHomogeneousMatrix &cMo)
{
  // Trajectory: an arc around the object, rising and moving away, with a rolling camera.
  const double s = frames > 1 ? static_cast<double>(k) / (frames - 1) : 0.0;
  const double azimuth = vpMath::rad(-60.0 + 120.0 * s);
  const double elevation = vpMath::rad(35.0 + 15.0 * s);
  const double distance = 0.8 + 0.4 * s;
  const vpColVector position({distance * std::cos(elevation) * std::cos(azimuth),
                              distance * std::cos(elevation) * std::sin(azimuth), distance * std::sin(elevation)});
  const vpColVector target({0.02 * std::sin(7.0 * s), 0.02 * std::cos(5.0 * s), 0.03});
  const vpHomogeneousMatrix wMc = lookAt(position, target, vpMath::rad(15.0) * std::sin(2.0 * M_PI * s));
  cMo = wMc.inverse() * wMo;

  vpGravityFrame frame;
  frame.frame = k;
  const vpColVector gWorld({0.0, 0.0, -1.0});
  frame.gCam = noisyDirection(vpColVector(wMc.getRotationMatrix().t() * gWorld), random);
  frame.gObj = noisyDirection(vpColVector(wMo.getRotationMatrix().t() * gWorld), random);

  const double sigma = kPixelNoisePx / kFocalPx;
  for (vpPoint P : objectPoints()) {
    P.project(cMo);
    P.set_x(P.get_x() + random.gaussian(sigma));
    P.set_y(P.get_y() + random.gaussian(sigma));
    frame.points.push_back(P);
  }
  if (k % kOutlierPeriod == kOutlierPeriod - 1) {
    // A mismatched point: its image position is anywhere in the image.
    const unsigned int victim = 3 + static_cast<unsigned int>(random.uniform() * (frame.points.size() - 3));
    frame.points[victim].set_x((random.uniform() * kWidthPx - kWidthPx / 2) / kFocalPx);
    frame.points[victim].set_y((random.uniform() * kHeightPx - kHeightPx / 2) / kFocalPx);
  }
  return frame;
}

//! The program; main() only adds a last-resort error report.
int run(int argc, char **argv)
{
  std::string output;
  unsigned int seed = 2013, frames = 60;
  vpCommandLine cli("--output DIR [--seed N] [--frames N]",
                    "Writes DIR/points.csv and DIR/groundtruth.csv (simulated gravity-aided pose sequence).");
  cli.addString("--output", output, "DIR", "folder of the two files (created if needed)");
  cli.addUnsigned("--seed", seed, "N", "seed of the random generator (default 2013, that of data/gravity_sequence)");
  cli.addUnsigned("--frames", frames, "N", "number of frames (default 60)", 1, 100000);
  cli.require({"--output"});
  if (!cli.parse(argc, argv))
    return cli.exitStatus();

  std::error_code ec;
  std::filesystem::create_directories(output, ec);
  SeededGaussian random(seed);
  // The object lies tilted on a support (theta-u rotation of 10 degrees about x and 25 about z).
  const vpHomogeneousMatrix wMo(0.0, 0.0, 0.0, vpMath::rad(10.0), 0.0, vpMath::rad(25.0));
  std::vector<vpGravityFrame> sequence;
  std::vector<vpPoseRow> truth;
  for (unsigned int k = 0; k < frames; ++k) {
    vpPoseRow row;
    row.frame = k;
    sequence.push_back(simulateFrame(k, frames, wMo, random, row.cMo));
    truth.push_back(row);
  }
  std::string error;
  if (!vpGravityPointsIo::writePoints(output + "/points.csv", sequence, error) ||
      !vpGravityPointsIo::writePoses(output + "/groundtruth.csv", truth, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::cout << "Wrote " << frames << " frames to " << output << "/points.csv and " << output
            << "/groundtruth.csv (seed " << seed << ")" << std::endl;
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
