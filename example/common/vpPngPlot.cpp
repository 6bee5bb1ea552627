/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpPngPlot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/io/vpImageIo.h>

namespace
{
// "Nice" tick spacing (1, 2 or 5 times a power of ten) giving about `target` ticks over `span`.
double tickStep(double span, int target)
{
  const double raw = span / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;
  return (m < 1.5 ? 1.0 : (m < 3.5 ? 2.0 : (m < 7.5 ? 5.0 : 10.0))) * p;
}

std::string formatTick(double v, double step)
{
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(buf, sizeof(buf), "%.*f", std::min(decimals, 6), std::abs(v) < 1e-12 * step ? 0.0 : v);
  return buf;
}
} // namespace

vpPngPlot::vpPngPlot(const std::string &title, const std::string &xLabel, const std::string &yLabel,
                     unsigned int width, unsigned int height)
  : m_title(title), m_xLabel(xLabel), m_yLabel(yLabel), m_width(std::max(width, 200u)),
    m_height(std::max(height, 150u)), m_fixedX(false), m_fixedY(false), m_xmin(0), m_xmax(1), m_ymin(0), m_ymax(1)
{
}

void vpPngPlot::addCurve(const std::string &name, const std::vector<double> &x, const std::vector<double> &y,
                         const vpColor &color)
{
  m_series.push_back(Series{name, x, y, color, false});
}

void vpPngPlot::addPoints(const std::string &name, const std::vector<double> &x, const std::vector<double> &y,
                          const vpColor &color)
{
  m_series.push_back(Series{name, x, y, color, true});
}

void vpPngPlot::setXRange(double xmin, double xmax)
{
  m_fixedX = xmax > xmin;
  m_xmin = xmin;
  m_xmax = xmax;
}

void vpPngPlot::setYRange(double ymin, double ymax)
{
  m_fixedY = ymax > ymin;
  m_ymin = ymin;
  m_ymax = ymax;
}

void vpPngPlot::dataRange(double &x0, double &x1, double &y0, double &y1) const
{
  x0 = y0 = std::numeric_limits<double>::infinity();
  x1 = y1 = -std::numeric_limits<double>::infinity();
  for (const Series &s : m_series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]);
        x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]);
        y1 = std::max(y1, s.y[i]);
      }
  if (!(x1 >= x0)) {
    x0 = 0;
    x1 = 1;
  }
  if (!(y1 >= y0)) {
    y0 = 0;
    y1 = 1;
  }
  // Degenerate spans get a unit window; data ranges get a 5 % margin in y.
  if (x1 - x0 < 1e-12) {
    x0 -= 0.5;
    x1 += 0.5;
  }
  if (y1 - y0 < 1e-12) {
    y0 -= 0.5;
    y1 += 0.5;
  }
  const double my = 0.05 * (y1 - y0);
  y0 -= my;
  y1 += my;
  if (m_fixedX) {
    x0 = m_xmin;
    x1 = m_xmax;
  }
  if (m_fixedY) {
    y0 = m_ymin;
    y1 = m_ymax;
  }
}

void vpPngPlot::render(vpImage<vpRGBa> &I) const
{
  I.resize(m_height, m_width, vpRGBa(255, 255, 255));
  const vpFont font(14), titleFont(18);
  const double left = 80, right = m_width - 20.0, top = 40, bottom = m_height - 55.0;
  double x0, x1, y0, y1;
  dataRange(x0, x1, y0, y1);
  auto toPixel = [&](double x, double y) {
    return vpImagePoint(bottom - (y - y0) / (y1 - y0) * (bottom - top), left + (x - x0) / (x1 - x0) * (right - left));
  };

  // Grid and tick labels.
  const vpColor grid(225, 225, 225), axis(60, 60, 60);
  const double sx = tickStep(x1 - x0, 8), sy = tickStep(y1 - y0, 6);
  for (double v = std::ceil(x0 / sx) * sx; v <= x1 + 1e-9 * sx; v += sx) {
    const vpImagePoint p = toPixel(v, y0);
    vpImageDraw::drawLine(I, vpImagePoint(top, p.get_j()), vpImagePoint(bottom, p.get_j()), grid);
    const std::string label = formatTick(v, sx);
    font.drawText(I, label, vpImagePoint(bottom + 6, p.get_j() - font.getMeasure(label).get_j() / 2), axis);
  }
  for (double v = std::ceil(y0 / sy) * sy; v <= y1 + 1e-9 * sy; v += sy) {
    const vpImagePoint p = toPixel(x0, v);
    vpImageDraw::drawLine(I, vpImagePoint(p.get_i(), left), vpImagePoint(p.get_i(), right), grid);
    const std::string label = formatTick(v, sy);
    font.drawText(I, label, vpImagePoint(p.get_i() - 8, left - 8 - font.getMeasure(label).get_j()), axis);
  }
  vpImageDraw::drawRectangle(I, vpRect(vpImagePoint(top, left), vpImagePoint(bottom, right)), axis);

  // Data, clipped to the plot area.
  auto inside = [&](const vpImagePoint &p) {
    return p.get_i() >= top - 0.5 && p.get_i() <= bottom + 0.5 && p.get_j() >= left - 0.5 && p.get_j() <= right + 0.5;
  };
  for (const Series &s : m_series) {
    const size_t n = std::min(s.x.size(), s.y.size());
    bool havePrevious = false;
    vpImagePoint previous;
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        havePrevious = false;
        continue;
      }
      const vpImagePoint p = toPixel(s.x[i], s.y[i]);
      if (s.markers) {
        if (inside(p))
          vpImageDraw::drawCircle(I, p, 3, s.color, 2);
      } else if (havePrevious && inside(p) && inside(previous)) {
        vpImageDraw::drawLine(I, previous, p, s.color, 2);
      }
      previous = p;
      havePrevious = true;
    }
  }

  // Title, axis labels and legend.
  titleFont.drawText(I, m_title, vpImagePoint(10, (m_width - titleFont.getMeasure(m_title).get_j()) / 2), vpColor::black);
  font.drawText(I, m_xLabel, vpImagePoint(m_height - 24, (left + right - font.getMeasure(m_xLabel).get_j()) / 2),
                vpColor::black);
  font.drawText(I, m_yLabel, vpImagePoint(top - 20, 8), vpColor::black);
  double row = top + 8;
  for (const Series &s : m_series) {
    if (s.name.empty())
      continue;
    const double w = font.getMeasure(s.name).get_j();
    const vpImagePoint at(row, right - w - 40);
    if (s.markers)
      vpImageDraw::drawCircle(I, vpImagePoint(row + 8, at.get_j() - 17), 3, s.color, 2);
    else
      vpImageDraw::drawLine(I, vpImagePoint(row + 8, at.get_j() - 4), vpImagePoint(row + 8, at.get_j() - 30), s.color, 3);
    font.drawText(I, s.name, vpImagePoint(row, at.get_j()), vpColor::black);
    row += 20;
  }
}

void vpPngPlot::write(const std::string &filename) const
{
  vpImage<vpRGBa> I;
  render(I);
  vpImageIo::write(I, filename);
}
