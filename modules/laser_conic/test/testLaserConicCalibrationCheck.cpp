/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  The calibration check of vpLaserConicPose (setCalibrationCheck()): each standard mistake (half
  opening angle, lMc for cMl, u and v swapped, intrinsics of another resolution) is refused with
  STATUS_CALIBRATION_MISMATCH and named by getSuspectedMistake(); a right calibration is not refused,
  on simulated traces (Monte Carlo) and on the shipped image sequences (at most 0.5 % of the frames).
*/
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include <visp3/core/vpXmlParserCamera.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "laser_test_utils.h"

namespace
{
using laser_test::Scene;

//! The mistakes made on a right rig, as a user would give them to the estimator.
enum class Mistake { NONE, HALF_ANGLE, INVERSE_POSE, SWAPPED_UV, HALF_RESOLUTION };

//! An estimator configured with \e mistake on \e rig; \e points are changed as the mistake implies.
vpLaserConicPose configured(const laser_test::Rig &rig, Mistake mistake, std::vector<vpImagePoint> &points)
{
  vpLaserConicPose estimator;
  const vpCameraParameters &c = rig.cam;
  estimator.setCameraParameters(
      mistake == Mistake::HALF_RESOLUTION
          ? vpCameraParameters(0.5 * c.get_px(), 0.5 * c.get_py(), 0.5 * c.get_u0(), 0.5 * c.get_v0())
          : c);
  estimator.setLaser(mistake == Mistake::HALF_ANGLE ? 0.5 * rig.openingAngle : rig.openingAngle,
                     mistake == Mistake::INVERSE_POSE ? rig.cMl.inverse() : rig.cMl);
  if (mistake == Mistake::SWAPPED_UV)
    for (vpImagePoint &p : points)
      p.set_uv(p.get_v(), p.get_u());
  return estimator;
}

struct Count
{
  int refused = 0, named = 0, total = 0;
};

//! Runs \e scenes simulated traces (0.5 px noise) through \e method with \e mistake.
Count simulate(vpLaserConicPose::vpLaserConicMethod method, Mistake mistake, vpLaserConicPose::vpLaserConicMistake name,
               int scenes, unsigned int seed)
{
  std::mt19937 rng(seed);
  Count count;
  for (int k = 0; k < scenes; ++k) {
    std::vector<vpImagePoint> points;
    Scene s;
    do
      s = laser_test::randomScene(rng, laser_test::SceneRanges(), 360, points);
    while (method == vpLaserConicPose::PP3 && laser_test::cameraInsideCone(laser_test::toCone(s.rig)));
    points = laser_test::addNoise(points, 0.5, rng);
    vpLaserConicPose estimator = configured(s.rig, mistake, points);
    estimator.setRansacSeed(static_cast<unsigned int>(k));
    vpPlane plane;
    ++count.total;
    if (!estimator.computePlane(points, method, plane) &&
        estimator.getStatus() == vpLaserConicPose::STATUS_CALIBRATION_MISMATCH) {
      ++count.refused;
      count.named += estimator.getSuspectedMistake() == name ? 1 : 0;
      EXPECT_NE(estimator.getFailureReason().find("half opening angle"), std::string::npos);
    }
  }
  return count;
}
} // namespace

