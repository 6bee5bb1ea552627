/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \example vsp-compare-poses.cpp
  Compares a pose file written by vsp-gravity-pose with a ground-truth pose file (same format,
  matched by frame index): prints the translation and rotation errors (mean, median, maximum),
  counted against the ground truth. Exit status 1 when the files do not match (a ground-truth frame
  absent from the estimate, an estimated frame without a ground truth, a frame with two rows), when
  more frames than --max-missing have a status word instead of a pose, or when a median exceeds its
  bound.

  \verbatim
  vsp-compare-poses --estimate poses.csv --truth groundtruth.csv
                    [--max-median-translation METRES] [--max-median-rotation-deg DEG]
  \endverbatim
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>

#include "vpCommandLine.h"
#include "vpGravityPointsIo.h"

namespace
{
double median(std::vector<double> v)
{
  if (v.empty())
    return std::nan("");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double> &v)
{
  double s = 0.0;
  for (double x : v)
    s += x;
  return v.empty() ? std::nan("") : s / v.size();
}

void summarize(const std::string &name, const std::vector<double> &v, double scale, const std::string &unit)
{
  const double maxValue = v.empty() ? std::nan("") : *std::max_element(v.begin(), v.end());
  std::cout << name << ": mean " << mean(v) * scale << " " << unit << ", median " << median(v) * scale << " " << unit
            << ", max " << maxValue * scale << " " << unit << std::endl;
}

int run(int argc, char **argv)
{
  std::string estimateFile, truthFile, error;
  double maxTranslation = -1.0, maxRotationDeg = -1.0;
  unsigned int maxMissing = 0;
  vpCommandLine cli("--estimate poses.csv --truth groundtruth.csv [--max-median-translation M]\n"
                    "          [--max-median-rotation-deg D] [--max-missing N]",
                    "Translation and rotation errors of a pose file against a ground-truth pose file.");
  cli.addString("--estimate", estimateFile, "FILE", "poses 'frame,status,tx,ty,tz,tux,tuy,tuz' (vsp-gravity-pose)");
  cli.addString("--truth", truthFile, "FILE", "ground-truth poses in the same format");
  cli.addDouble("--max-median-translation", maxTranslation, "M",
                "exit status 1 when the median translation error exceeds M metres", vpCommandLine::NON_NEGATIVE);
  cli.addDouble("--max-median-rotation-deg", maxRotationDeg, "D",
                "exit status 1 when the median rotation error exceeds D degrees", vpCommandLine::NON_NEGATIVE);
  cli.addUnsigned("--max-missing", maxMissing, "N",
                  "frames allowed without a pose (a status word instead: refused, in motion, ...); default 0");
  cli.require({"--estimate", "--truth"});
  if (!cli.parse(argc, argv))
    return cli.exitStatus();

  std::vector<vpPoseRow> estimates, truth;
  if (!vpGravityPointsIo::readPoses(estimateFile, estimates, error) ||
      !vpGravityPointsIo::readPoses(truthFile, truth, error)) {
    std::cerr << argv[0] << ": " << error << std::endl;
    return EXIT_FAILURE;
  }
  std::map<unsigned int, vpHomogeneousMatrix> truthByFrame;
  for (const vpPoseRow &row : truth) {
    // A truth row with a status word has no pose (its cMo is the identity): compared, it made an error of
    // metres out of a frame without a ground truth.
    if (row.status != "ok") {
      std::cerr << argv[0] << ": " << truthFile << ": frame " << row.frame << " has no pose ('" << row.status
                << "'): every ground-truth row needs one" << std::endl;
      return EXIT_FAILURE;
    }
    if (!truthByFrame.emplace(row.frame, row.cMo).second) {
      std::cerr << argv[0] << ": " << truthFile << ": frame " << row.frame << " appears twice in the ground truth"
                << std::endl;
      return EXIT_FAILURE;
    }
  }

  // Counted against the truth: every truth frame once in the estimate, nothing else.
  std::vector<double> translationErrors, rotationErrors;
  std::map<unsigned int, unsigned int> rowsOfFrame;
  std::vector<unsigned int> extra, duplicated, withoutPose;
  for (const vpPoseRow &row : estimates) {
    if (++rowsOfFrame[row.frame] == 2)
      duplicated.push_back(row.frame);
    const auto it = truthByFrame.find(row.frame);
    if (it == truthByFrame.end()) {
      extra.push_back(row.frame);
      continue;
    }
    if (rowsOfFrame[row.frame] > 1)
      continue;
    if (row.status != "ok") {
      withoutPose.push_back(row.frame);
      continue;
    }
    const vpHomogeneousMatrix delta = it->second.inverse() * row.cMo;
    translationErrors.push_back((row.cMo.getTranslationVector() - it->second.getTranslationVector()).frobeniusNorm());
    rotationErrors.push_back(vpThetaUVector(delta.getRotationMatrix()).getTheta());
  }
  std::vector<unsigned int> absent;
  for (const auto &t : truthByFrame)
    if (rowsOfFrame.find(t.first) == rowsOfFrame.end())
      absent.push_back(t.first);
  std::cout << translationErrors.size() << "/" << truthByFrame.size() << " ground-truth frames with a pose"
            << std::endl;
  summarize("translation error", translationErrors, 1000.0, "mm");
  summarize("rotation error", rotationErrors, 180.0 / M_PI, "deg");

  // The files match when every truth frame has exactly one row and no row is of another frame.
  bool pass = absent.empty() && extra.empty() && duplicated.empty() && !translationErrors.empty();
  const std::pair<const char *, const std::vector<unsigned int> *> problems[] = {
      {"ground-truth frame(s) absent from the estimate", &absent},
      {"estimated frame(s) without a ground truth", &extra},
      {"frame(s) with more than one row in the estimate", &duplicated},
      {"frame(s) without a pose (a status word instead)", &withoutPose}};
  for (const auto &problem : problems)
    if (!problem.second->empty()) {
      std::cerr << problem.second->size() << " " << problem.first << ":";
      for (size_t k = 0; k < problem.second->size() && k < 10; ++k)
        std::cerr << " " << (*problem.second)[k];
      std::cerr << (problem.second->size() > 10 ? " ..." : "") << std::endl;
    }
  if (withoutPose.size() > maxMissing) {
    std::cerr << "more frames without a pose than --max-missing " << maxMissing << std::endl;
    pass = false;
  }
  if (maxTranslation >= 0.0 && !(median(translationErrors) <= maxTranslation)) {
    std::cerr << "median translation error above " << maxTranslation << " m" << std::endl;
    pass = false;
  }
  if (maxRotationDeg >= 0.0 && !(median(rotationErrors) * 180.0 / M_PI <= maxRotationDeg)) {
    std::cerr << "median rotation error above " << maxRotationDeg << " deg" << std::endl;
    pass = false;
  }
  return pass ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace

int main(int argc, char **argv) { return vpCommandLine::runGuarded(run, argc, argv); }
