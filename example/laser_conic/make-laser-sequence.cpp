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

  With --hard it generates data/laser_hard instead: what real photographs of a laser ring look like, a
  960x720 wide-angle camera with lens distortion (kdu, with the kud that inverts it) on a drone-like
  trajectory at 0.5-3 m, each frame in one of the hard conditions of the detector (dim stripe on a dark
  floor, saturated stripe with bloom on white glossy tiles, bright grey floor, colourful mosaic floor, red
  distractors and clutter, an occluding object, motion blur, a few frames without laser) with sensor noise,
  followed by 9 frames of a stripe that fades along the ring (inverse-square and Lambert fall-off, 60-150 grey
  levels of red dominance near, 14-30 far; on a dark floor and on a textured floor whose reflectance scales
  the laser light; the last one faint, its far side at twice the sensor noise).

  Writes camera.xml, laser.txt (the laser pose calibrated with vpLaserConicCalibration from simulated
  grid views, as in the paper), laser_true.txt (the pose used for rendering), groundtruth.csv and
  images/frame_XXX.jpg (with --hard, conditions.csv too: the condition of each frame and what the default
  detector finds on it). The output depends
  only on the seed and the options (deterministic).
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPolygon.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicCalibration.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "laserRigSetup.h"
#include "vpCommandLine.h"
#include "vpLaserRigIo.h"

