/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchPeersMain.cpp
  \brief Times our gravity-aided and laser-conic estimators against OpenCV, ViSP and OpenGV on
  identical seeded inputs and prints markdown tables of median times and ratios.

  Usage: bench-peers [--seed S] [--quick] [--only gravity|laser|laser-frame|filter] [--out results.md] [--benchmark_... flags]
         bench-peers --profile gp3|pp3|pp5|planepair [--outliers 0.5] [--frames 20] [--points 1000]
         bench-peers --profile detect-dark|detect-grey|detect-mosaic|track-dark|track-grey|track-mosaic [--frames 20]
                     [--one-frame]
         bench-peers --profile p2p|p3p|lsq|facade|compute [--frames 1000]
  (the second form only runs one laser method, the third one times one of our gravity solvers on
  --frames seeded problems; both are meant for a profiler). Every row is timed by Google Benchmark
  (benchTimer.cpp), which takes its own --benchmark_* flags; the other options are read strictly
  (vpCommandLine).
*/
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "benchTable.h"
#include "vpCommandLine.h"
#include "vpOutputFile.h"
#include "vspBenchUtils.h"

void printMarkdown(std::ostream &os, const std::vector<BenchTable> &tables)
{
  for (const BenchTable &table : tables) {
    os << "\n### " << table.title << "\n\n";
    if (!table.note.empty()) {
      os << table.note << "\n\n";
    }
    bool withSuccess = false;
    for (const BenchRow &row : table.rows) {
      withSuccess = withSuccess || row.successRate >= 0.0;
    }
    os << "| Problem | Method | Median time | " << table.ratioHeader << " |" << (withSuccess ? " Success |" : "")
       << "\n";
    os << "|---|---|---:|---:|" << (withSuccess ? "---:|" : "") << "\n";
    for (const BenchRow &row : table.rows) {
      std::ostringstream ratio;
      if (row.referenceNs > 0.0) {
        ratio << std::fixed << std::setprecision(row.ns / row.referenceNs < 10.0 ? 2 : 0) << row.ns / row.referenceNs
              << "x";
      } else {
        ratio << "-";
      }
      os << "| " << row.problem << " | " << (row.ours ? "**" + row.method + "**" : row.method) << " | "
         << vspBench::formatNs(row.ns) << " | " << ratio.str() << " |";
      if (withSuccess) {
        if (row.successRate >= 0.0) {
          os << " " << std::fixed << std::setprecision(0) << 100.0 * row.successRate << " % |";
        } else {
          os << " - |";
        }
      }
      os << "\n";
    }
  }
}