// Each mistake on simulated traces: a right estimate is impossible with the wrong calibration, so a
// plane is either refused or, when the wrong rig cannot even produce a consensus, refused by another
// status; never STATUS_OK with a wrong calibration that the check can see. The mistake is named.
TEST(LaserConicCalibrationCheck, EachMistakeIsRefusedAndNamed)
{
  const std::vector<std::pair<Mistake, vpLaserConicPose::vpLaserConicMistake> > cases = {
      {Mistake::HALF_ANGLE, vpLaserConicPose::MISTAKE_HALF_OPENING_ANGLE},
      {Mistake::INVERSE_POSE, vpLaserConicPose::MISTAKE_INVERSE_LASER_POSE},
      {Mistake::SWAPPED_UV, vpLaserConicPose::MISTAKE_SWAPPED_UV},
      {Mistake::HALF_RESOLUTION, vpLaserConicPose::MISTAKE_CAMERA_RESOLUTION}};
  const int kScenes = 40;
  for (const auto &c : cases) {
    for (vpLaserConicPose::vpLaserConicMethod method : {vpLaserConicPose::GP3, vpLaserConicPose::PP5}) {
      const Count count = simulate(method, c.first, c.second, kScenes, 77);
      std::printf("mistake %d, method %d: %d/%d refused as a calibration mismatch, %d named right\n",
                  static_cast<int>(c.first), static_cast<int>(method), count.refused, count.total, count.named);
      // The wrong rig's own failures (no consensus, plane behind...) are diagnosed too.
      // Measured: 35-40 of 40 per case (the others fail with the wrong rig's own status, never ok).
      EXPECT_GE(count.refused, 8 * count.total / 10);
      EXPECT_GE(count.named, 8 * count.refused / 10);
    }
  }
}

// No wrong calibration of the cases above is accepted: every frame fails, whatever its status.
TEST(LaserConicCalibrationCheck, NoMistakeGivesAPlane)
{
  std::mt19937 rng(91);
  for (Mistake mistake : {Mistake::HALF_ANGLE, Mistake::INVERSE_POSE, Mistake::SWAPPED_UV}) {
    int accepted = 0;
    for (int k = 0; k < 30; ++k) {
      std::vector<vpImagePoint> points;
      const Scene s = laser_test::randomScene(rng, laser_test::SceneRanges(), 360, points);
      points = laser_test::addNoise(points, 0.5, rng);
      vpLaserConicPose estimator = configured(s.rig, mistake, points);
      vpPlane plane;
      accepted += estimator.computePlane(points, vpLaserConicPose::GP3, plane) ? 1 : 0;
    }
    EXPECT_LE(accepted, 1) << "mistake " << static_cast<int>(mistake);
  }
}

// Right calibration, 0.5 px noise: the check refuses at most 0.5 % of the estimates (measured: none
// of 600 per method; 200 per method here). The misfit it allows is 30 times the noise; the misfit a right calibration
// leaves is a small fraction of the noise. (Intrinsics off by 5 px: LaserConicPose.ToleratesIntrinsicErrors.)
TEST(LaserConicCalibrationCheck, RightCalibrationIsNotRefused)
{
  const int kScenes = 200;
  int refused = 0, total = 0;
  for (vpLaserConicPose::vpLaserConicMethod method :
       {vpLaserConicPose::GP3, vpLaserConicPose::PP3, vpLaserConicPose::PP5, vpLaserConicPose::PLANE_PAIR}) {
    const Count count = simulate(method, Mistake::NONE, vpLaserConicPose::MISTAKE_UNKNOWN, kScenes, 2024);
    std::printf("method %d, right calibration: %d/%d refused as a calibration mismatch\n", static_cast<int>(method),
                count.refused, count.total);
    refused += count.refused;
    total += count.total;
  }
  EXPECT_LE(refused * 200, total);
}