namespace
{
struct Options
{
  std::string output;
  bool hard = false;
  unsigned int frames = 0; // 0: 100 frames, 48 with --hard
  std::string diagnostics; // folder for the detector's masks (empty: none)
  unsigned int seed = 2018;
  int quality = 60;
  double sensorNoise = 1.0;
  double stripeWidth = 3.0;
};

//! The camera of the hard sequence: 960 x 720 (the size of the photographs), 80 deg wide, barrel distortion.
const unsigned int kHardWidth = 960, kHardHeight = 720;
vpCameraParameters hardCamera()
{
  // kdu: the simulator's lens (pixel -> metre); kud fitted as its inverse, as a calibration estimates both.
  return vpLaserConicSimulator::fitInverseDistortion(vpCameraParameters(575.0, 575.0, 483.5, 356.0, 0.0, 0.16),
                                                     kHardWidth, kHardHeight);
}

//! The conditions of the hard sequence (one per frame, in a fixed cycle).
enum HardCondition {
  DIM_DARK,
  SATURATED_WHITE_TILES,
  BRIGHT_GREY,
  MOSAIC,
  DISTRACTORS,
  OCCLUDED,
  MOTION_BLUR,
  NO_LASER,
  FADING_RING,      // appended after the cycle
  FADING_RING_FAINT // the last frame: the far side at about twice the sensor noise
};
//! Frames appended after the cycle with --hard: fading rings, then one faint ring.
const unsigned int kFadingFrames = 8;
const char *conditionName(HardCondition c)
{
  static const char *names[] = {"dim_dark_floor",    "saturated_white_tiles",
                                "bright_grey_floor", "colourful_floor",
                                "red_distractors",   "occluded",
                                "motion_blur",       "no_laser",
                                "fading_ring",       "fading_ring_faint"};
  return names[c];
}

//! The condition of frame k: a cycle of the first seven, and one frame in twelve without laser.
HardCondition hardCondition(unsigned int k)
{
  if (k % 12 == 11)
    return NO_LASER;
  return static_cast<HardCondition>((k - k / 12) % 7);
}

//! Render settings of a condition (the floor moves with the ground: the scene is fixed in the ground frame).
vpLaserConicSimulator::vpRenderSettings hardSettings(HardCondition c, unsigned int k, std::mt19937 &rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  vpLaserConicSimulator::vpRenderSettings s;
  s.stripeWidth = 2.0 + 1.0 * unit(rng); // a 1-3 px wide stripe after the optics
  s.noise = 2.5;
  s.laserPower = 90.0 + 60.0 * unit(rng);
  switch (c) {
  case DIM_DARK:
    s.ambient = 0.5;
    s.laserPower = 55.0 + 30.0 * unit(rng); // V about 45-110 on the stripe
    break;
  case SATURATED_WHITE_TILES:
    s.floor = vpLaserConicSimulator::FLOOR_WHITE_TILES;
    s.ambient = 0.85;
    s.specular = 45.0; // the lamp's reflection stays below the sensor's white
    s.shininess = 250.0;
    s.laserPower = 500.0 + 300.0 * unit(rng);
    s.whiteCore = 0.6;
    s.bloom = 0.05;
    s.bloomWidth = 9.0;
    break;
  case BRIGHT_GREY:
    s.floor = vpLaserConicSimulator::FLOOR_BRIGHT_GREY;
    s.ambient = 1.0;
    s.specular = 40.0;
    break;
  case MOSAIC:
    s.floor = vpLaserConicSimulator::FLOOR_MOSAIC;
    s.laserPower = 160.0 + 60.0 * unit(rng);
    s.specular = 40.0;
    break;
  case DISTRACTORS: {
    s.ambient = 0.8;
    s.clutter = 120;
    s.clutterRadius = 2.5;
    typedef vpLaserConicSimulator::vpDistractor Distractor;
    s.distractors = {Distractor::square(0.4, -0.3, 0.3), Distractor::disc(-0.5, 0.4, 0.4),
                     Distractor::line(-1.5, -0.6, 1.5, 0.2, 0.006)};
    break;
  }
  case OCCLUDED: {
    // A dark object (a leg, a box) in front of the lower right part of the image.
    const double u0 = 520.0 + 120.0 * unit(rng);
    s.occluders.push_back(
        {vpImagePoint(330, u0), vpImagePoint(300, u0 + 220), vpImagePoint(719, u0 + 300), vpImagePoint(719, u0 + 60)});
    break;
  }
  case MOTION_BLUR:
    s.motionBlurLength = 5.0 + 5.0 * unit(rng);
    s.motionBlurAngle = 2.0 * M_PI * unit(rng);
    s.floor = vpLaserConicSimulator::FLOOR_BRIGHT_GREY;
    s.ambient = 0.7;
    break;
  case NO_LASER:
    s.laserOn = false;
    s.floor = k % 2 ? vpLaserConicSimulator::FLOOR_MOSAIC : vpLaserConicSimulator::FLOOR_DARK_TILES;
    s.clutter = 120;
    s.clutterRadius = 2.5;
    break;
  case FADING_RING:
  case FADING_RING_FAINT:
    break; // fadingSettings()
  }
  return s;
}

/*!
  Render settings of the fading-ring frames: the stripe fades along the ring with the distance and the
  incidence (inverse square, Lambert cosine) from \e nearPeak to \e farPeak grey levels of red dominance
  R - max(G, B), as real photographs of a dark room show (60-150 near, 14-30 far, over a background red level
  of 0-7). Frame \e f even: the dark floor at that background; odd: a textured (bright grey, mottled) floor
  whose reflectance scales the laser light. The laser power is set from the ground truth at unit power so that
  the brightest visible part reads \e nearPeak on the median reflectance of the ring.
*/
vpLaserConicSimulator::vpRenderSettings fadingSettings(unsigned int f, double nearPeak, double farPeak, double noise,
                                                       std::mt19937 &rng, vpLaserConicSimulator &sim)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  vpLaserConicSimulator::vpRenderSettings s;
  s.stripeWidth = 2.0 + 1.0 * unit(rng);
  s.noise = noise;
  s.distanceFalloff = 2.0;
  s.lambertIncidence = true;
  s.stripeFarFraction = farPeak / nearPeak;
  const bool textured = f % 2 == 1;
  s.floor = textured ? vpLaserConicSimulator::FLOOR_BRIGHT_GREY : vpLaserConicSimulator::FLOOR_DARK_TILES;
  s.ambient = textured ? 0.45 : 0.12;
  s.reflectanceScaled = textured;
  s.laserPower = 1.0;
  std::vector<double> perUnitPower;
  for (const vpLaserConicSimulator::vpTraceTruth &t : sim.traceTruth(2000, s))
    perUnitPower.push_back(t.peakDominance / t.falloff);
  if (!perUnitPower.empty()) {
    std::nth_element(perUnitPower.begin(), perUnitPower.begin() + perUnitPower.size() / 2, perUnitPower.end());
    s.laserPower = nearPeak / perUnitPower[perUnitPower.size() / 2];
  }
  return s;
}

