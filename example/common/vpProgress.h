/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpProgress.h
  \brief Progress of long work (calibration, Monte Carlo studies) on stderr.
*/
#ifndef VP_PROGRESS_H
#define VP_PROGRESS_H

#include <chrono>
#include <string>

/*!
  Prints "label: done/total (elapsed, about N s left)" on stderr, at most once a second and once at
  the end, so that a long run is seen to progress without flooding a log. On a terminal the line is
  rewritten in place; otherwise (a log file, a pipe) each report is its own line.
*/
class vpProgress
{
public:
  //! Progress of \e total steps named \e label; \e enabled false prints nothing (e.g. a --quiet option).
  vpProgress(const std::string &label, std::size_t total, bool enabled = true);
  //! Records that \e done steps of the total are complete, printing when a second has passed.
  void update(std::size_t done);
  //! Prints the final report (all steps complete).
  void finish();

private:
  void print(std::size_t done, bool last);
  std::string m_label;
  std::size_t m_total;
  bool m_enabled, m_terminal, m_finished;
  std::chrono::steady_clock::time_point m_start, m_lastPrint;
};

#endif