// Right calibration, a part of the ring only (30 % of its points, as where most of the ring is out of view or
// hidden): the estimate may be refused as a short arc or a weak trace, but a calibration that fits the trace it
// sees is not blamed. Any calibration fits a short arc, and the alternatives tried after such a refusal were
// taken whenever one fitted (measured before: 68 of 300 GP-3 estimates on 108 points at 0.5 px, 189 of 300 at
// 1.5 px, refused as a calibration mismatch, each naming a mistake the rig did not have).
TEST(LaserConicCalibrationCheck, ARightCalibrationOnAPartOfTheRingIsNotBlamed)
{
  std::mt19937 rng(404);
  int blamed = 0, refused = 0, total = 0;
  for (vpLaserConicPose::vpLaserConicMethod method : {vpLaserConicPose::GP3, vpLaserConicPose::PP3}) {
    for (double noise : {0.5, 1.5}) {
      for (int k = 0; k < 60; ++k) {
        std::vector<vpImagePoint> points;
        Scene s;
        do
          s = laser_test::randomScene(rng, laser_test::SceneRanges(), 360, points);
        while (method == vpLaserConicPose::PP3 && laser_test::cameraInsideCone(laser_test::toCone(s.rig)));
        const size_t first = static_cast<size_t>(k % 10) * 36;
        std::vector<vpImagePoint> part;
        for (size_t j = 0; j < 108; ++j)
          part.push_back(points[(first + j) % points.size()]);
        part = laser_test::addNoise(part, noise, rng);
        vpLaserConicPose estimator = configured(s.rig, Mistake::NONE, part);
        estimator.setRansacSeed(static_cast<unsigned int>(k));
        vpPlane plane;
        ++total;
        if (!estimator.computePlane(part, method, plane)) {
          ++refused;
          blamed += estimator.getStatus() == vpLaserConicPose::STATUS_CALIBRATION_MISMATCH ? 1 : 0;
        }
      }
    }
  }
  std::printf("right calibration, 30 %% of the ring: %d of %d refused, %d of them as a calibration mismatch\n", refused,
              total, blamed);
  EXPECT_LE(blamed * 100, total);
}

namespace
{
//! Reads the shipped laser.txt ('opening_angle_deg A', 'cMl', 4 rows).
bool readLaser(const std::string &file, double &angle, vpHomogeneousMatrix &cMl)
{
  std::ifstream in(file);
  std::string line, key;
  int row = -1;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream s(line);
    if (row < 0) {
      s >> key;
      if (key == "opening_angle_deg")
        s >> angle;
      else if (key == "cMl")
        row = 0;
      continue;
    }
    for (unsigned int j = 0; j < 4; ++j)
      s >> cMl[static_cast<unsigned int>(row)][j];
    if (++row == 4)
      break;
  }
  angle = vpMath::rad(angle);
  return row == 4;
}

//! Statuses of GP3 on a shipped sequence with one calibration, and how often the mistake \e named was named.
struct SequenceRun
{
  std::map<int, int> statuses; //!< frames per status (-1: fewer than 3 trace points)
  int named = 0;               //!< frames whose suspected mistake is the one expected
  std::vector<int> accepted;   //!< frames with a plane
};

/*!
  GP3 on every frame of a shipped sequence, with its calibration (runs[0]), the half opening angle
  (runs[1]), the inverse laser pose, lMc for cMl (runs[2]), and u and v swapped in the points (runs[3]).
*/
std::vector<SequenceRun> sequenceStatuses(const std::string &sequence)
{
  const std::string folder = std::string(VSP_DATA_DIR) + "/" + sequence;
  vpCameraParameters cam;
  vpXmlParserCamera parser;
  if (parser.parse(cam, folder + "/camera.xml", "Camera", vpCameraParameters::perspectiveProjWithDistortion) !=
      vpXmlParserCamera::SEQUENCE_OK) {
    EXPECT_EQ(parser.parse(cam, folder + "/camera.xml", "Camera", vpCameraParameters::perspectiveProjWithoutDistortion),
              vpXmlParserCamera::SEQUENCE_OK);
  }
  double angle = 0.0;
  vpHomogeneousMatrix cMl;
  EXPECT_TRUE(readLaser(folder + "/laser.txt", angle, cMl));
  std::vector<std::string> images;
  for (const auto &entry : std::filesystem::directory_iterator(folder + "/images"))
    images.push_back(entry.path().string());
  std::sort(images.begin(), images.end());
  vpLaserConicDetector detector;
  const std::vector<std::pair<double, vpHomogeneousMatrix> > rigs = {{angle, cMl},
                                                                     {0.5 * angle, cMl},
                                                                     {angle, cMl.inverse()},
                                                                     {angle, cMl}};
  const vpLaserConicPose::vpLaserConicMistake expected[] = {vpLaserConicPose::MISTAKE_UNKNOWN,
                                                            vpLaserConicPose::MISTAKE_HALF_OPENING_ANGLE,
                                                            vpLaserConicPose::MISTAKE_INVERSE_LASER_POSE,
                                                            vpLaserConicPose::MISTAKE_SWAPPED_UV};
  std::vector<SequenceRun> runs(rigs.size());
  // Every frame; every third under the sanitizers (laser_test::trials), where the same paths run.
  const size_t stride = static_cast<size_t>(laser_test::trials(1, 3));
  for (size_t frame = 0; frame < images.size(); frame += stride) {
    vpImage<vpRGBa> I;
    vpImageIo::read(I, images[frame]);
    const std::vector<vpImagePoint> points = detector.detect(I);
    std::vector<vpImagePoint> swapped = points;
    for (vpImagePoint &p : swapped)
      p.set_uv(p.get_v(), p.get_u());
    for (size_t r = 0; r < rigs.size(); ++r) {
      if (points.size() < 3) {
        ++runs[r].statuses[-1];
        continue;
      }
      vpLaserConicPose estimator;
      estimator.setCameraParameters(cam);
      estimator.setLaser(rigs[r].first, rigs[r].second);
      vpPlane plane;
      if (estimator.computePlane(r == 3 ? swapped : points, vpLaserConicPose::GP3, plane))
        runs[r].accepted.push_back(static_cast<int>(frame));
      ++runs[r].statuses[estimator.getStatus()];
      runs[r].named += estimator.getSuspectedMistake() == expected[r] ? 1 : 0;
    }
  }
  return runs;
}
} // namespace

