/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "demoCommon.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <unistd.h>

void vpErrorStats::add(double error) { m_values.push_back(std::fabs(error)); }

double vpErrorStats::mean() const
{
  if (m_values.empty())
    return std::nan("");
  double s = 0.0;
  for (double v : m_values)
    s += v;
  return s / m_values.size();
}

double vpErrorStats::stddev() const
{
  if (m_values.empty())
    return std::nan("");
  const double m = mean();
  double s = 0.0;
  for (double v : m_values)
    s += (v - m) * (v - m);
  return std::sqrt(s / m_values.size());
}

double vpErrorStats::median() const
{
  if (m_values.empty())
    return std::nan("");
  std::vector<double> v = m_values;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double vpErrorStats::max() const
{
  return m_values.empty() ? std::nan("") : *std::max_element(m_values.begin(), m_values.end());
}

namespace
{
//! "mean +/- std, median" in the display unit.
std::string meanStdMedian(const vpErrorColumn &column)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(column.scale >= 100.0 ? 1 : 3) << column.stats.mean() * column.scale << " +/- "
     << column.stats.stddev() * column.scale << ", " << column.stats.median() * column.scale;
  return os.str();
}

double statistic(const vpErrorStats &stats, const std::string &name)
{
  if (name == "median")
    return stats.median();
  if (name == "max")
    return stats.max();
  return stats.mean();
}
} // namespace

void printSummary(std::ostream &os, const std::string &title, const std::vector<vpMethodSummary> &summaries,
                  const std::string &note)
{
  os << "\n"
     << title << "\n(absolute errors against the ground truth over the frames with a result: mean +/- std, median)\n";
  if (summaries.empty())
    return;
  const int methodWidth = 22, successWidth = 9, columnWidth = 26;
  os << std::left << std::setw(methodWidth) << "method" << std::setw(successWidth) << "ok";
  for (const vpErrorColumn &c : summaries.front().errors)
    os << std::setw(columnWidth) << (c.name + " [" + c.unit + "]");
  os << "time [ms/frame]\n";
  for (const vpMethodSummary &s : summaries) {
    std::ostringstream ok;
    ok << s.successes << "/" << s.frames;
    os << std::left << std::setw(methodWidth) << s.method << std::setw(successWidth) << ok.str();
    for (const vpErrorColumn &c : s.errors)
      os << std::setw(columnWidth) << meanStdMedian(c);
    os << std::fixed << std::setprecision(3) << (s.frames ? s.totalTimeMs / s.frames : 0.0) << "\n";
  }
  os.unsetf(std::ios::floatfield);
  if (!note.empty())
    os << note << "\n";
}

bool checkBounds(std::ostream &os, const std::vector<vpMethodSummary> &summaries,
                 const std::vector<vpAccuracyBound> &bounds, double minSuccessRate)
{
  bool pass = true;
  for (const vpMethodSummary &s : summaries)
    if (s.frames == 0 || s.successes < minSuccessRate * s.frames) {
      os << "CHECK FAILED: " << s.method << " succeeded on " << s.successes << "/" << s.frames << " frames (at least "
         << minSuccessRate * 100.0 << " % required)\n";
      pass = false;
    }
  for (const vpAccuracyBound &b : bounds) {
    bool found = false;
    for (const vpMethodSummary &s : summaries)
      for (const vpErrorColumn &c : s.errors)
        if (s.method == b.method && c.name == b.quantity) {
          found = true;
          const double value = statistic(c.stats, b.statistic) * c.scale;
          if (!(value <= b.value)) {
            os << "CHECK FAILED: " << b.method << " " << b.statistic << " " << b.quantity << " error " << value << " "
               << c.unit << " > " << b.value << " " << c.unit << " (" << b.why << ")\n";
            pass = false;
          }
        }
    if (!found) {
      os << "CHECK FAILED: no result for " << b.method << " / " << b.quantity << "\n";
      pass = false;
    }
  }
  return pass;
}

vpProgress::vpProgress(const std::string &label, size_t total)
  : m_label(label), m_total(total), m_terminal(isatty(STDOUT_FILENO) != 0)
{
}

void vpProgress::update(size_t index)
{
  const size_t k = index + 1;
  if (m_terminal)
    std::cout << "\r" << m_label << ": frame " << k << "/" << m_total << std::flush;
  else if (k == 1 || k % 10 == 0 || k == m_total)
    std::cout << m_label << ": frame " << k << "/" << m_total << std::endl;
}

void vpProgress::done()
{
  if (m_terminal)
    std::cout << std::endl;
}

double angleDifference(double a, double b)
{
  double d = std::fmod(a - b, 2.0 * M_PI);
  if (d > M_PI)
    d -= 2.0 * M_PI;
  else if (d <= -M_PI)
    d += 2.0 * M_PI;
  return d;
}