namespace
{
// One row of the targets table: what was measured, its value (3 digits, then \e unit) and \e verdict.
void printRow(std::ostream &os, const char *what, double measured, const std::string &unit, const char *verdict)
{
  if (measured < 0.0) {
    os << "| " << what << " | not measured | - |\n";
    return;
  }
  std::ostringstream value; // the stream's own format, whatever os holds
  value << std::setprecision(3) << measured << unit;
  os << "| " << what << " | " << value.str() << " | " << verdict << " |\n";
}

void printVerdict(std::ostream &os, const char *target, double measured, double required, bool higherIsBetter,
                  const char *unit)
{
  const bool met = higherIsBetter ? measured >= required : measured <= required;
  printRow(os, target, measured, unit, met ? "met" : "**not met**");
}

// What follows the median of a ratio of interleaved rounds: its quartiles and its number of rounds.
std::string roundsSpread(const vspBench::RatioRounds &ratio)
{
  std::ostringstream spread;
  spread << std::setprecision(3) << "x (quartiles " << ratio.lowQuartile << "-" << ratio.highQuartile << ", "
         << ratio.rounds << " rounds)";
  return spread.str();
}

// A ratio of interleaved rounds: its median judged, its quartiles printed beside it.
void printVerdict(std::ostream &os, const char *target, const vspBench::RatioRounds &ratio, double required)
{
  printVerdict(os, target, ratio.median, required, false, roundsSpread(ratio).c_str());
}

// A ratio of interleaved rounds that no target judges, printed for what it tells (its median and quartiles).
void printMeasure(std::ostream &os, const char *what, const vspBench::RatioRounds &ratio)
{
  printRow(os, what, ratio.median, roundsSpread(ratio), "no target");
}

void printTargets(std::ostream &os, const BenchTargets &t)
{
  os << "\n### Targets\n\n| Target | Measured | Verdict |\n|---|---:|---|\n";
  printVerdict(os, "our P3P >= 100x faster than cv::solveP3P (AP3P)",
               (t.oursP3P > 0 && t.cvAp3p > 0) ? t.cvAp3p / t.oursP3P : -1.0, 100.0, true, "x");
  printVerdict(os, "our P3P >= 200x faster than vpPose LAGRANGE (4 points)",
               (t.oursP3P > 0 && t.vpPoseLagrange4 > 0) ? t.vpPoseLagrange4 / t.oursP3P : -1.0, 200.0, true, "x");
  printVerdict(os, "GP-3 at 50 % outliers <= 0.3 ms per 1000-point frame", t.gp3At50 > 0 ? t.gp3At50 * 1e-6 : -1.0, 0.3,
               false, " ms");
  printVerdict(os, "GP-3 on a 1000-point trace + 1000 outliers <= 1x one cv::fitEllipse on the 2000 points",
               t.gp3Vs2000FitEllipse, 1.0, false, "x");
  printVerdict(os, "whole frame (detection + GP-3, worst floor) <= 0.5x one cvtColor BGR->HSV", t.wholeFrame, 0.5);
  printVerdict(os, "tracking (previous conic, 20 px, + GP-3, worst floor) <= 0.1x one cvtColor BGR->HSV",
               t.trackingFrame, 0.1);
  printMeasure(os, "frame without the laser (every search runs, 120 red patches, + GP-3, worst floor), to one cvtColor",
               t.laserOffFrame);
  printVerdict(os, "filter: one IMU propagation <= 1 us", t.filterPropagate > 0 ? t.filterPropagate * 1e-3 : -1.0, 1.0,
               false, " us");
  printVerdict(os, "filter: one frame update (30 ms late) <= 10 us", t.filterUpdate > 0 ? t.filterUpdate * 1e-3 : -1.0,
               10.0, false, " us");
  printVerdict(os, "filter: no heap allocation per sample", t.filterAllocationsPerSample, 0.0, false, "");
  printVerdict(os, "laser self-calibration, 20 frames x 1000 points <= 1 s",
               t.selfCalibration20 > 0 ? t.selfCalibration20 * 1e-9 : -1.0, 1.0, false, " s");
  printVerdict(os, "drift test <= 5 us per frame", t.driftPerFrame > 0 ? t.driftPerFrame * 1e-3 : -1.0, 5.0, false,
               " us");
}
} // namespace