//! Condition of frame \e k of the hard sequence: the cycle for the first \e cycleFrames, then the fading rings.
HardCondition frameCondition(unsigned int k, unsigned int cycleFrames)
{
  if (k < cycleFrames)
    return hardCondition(k);
  return k - cycleFrames < kFadingFrames ? FADING_RING : FADING_RING_FAINT;
}

//! Settings of frame \e k of the hard sequence (see hardSettings() and fadingSettings()).
vpLaserConicSimulator::vpRenderSettings hardFrameSettings(unsigned int k, unsigned int cycleFrames, double noise,
                                                          std::mt19937 &rng, vpLaserConicSimulator &sim)
{
  const HardCondition c = frameCondition(k, cycleFrames);
  if (c == FADING_RING) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double nearPeak = 60.0 + 90.0 * unit(rng), farPeak = 14.0 + 16.0 * unit(rng);
    return fadingSettings(k - cycleFrames, nearPeak, farPeak, noise, rng, sim);
  }
  if (c == FADING_RING_FAINT)
    return fadingSettings(0, 40.0, 2.0 * noise, noise, rng, sim);
  vpLaserConicSimulator::vpRenderSettings settings = hardSettings(c, k, rng);
  settings.noise = noise;
  return settings;
}

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

//! Parameters of one SmoothSignal: mean, slow amplitude, slow cycles, wobble amplitude, wobble cycles.
typedef double SignalParameters[5];

/*!
  The states at \e frames instants of [0, 1] of six smooth signals altitude, roll, pitch, yaw, x, y (in
  that order, their phases drawn from \e rng in that order), the altitude kept above \e minAltitude.
*/
std::vector<RigState> sampleTrajectory(std::mt19937 &rng, const SignalParameters (&parameters)[6], unsigned int frames,
                                       double minAltitude)
{
  std::vector<SmoothSignal> signals;
  for (const SignalParameters &p : parameters)
    signals.push_back(SmoothSignal(rng, p[0], p[1], p[2], p[3], p[4]));
  std::vector<RigState> states;
  for (unsigned int k = 0; k < frames; ++k) {
    const double t = frames > 1 ? k / static_cast<double>(frames - 1) : 0.0;
    states.push_back({std::max(minAltitude, signals[0](t)), signals[1](t), signals[2](t), signals[3](t), signals[4](t),
                      signals[5](t)});
  }
  return states;
}

std::vector<RigState> trajectory(unsigned int frames, unsigned int seed)
{
  std::mt19937 rng(seed);
  // Amplitudes keep the altitude in [0.55, 1.45] m and the tilts within +-(15 + 3) deg.
  const SignalParameters parameters[6] = {{1.0, 0.38, 1.3, 0.05, 5.0},
                                          {0.0, vpMath::rad(15.0), 1.7, vpMath::rad(3.0), 6.5},
                                          {0.0, vpMath::rad(14.0), 1.1, vpMath::rad(3.0), 7.3},
                                          {0.0, vpMath::rad(40.0), 0.6, vpMath::rad(2.0), 4.0},
                                          {0.0, 1.0, 0.5, 0.02, 6.0},
                                          {0.0, 0.6, 0.8, 0.02, 5.5}};
  return sampleTrajectory(rng, parameters, frames, 0.0);
}

/*!
  The drone-like trajectory of the hard sequence: altitude 0.5-3 m, roll and pitch within about +-25 deg,
  yaw and horizontal drift; the low, tilted frames put part of the trace out of the image.
*/
std::vector<RigState> hardTrajectory(unsigned int frames, unsigned int seed)
{
  std::mt19937 rng(seed + 1);
  const SignalParameters parameters[6] = {{1.7, 1.15, 1.2, 0.08, 4.0},
                                          {0.0, vpMath::rad(20.0), 1.6, vpMath::rad(4.0), 6.5},
                                          {0.0, vpMath::rad(18.0), 1.3, vpMath::rad(4.0), 7.3},
                                          {0.0, vpMath::rad(60.0), 0.7, vpMath::rad(3.0), 4.0},
                                          {0.0, 0.6, 0.6, 0.02, 6.0},
                                          {0.0, 0.4, 0.9, 0.02, 5.5}};
  return sampleTrajectory(rng, parameters, frames, 0.5);
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
      const double bottom = grid[(gy + 1) * (cells + 1) + gx] * (1.0 - fx) + grid[(gy + 1) * (cells + 1) + gx + 1] * fx;
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
vpHomogeneousMatrix calibrateLaser(const vpCameraParameters &cam, unsigned int width, unsigned int height,
                                   double openingAngle, const vpHomogeneousMatrix &cMl, unsigned int seed, double &rms)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> distance(0.6, 1.2), tilt(vpMath::rad(-25.0), vpMath::rad(25.0)),
      yaw(-M_PI, M_PI);
  std::normal_distribution<double> gridTranslationError(0.0, 1e-3), gridRotationError(0.0, vpMath::rad(0.1));
  vpLaserConicSimulator sim;
  sim.setCamera(cam, width, height);
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
    const vpHomogeneousMatrix gridError(gridTranslationError(rng), gridTranslationError(rng), gridTranslationError(rng),
                                        gridRotationError(rng), gridRotationError(rng), gridRotationError(rng));
    calibration.addView(cMg * gridError, points);
  }
  vpHomogeneousMatrix calibrated;
  rms = calibration.calibrate(calibrated);
  return calibrated;
}

