/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchTable.h
  \brief Rows of the peer benchmark and their markdown rendering.
*/
#ifndef VSP_BENCH_TABLE_H
#define VSP_BENCH_TABLE_H

#include <ostream>
#include <string>
#include <vector>

#include "vspBenchUtils.h"

//! One measured method: its median time and, for estimators run on noisy data, a success rate.
struct BenchRow
{
  std::string problem;       //!< what is solved ("P3P", "4 coplanar points", ...)
  std::string method;        //!< the method and its library
  double ns = 0.0;           //!< median time per call, nanoseconds
  double referenceNs = 0.0;  //!< median time of our solver of the same group (ratio denominator)
  double successRate = -1.0; //!< fraction of successful estimates in [0, 1], or < 0 when not measured
  bool ours = false;         //!< true for this project's code
};

//! A row from its fields: \e referenceNs is the ratio denominator, \e success < 0 when not measured.
inline BenchRow benchRow(const std::string &problem, const std::string &method, double ns, double referenceNs,
                         bool ours = false, double success = -1.0)
{
  return BenchRow{problem, method, ns, referenceNs, success, ours}; // the order of the members
}

//! A titled table of rows.
struct BenchTable
{
  std::string title;
  std::string note;
  std::string ratioHeader = "Ratio to ours"; //!< what the ratio column divides by
  std::vector<BenchRow> rows;
};

//! Prints tables as markdown (a ratio above 1 means slower than our reference solver).
void printMarkdown(std::ostream &os, const std::vector<BenchTable> &tables);

//! Measurements used to evaluate the targets of the benchmark (negative when not measured).
struct BenchTargets
{
  double oursP3P = -1.0, cvAp3p = -1.0, vpPoseLagrange4 = -1.0;
  double gp3At50 = -1.0;
  double gp3Vs2000FitEllipse = -1.0; //!< GP-3 on 1000 trace points + 1000 outliers / cv::fitEllipse on them
  //! detection + GP-3 / one cvtColor BGR->HSV on the same frames, interleaved rounds, worst floor
  vspBench::RatioRounds wholeFrame;
  vspBench::RatioRounds trackingFrame; //!< the same for tracking (previous conic) + GP-3
  //! the same for a frame without the laser (every search runs; no target, the worst case of a frame)
  vspBench::RatioRounds laserOffFrame;
  double filterPropagate = -1.0, filterUpdate = -1.0,
         filterAllocationsPerSample = -1.0; //!< vpLaserConicFilter (ns, ns, count)
  double selfCalibration20 = -1.0;          //!< laser self-calibration on 20 frames of 1000 points, ns
  double driftPerFrame = -1.0;              //!< drift monitor, one frame, ns
};

//! Gravity-aided pose benchmarks: appends their tables and fills the P3P targets.
void runGravityBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick);
//! Laser-conic benchmarks (1000-point frames and whole 1600x1200 frames).
void runLaserBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick);
//! vpLaserConicFilter: IMU propagation, frame update, allocations per sample, beside GP-3 frames.
void runFilterBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick);
//! Laser self-calibration from ground frames and the drift test (benchSelfCalPeers.cpp).
void runSelfCalibrationBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed,
                                  bool quick);
//! The whole-frame part of the laser benchmarks alone (detection + GP-3 against cvtColor, three floors, ROI).
void runLaserFrameBenchmarks(std::vector<BenchTable> &tables, BenchTargets &targets, unsigned int seed, bool quick);

/*!
  Times one of our gravity solvers on \e instances seeded problems and prints its median time per
  call: p2p, p3p, lsq, facade (the vpPoseGravity API calls of one pose, ending in computePose(P3P))
  or compute (computePose(P3P) alone). A short loop to run under a profiler (perf record, valgrind
  --tool=callgrind) or to compare builds.
*/
int runGravityProfileLoop(const std::string &method, int instances, unsigned int seed);

/*!
  Runs one laser method on \e frames seeded 1000-point frames and prints its success rate and mean
  RANSAC trial count: a short, deterministic loop to run under a profiler (valgrind --tool=callgrind).
*/
int runLaserProfileLoop(const std::string &method, double outlierRatio, int frames, int points, unsigned int seed,
                        bool oneFrame = false);

#endif