int main(int argc, char **argv)
{
  unsigned int seed = 42, frames = 0, points = 1000;
  double outliers = 0.5;
  bool quick = false, oneFrame = false;
  std::string only, out, profile;
  const std::vector<std::string> gravityProfiles = {"p2p", "p3p", "lsq", "facade", "compute"};
  const std::vector<std::string> laserProfiles = {"gp3",         "pp3",         "pp5",           "planepair",
                                                  "detect-dark", "detect-grey", "detect-mosaic", "track-dark",
                                                  "track-grey",  "track-mosaic"};
  std::vector<std::string> profiles = gravityProfiles;
  profiles.insert(profiles.end(), laserProfiles.begin(), laserProfiles.end());
  vpCommandLine cli("[--seed S] [--quick] [--only gravity|laser|laser-frame|filter|selfcal] [--out FILE] | --profile "
                    "METHOD "
                    "[--frames N] "
                    "[--outliers R] [--points N]",
                    "Times our gravity-aided and laser-conic estimators against OpenCV, ViSP and OpenGV (Google "
                    "Benchmark) and prints markdown tables of median times and ratios. Google Benchmark's own "
                    "--benchmark_* flags are accepted too.");
  cli.addUnsigned("--seed", seed, "S", "seed of the problem instances (default 42)");
  cli.addFlag("--quick", quick, "fewer instances and repetitions");
  cli.addChoice("--only", only, {"gravity", "laser", "laser-frame", "filter", "selfcal"}, "part",
                "run only one part (laser-frame: the whole-frame detection tables alone; filter: the IMU-rate "
                "filter; selfcal: the laser self-calibration and drift test)");
  cli.addString("--out", out, "FILE", "also write the tables to FILE");
  cli.addChoice("--profile", profile, profiles, "method",
                "run one method in a loop for a profiler: p2p, p3p, lsq, facade, compute (gravity) or gp3, pp3, "
                "pp5, planepair (laser), detect-dark, detect-grey, detect-mosaic (detection + GP-3 on the "
                "whole-frame benchmark's frames of one floor), track-dark, track-grey, track-mosaic (the same with "
                "the previous conic as the search region)");
  cli.addFlag("--one-frame", oneFrame,
              "--profile detect-* or track-*: the first of the six frames over and over (its pixels stay in cache) "
              "instead of the six in turn");
  cli.addUnsigned("--frames", frames, "N", "--profile: problems (default 1000) or laser frames (default 20)", 1);
  cli.addDouble("--outliers", outliers, "R", "--profile of a laser method: outlier ratio (default 0.5)",
                vpCommandLine::NON_NEGATIVE);
  cli.addUnsigned("--points", points, "N",
                  "--profile of a laser method: points per frame, outliers included (default 1000; 2000 with "
                  "--outliers 0.5 is the problem of the fitEllipse target)",
                  10);
  // Google Benchmark takes out its --benchmark_* flags; it would answer --help with its own usage.
  const bool help = std::any_of(argv + 1, argv + argc,
                                [](const char *a) { return std::string(a) == "--help" || std::string(a) == "-h"; });
  if (!help)
    benchmark::Initialize(&argc, argv);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (outliers >= 1.0)
    return cli.fail("--outliers expects a ratio below 1");
  std::string error;
  if (!out.empty() && !vpOutputFile::checkWritable(out, error)) // before minutes of benchmarks
    return cli.fail(error);

  // Every method runs on one core: the timer measures the calling thread's CPU time, and a
  // per-core comparison is what matters on a machine that runs several cameras or processes.
  cv::setNumThreads(1);
  if (std::find(gravityProfiles.begin(), gravityProfiles.end(), profile) != gravityProfiles.end())
    return runGravityProfileLoop(profile, frames ? static_cast<int>(frames) : 1000, seed);
  const bool frameProfile = profile.compare(0, 7, "detect-") == 0 || profile.compare(0, 6, "track-") == 0;
  if (oneFrame && !frameProfile)
    return cli.fail("--one-frame applies to --profile detect-* and track-* only");
  if (!profile.empty())
    return runLaserProfileLoop(profile, outliers, frames ? static_cast<int>(frames) : 20, static_cast<int>(points),
                               seed, oneFrame);

  std::vector<BenchTable> tables;
  BenchTargets targets;
  if (only.empty() || only == "gravity") {
    runGravityBenchmarks(tables, targets, seed, quick);
  }
  if (only.empty() || only == "laser") {
    runLaserBenchmarks(tables, targets, seed, quick);
  }
  if (only.empty() || only == "filter") {
    runFilterBenchmarks(tables, targets, seed, quick);
  }
  if (only.empty() || only == "selfcal") {
    runSelfCalibrationBenchmarks(tables, targets, seed, quick);
  }
  if (only == "laser-frame") {
    runLaserFrameBenchmarks(tables, targets, seed, quick);
  }

  std::ostringstream report;
  printMarkdown(report, tables);
  printTargets(report, targets);
  std::cout << report.str() << std::flush;
  std::fprintf(stderr, "(sink %g)\n", static_cast<double>(vspBench::g_sink));
  if (!out.empty()) {
    vpOutputFile file(out);
    const bool opened = file.open(error);
    if (opened)
      file.stream() << report.str();
    if (!opened || !file.commit(error)) { // commit() reports the write errors
      std::cerr << "bench-peers: " << error << std::endl;
      return EXIT_FAILURE;
    }
  }
  return 0;
}