// The shipped sequences (157 frames, rendered with detector bias, blur, saturation): no frame refused
// with the right calibration; with the half opening angle (17 deg for 34), the inverse laser pose
// (lMc given for cMl) or u and v swapped, almost every frame that has a trace is refused, and named;
// none gives a plane.
TEST(LaserConicCalibrationCheck, ShippedSequences)
{
  for (const std::string sequence : {"laser_hard", "laser_sequence"}) {
    const std::vector<SequenceRun> runs = sequenceStatuses(sequence);
    int frames = 0;
    for (const auto &s : runs[0].statuses)
      frames += s.second;
    const int right = runs[0].statuses.count(vpLaserConicPose::STATUS_CALIBRATION_MISMATCH)
                          ? runs[0].statuses.at(vpLaserConicPose::STATUS_CALIBRATION_MISMATCH)
                          : 0;
    std::printf("%s: %d frames, %zu ok, %d refused as a calibration mismatch (right calibration)\n", sequence.c_str(),
                frames, runs[0].accepted.size(), right);
    EXPECT_LE(200 * right, frames) << sequence;
    const char *names[] = {"", "half opening angle", "inverse laser pose", "u and v swapped"};
    for (size_t r = 1; r < runs.size(); ++r) {
      const int refused = runs[r].statuses.count(vpLaserConicPose::STATUS_CALIBRATION_MISMATCH)
                              ? runs[r].statuses.at(vpLaserConicPose::STATUS_CALIBRATION_MISMATCH)
                              : 0;
      std::printf("%s, %s: %zu ok, %d refused, %d named\n", sequence.c_str(), names[r], runs[r].accepted.size(),
                  refused, runs[r].named);
      for (int frame : runs[r].accepted)
        std::printf("  frame %d gives a plane with the %s\n", frame, names[r]);
      // No plane at all. With the half angle, frames the misfit test let through collapsed onto planes
      // through the rig (STATUS_PLANE_BEHIND now refuses them); with the inverse pose, 2 frames of
      // laser_hard gave planes 0.7 m off whose misfit the noise did not explain but the tolerance for
      // imperfect calibrations did (see laser_calibration_check.h); with u and v swapped, frame 42 (red
      // distractors) gave a plane at 6 cm, a fit whose inliers were crossings of the trace and clutter, of
      // noise scale 2.8 px where the right calibration's fit has 0.21 px (localNoise()).
      EXPECT_TRUE(runs[r].accepted.empty()) << sequence << ", " << names[r];
      EXPECT_GE(runs[r].named, 8 * refused / 10) << sequence << ", " << names[r];
    }
  }
}
