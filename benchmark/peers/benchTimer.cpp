/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file benchTimer.cpp
  \brief vspBench::medianNsPerBatch(), the timer of the peer benchmark, on Google Benchmark: every row
  of the tables is one Google Benchmark run (its own iteration count estimate, repetitions, median
  aggregate of the CPU time of the benchmark thread), read back by a reporter that prints nothing, so
  that the program still prints its side-by-side markdown tables; vspBench::threadCpuNs(), the clock of
  the interleaved ratios of the targets.
*/
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <limits>
#include <vector>

#include <benchmark/benchmark.h>

#include "vspBenchUtils.h"

namespace
{
//! Keeps the median CPU time per iteration of the run just made (nanoseconds) and prints nothing.
class MedianReporter : public benchmark::BenchmarkReporter
{
public:
  bool ReportContext(const Context &) override { return true; }
  void ReportRuns(const std::vector<Run> &runs) override
  {
    for (const Run &run : runs)
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median" && !run.error_occurred)
        medianNs = run.GetAdjustedCPUTime(); // time unit set to nanoseconds below
  }
  double medianNs = std::numeric_limits<double>::quiet_NaN();
};
} // namespace

namespace vspBench
{
double medianNsPerBatch(const std::function<void()> &batch, int nInstances, int repetitions, double minSeconds)
{
  benchmark::ClearRegisteredBenchmarks();
  benchmark::RegisterBenchmark("row",
                               [&batch](benchmark::State &state) {
                                 for (auto _ : state)
                                   batch();
                               })
      ->Unit(benchmark::kNanosecond)
      ->Repetitions(repetitions)
      ->ReportAggregatesOnly(true)
      // Google Benchmark sizes each repetition to last MinTime: the whole run lasts about minSeconds.
      ->MinTime(std::max(minSeconds / repetitions, 1e-3));
  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::ClearRegisteredBenchmarks();
  return reporter.medianNs / nInstances;
}

double threadCpuNs()
{
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec t{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t) == 0)
    return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
#endif
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace vspBench