/*!
  How well the default vpLaserConicDetector finds the rendered trace: the share of the exact trace (sampled
  about every 0.3 px, away from the image border and from the occluders) with a detected point within
  1 px, and the RMS distance of the points within 2 px of the trace to it.
*/
void detectorQuality(vpLaserConicSimulator &sim, const vpLaserConicSimulator::vpRenderSettings &settings,
                     const std::vector<vpImagePoint> &points, unsigned int width, unsigned int height, double &coverage,
                     double &rms)
{
  const std::vector<vpImagePoint> trace = sim.tracePoints(20000);
  std::vector<vpPolygon> occluders;
  for (const std::vector<vpImagePoint> &polygon : settings.occluders)
    occluders.push_back(vpPolygon(polygon));
  // Detections by 2-pixel cell, for the nearest-point queries.
  std::map<std::pair<int, int>, std::vector<vpImagePoint> > cells;
  for (const vpImagePoint &p : points)
    cells[std::make_pair(static_cast<int>(p.get_u() / 2), static_cast<int>(p.get_v() / 2))].push_back(p);
  auto nearest = [&cells](const vpImagePoint &q) {
    double best = 1e30;
    const int cx = static_cast<int>(q.get_u() / 2), cy = static_cast<int>(q.get_v() / 2);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = cells.find(std::make_pair(cx + dx, cy + dy));
        if (it != cells.end())
          for (const vpImagePoint &p : it->second)
            best = std::min(best, vpImagePoint::distance(p, q));
      }
    return best;
  };
  size_t visible = 0, found = 0;
  for (const vpImagePoint &t : trace) {
    if (t.get_u() < 15 || t.get_v() < 15 || t.get_u() > width - 16.0 || t.get_v() > height - 16.0)
      continue;
    bool hidden = false;
    for (const vpPolygon &o : occluders)
      hidden = hidden || o.isInside(t) || o.isInside(vpImagePoint(t.get_i() + 4, t.get_j())) ||
               o.isInside(vpImagePoint(t.get_i() - 4, t.get_j())) ||
               o.isInside(vpImagePoint(t.get_i(), t.get_j() + 4)) || o.isInside(vpImagePoint(t.get_i(), t.get_j() - 4));
    if (hidden)
      continue;
    ++visible;
    found += nearest(t) <= 1.0 ? 1 : 0;
  }
  coverage = visible ? static_cast<double>(found) / visible : 0.0;
  // RMS: distance of each point to the trace (the samples are ~0.3 px apart: nearest sample within 0.01 px).
  std::map<std::pair<int, int>, std::vector<vpImagePoint> > traceCells;
  for (const vpImagePoint &t : trace)
    traceCells[std::make_pair(static_cast<int>(t.get_u() / 2), static_cast<int>(t.get_v() / 2))].push_back(t);
  double sum2 = 0.0;
  size_t on = 0;
  for (const vpImagePoint &p : points) {
    double best = 1e30;
    const int cx = static_cast<int>(p.get_u() / 2), cy = static_cast<int>(p.get_v() / 2);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = traceCells.find(std::make_pair(cx + dx, cy + dy));
        if (it != traceCells.end())
          for (const vpImagePoint &t : it->second)
            best = std::min(best, vpImagePoint::distance(p, t));
      }
    if (best <= 2.0) {
      sum2 += best * best;
      ++on;
    }
  }
  rms = on ? std::sqrt(sum2 / on) : 0.0;
}

