/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpProgress.h"

#include <cstdio>

#include <unistd.h>

vpProgress::vpProgress(const std::string &label, std::size_t total, bool enabled)
  : m_label(label), m_total(total), m_enabled(enabled), m_terminal(isatty(STDERR_FILENO) != 0), m_finished(false),
    m_start(std::chrono::steady_clock::now()), m_lastPrint(m_start)
{
}

void vpProgress::update(std::size_t done)
{
  if (!m_enabled || m_finished)
    return;
  const auto now = std::chrono::steady_clock::now();
  if (now - m_lastPrint < std::chrono::seconds(1))
    return;
  m_lastPrint = now;
  print(done, false);
}

void vpProgress::finish()
{
  if (!m_enabled || m_finished)
    return;
  m_finished = true;
  print(m_total, true);
}

void vpProgress::print(std::size_t done, bool last)
{
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  char line[256];
  if (last || done == 0 || done >= m_total)
    std::snprintf(line, sizeof(line), "%s: %zu/%zu (%.0f s)", m_label.c_str(), done, m_total, elapsed);
  else
    std::snprintf(line, sizeof(line), "%s: %zu/%zu (%.0f s, about %.0f s left)", m_label.c_str(), done, m_total,
                  elapsed, elapsed * double(m_total - done) / double(done));
  if (m_terminal)
    std::fprintf(stderr, "\r%s\033[K%s", line, last ? "\n" : "");
  else
    std::fprintf(stderr, "%s\n", line);
  std::fflush(stderr);
}