/*!
  The default detector on the frame as shipped (the JPEG \e file): in \e coverage the share of the ring's length
  where the stripe is at least 3 times the sensor noise with a detected point within 1.5 px of the true centre
  line (vpLaserConicSimulator::stripeCoverage()), and in \e kept the same share over the ring where what the
  JPEG compression at \e quality kept of the stripe is still 3 times the noise
  (vpLaserConicSimulator::keptCoverage()), measured on \e beforeRendering, a copy of the simulator made before
  the frame was rendered (the simulator's codec gives the pixels vpImageIo::writeJPEG() writes: libjpeg at the
  same quality). NaN without laser; \e kept NaN without the copy.
*/
void coverageOnShippedFrame(vpLaserConicSimulator &sim, const vpLaserConicSimulator *beforeRendering,
                            const vpLaserConicSimulator::vpRenderSettings &settings, int quality,
                            const std::string &file, double &coverage, double &kept)
{
  coverage = kept = std::numeric_limits<double>::quiet_NaN();
  if (!settings.laserOn)
    return;
  vpImage<vpRGBa> I;
  vpImageIo::read(I, file);
  vpLaserConicDetector detector;
  const std::vector<vpImagePoint> points = detector.detect(I);
  std::vector<vpLaserConicSimulator::vpTraceTruth> truth = sim.traceTruth(20000, settings);
  coverage = vpLaserConicSimulator::stripeCoverage(truth, points, 3.0, 1.5);
  if (beforeRendering == nullptr)
    return;
  // The truth does not depend on the compression: the same samples serve.
  vpLaserConicSimulator::vpRenderSettings compressed = settings;
  compressed.jpegQuality = quality;
  beforeRendering->measureCompression(truth, compressed);
  kept = vpLaserConicSimulator::keptCoverage(truth, points, 3.0, 1.5);
}

//! Distance between the apexes (m) and angle between the cone axes (rad) of two laser poses.
void laserPoseError(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &apexError, double &axisError)
{
  apexError =
      std::sqrt(vpMath::sqr(a[0][3] - b[0][3]) + vpMath::sqr(a[1][3] - b[1][3]) + vpMath::sqr(a[2][3] - b[2][3]));
  const double dot = a[0][2] * b[0][2] + a[1][2] * b[1][2] + a[2][2] * b[2][2];
  axisError = std::acos(std::max(-1.0, std::min(1.0, dot)));
}

//! Declares the options of the program; \e opt receives their values.
vpCommandLine commandLine(Options &opt)
{
  vpCommandLine cli("[--hard] [--output DIR] [--frames N] [--seed S] [--quality Q] [--sensor-noise GREY]",
                    "Writes the simulated hand-held laser sequence (camera.xml, laser.txt, groundtruth.csv, images/),\n"
                    "or with --hard the sequence of hard conditions with a distorted wide-angle camera.");
  cli.addFlag("--hard", opt.hard, "the hard sequence (default output " VSP_DATA_DIR "/laser_hard, 48 + 9 frames)");
  cli.addString("--output", opt.output, "DIR", "default " VSP_DATA_DIR "/laser_sequence (laser_hard with --hard)");
  cli.addString("--diagnostics", opt.diagnostics, "DIR",
                "with --hard: also write each frame with the default detector's mask over it (PNG) to DIR");
  cli.addUnsigned("--frames", opt.frames, "N",
                  "number of frames (default 100; with --hard 48 of the cycle, then 9 fading rings)", 1);
  cli.addUnsigned("--seed", opt.seed, "S", "trajectory and rendering seed (default 2018)");
  cli.addInt("--quality", opt.quality, "Q", "JPEG quality (default 60)", 1, 100);
  cli.addDouble("--sensor-noise", opt.sensorNoise, "GREY", "sensor noise standard deviation, grey levels (default 1)",
                vpCommandLine::NON_NEGATIVE);
  return cli;
}
//! The program's work once its options are read; returns its exit status.
int run(Options &opt, const vpCommandLine &)
{
  if (opt.output.empty())
    opt.output = std::string(VSP_DATA_DIR) + (opt.hard ? "/laser_hard" : "/laser_sequence");
  if (opt.frames == 0)
    opt.frames = opt.hard ? 48 : 100;
  try {
    vpIoTools::makeDirectory(opt.output + "/images");
    const vpCameraParameters cam = opt.hard ? hardCamera() : vspLaserRig::camera();
    const unsigned int width = opt.hard ? kHardWidth : vspLaserRig::kWidth;
    const unsigned int height = opt.hard ? kHardHeight : vspLaserRig::kHeight;
    const double openingAngle = vpMath::rad(vspLaserRig::kOpeningAngleDeg);
    const vpHomogeneousMatrix cMl = vspLaserRig::laserPose();
    double rms = 0.0, apexError = 0.0, axisError = 0.0;
    const vpHomogeneousMatrix cMlCalibrated = calibrateLaser(cam, width, height, openingAngle, cMl, opt.seed, rms);
    laserPoseError(cMlCalibrated, cMl, apexError, axisError);
    std::cout << "Laser calibration from 16 simulated grid views: RMS " << rms * 1e3 << " mm, apex error "
              << apexError * 1e3 << " mm, axis error " << vpMath::deg(axisError) << " deg" << std::endl;
    std::string error;
    if (!vpLaserRigIo::writeCamera(opt.output + "/camera.xml", cam, width, height, error) ||
        !vpLaserRigIo::writeLaserCalibration(opt.output + "/laser.txt", openingAngle, cMlCalibrated, error) ||
        !vpLaserRigIo::writeLaserCalibration(opt.output + "/laser_true.txt", openingAngle, cMl, error)) {
      std::cerr << error << std::endl;
      return EXIT_FAILURE;
    }

    const vpImage<vpRGBa> floor = darkFloorTexture(opt.seed);
    vpLaserConicSimulator sim;
    sim.setCamera(cam, width, height);
    sim.setLaser(openingAngle, cMl);
    std::vector<vpLaserGroundTruthFrame> frames;
    std::vector<RigState> states = opt.hard ? hardTrajectory(opt.frames, opt.seed) : trajectory(opt.frames, opt.seed);
    if (opt.hard) { // the fading rings after the cycle, on a trajectory of their own (the cycle's frames unchanged)
      const std::vector<RigState> fading = hardTrajectory(kFadingFrames + 1, opt.seed + 50);
      states.insert(states.end(), fading.begin(), fading.end());
    }
    std::ofstream conditions;
    if (opt.hard) {
      conditions.open(opt.output + "/conditions.csv");
      conditions << "frame,image,condition,detected_points,detector_coverage,detector_rms_px,"
                    "detector_coverage_3sigma,detector_kept_coverage_3sigma\n";
      if (!conditions) {
        std::cerr << "Cannot write " << opt.output << "/conditions.csv" << std::endl;
        return EXIT_FAILURE;
      }
    }
    std::mt19937 settingsRng(opt.seed + 7);
    vpLaserConicDetector detector;
    if (!opt.diagnostics.empty())
      vpIoTools::makeDirectory(opt.diagnostics);
    double worstCoverage = 1.0, worstRms = 0.0;
    std::string qualityLine;
    std::ostringstream fadingCoverage;
    for (unsigned int k = 0; k < states.size(); ++k) {
      const RigState &s = states[k];
      sim.setGroundPose(vspLaserRig::groundPose(s.altitude, s.roll, s.pitch, s.yaw, s.x, s.y));
      // Reseeding per frame makes each image reproducible on its own (the hard sequence keeps one scene
      // seed: its floors and clutter stay fixed in the ground frame).
      sim.setSeed(opt.seed + k);
      vpImage<vpRGBa> I;
      vpLaserConicSimulator::vpRenderSettings settings;
      // The fading rings: what the compression keeps of their stripe is measured on the simulator as it was
      // before the render (the same noise draws).
      std::unique_ptr<vpLaserConicSimulator> beforeRendering;
      if (opt.hard && frameCondition(k, opt.frames) >= FADING_RING)
        beforeRendering = std::make_unique<vpLaserConicSimulator>(sim);
      if (opt.hard) {
        settings = hardFrameSettings(k, opt.frames, 2.5 * opt.sensorNoise, settingsRng, sim);
        settings.sceneSeed = static_cast<int>(opt.seed);
        sim.render(I, settings);
        // The default detector on the rendered frame (before the JPEG compression): how much of the trace it finds.
        const std::vector<vpImagePoint> points = detector.detect(I);
        std::ostringstream quality;
        quality << points.size();
        if (settings.laserOn) {
          double coverage = 0.0, detectionRms = 0.0;
          detectorQuality(sim, settings, points, width, height, coverage, detectionRms);
          worstCoverage = std::min(worstCoverage, coverage);
          worstRms = std::max(worstRms, detectionRms);
          quality << "," << std::setprecision(4) << coverage << "," << detectionRms;
        } else
          quality << ",nan,nan";
        qualityLine = quality.str();
        if (!opt.diagnostics.empty()) {
          vpImage<vpRGBa> O = I;
          const vpImage<unsigned char> &mask = detector.getMask();
          for (unsigned int i = 0; i < O.getHeight(); ++i)
            for (unsigned int j = 0; j < O.getWidth(); ++j)
              if (mask[i][j])
                O[i][j] = mask[i][j] == 255 ? vpRGBa(0, 255, 0, 255) : vpRGBa(0, 128, 255, 255);
          std::ostringstream file;
          file << opt.diagnostics << "/mask_" << std::setw(3) << std::setfill('0') << k << ".png";
          vpImageIo::write(O, file.str());
        }
      } else
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
        std::cerr << "Frame " << k << ": the ground truth convention disagrees with vpLaserConicPose (" << f.altitude
                  << ", " << f.roll << ", " << f.pitch << " vs " << s.altitude << ", " << s.roll << ", " << s.pitch
                  << ")" << std::endl;
        return EXIT_FAILURE;
      }
      vpImageIo::writeJPEG(I, opt.output + "/" + f.image, vpImageIo::IO_DEFAULT_BACKEND, opt.quality);
      frames.push_back(f);
      if (opt.hard) {
        double coverage = 0.0, kept = 0.0;
        coverageOnShippedFrame(sim, beforeRendering.get(), settings, opt.quality, opt.output + "/" + f.image, coverage,
                               kept);
        conditions << k << "," << f.image << "," << conditionName(frameCondition(k, opt.frames)) << "," << qualityLine
                   << "," << std::setprecision(4) << coverage << "," << kept << "\n";
        if (frameCondition(k, opt.frames) >= FADING_RING) {
          double nearPeak = 0.0, farPeak = 1e9;
          for (const vpLaserConicSimulator::vpTraceTruth &t : sim.traceTruth(2000, settings)) {
            nearPeak = std::max(nearPeak, t.peakDominance);
            farPeak = std::min(farPeak, t.peakDominance);
          }
          fadingCoverage << "\n  " << f.image << " (" << conditionName(frameCondition(k, opt.frames)) << ", stripe "
                         << std::setprecision(3) << nearPeak << " to " << farPeak
                         << " grey levels of red dominance): " << 100.0 * coverage
                         << " %, of what JPEG kept at 3 sigma " << 100.0 * kept << " %";
        }
      }
      std::cout << f.image << ": altitude " << std::setprecision(4) << f.altitude << " m, roll " << vpMath::deg(f.roll)
                << " deg, pitch " << vpMath::deg(f.pitch) << " deg"
                << (opt.hard ? std::string(", ") + conditionName(frameCondition(k, opt.frames)) : std::string())
                << std::endl;
    }
    if (opt.hard) {
      conditions.close();
      if (!conditions) {
        std::cerr << "Cannot write " << opt.output << "/conditions.csv (the disk full?)" << std::endl;
        return EXIT_FAILURE;
      }
    }
    if (!vpLaserRigIo::writeGroundTruth(opt.output + "/groundtruth.csv", frames, error)) {
      std::cerr << error << std::endl;
      return EXIT_FAILURE;
    }
    std::cout << "Wrote " << frames.size() << " frames to " << opt.output << std::endl;
    if (opt.hard)
      std::cout << "Default detector on the frames with laser: coverage >= " << 100.0 * worstCoverage
                << " %, RMS distance to the trace <= " << worstRms << " px (conditions.csv)\n"
                << "Default detector on the fading rings as shipped (JPEG): share of the ring where the stripe "
                << "is >= 3x the noise with a point within 1.5 px of the true centre line" << fadingCoverage.str()
                << std::endl;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv) { return vpRunProgram(argc, argv, commandLine, run); }
