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

/*!
  Draws marker \e shape (0 circle, 1 square, 2 plus, 3 cross, then again) centred on \e p. Series of
  points get different shapes, so that markers of methods that agree stay visible on top of each other.
*/
void drawMarker(vpImage<vpRGBa> &I, const vpImagePoint &p, unsigned int shape, const vpColor &color)
{
  const double r = 4.0;
  switch (shape % 4) {
  case 0:
    vpImageDraw::drawCircle(I, p, r, color, 2);
    break;
  case 1:
    vpImageDraw::drawRectangle(I, vpRect(p - vpImagePoint(r, r), p + vpImagePoint(r, r)), color, false, 1);
    break;
  case 2:
    vpImageDraw::drawLine(I, p - vpImagePoint(r + 2, 0), p + vpImagePoint(r + 2, 0), color, 1);
    vpImageDraw::drawLine(I, p - vpImagePoint(0, r + 2), p + vpImagePoint(0, r + 2), color, 1);
    break;
  default:
    vpImageDraw::drawLine(I, p - vpImagePoint(r + 1, r + 1), p + vpImagePoint(r + 1, r + 1), color, 1);
    vpImageDraw::drawLine(I, p + vpImagePoint(-r - 1, r + 1), p + vpImagePoint(r + 1, -r - 1), color, 1);
    break;
  }
}

/*!
  A marker beyond the y range: a filled triangle on the edge of the chart at column \e j, pointing out
  (up on the top edge \e i, down on the bottom one), with the value on the inside. \e labelEnds holds,
  per row of labels along that edge, where the last label ends: the value goes on the first row where it
  overlaps no other.
*/
void drawClipped(vpImage<vpRGBa> &I, const vpFont &font, double i, double j, bool above, double value,
                 const vpColor &color, std::vector<double> &labelEnds)
{
  const double height = 9.0, halfWidth = 6.0, inward = above ? 1.0 : -1.0;
  for (double d = 0.0; d <= height; d += 1.0) { // row by row from the tip
    const double w = halfWidth * d / height;
    vpImageDraw::drawLine(I, vpImagePoint(i + inward * d, j - w), vpImagePoint(i + inward * d, j + w), color, 1);
  }
  char text[32];
  std::snprintf(text, sizeof(text), std::abs(value) >= 100.0 ? "%.0f" : "%.3g", value);
  const vpImagePoint size = font.getMeasure(text);
  const double start = j - size.get_j() / 2, end = j + size.get_j() / 2;
  size_t row = 0;
  while (row < labelEnds.size() && labelEnds[row] > start - 4.0)
    ++row;
  if (row == labelEnds.size())
    labelEnds.push_back(end);
  labelEnds[row] = end;
  const double offset = height + 2.0 + row * (size.get_i() + 2.0);
  font.drawText(I, text, vpImagePoint(above ? i + offset : i - offset - size.get_i(), start), color);
}

std::string formatTick(double v, double step)
{
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(buf, sizeof(buf), "%.*f", std::min(decimals, 6), std::abs(v) < 1e-12 * step ? 0.0 : v);
  return buf;
}
} // namespace

vpPngPlot::vpPngPlot(const std::string &title, const std::string &xLabel, const std::string &yLabel, unsigned int width,
                     unsigned int height)
  : m_title(title), m_xLabel(xLabel), m_yLabel(yLabel), m_width(std::max(width, 200u)),
    m_height(std::max(height, 150u)), m_fixedX(false), m_fixedY(false), m_logY(false), m_xmin(0), m_xmax(1), m_ymin(0),
    m_ymax(1)
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

void vpPngPlot::setLogY(bool logY) { m_logY = logY; }

double vpPngPlot::plotY(double y) const
{
  if (!m_logY)
    return y;
  return y > 0.0 ? std::log10(y) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> vpPngPlot::yTicks(double y0, double y1) const
{
  std::vector<double> ticks;
  if (!m_logY || y1 - y0 < 1.0) {
    // Linear steps (on a log axis spanning less than a decade, steps of the exponent).
    const double step = tickStep(y1 - y0, 6);
    for (double v = std::ceil(y0 / step) * step; v <= y1 + 1e-9 * step; v += step)
      ticks.push_back(v);
    return ticks;
  }
  // Decades, plus 2 and 5 times them when the axis spans few decades.
  const bool fine = y1 - y0 < 3.0;
  for (double decade = std::floor(y0); decade <= y1; decade += 1.0)
    for (const double factor : {1.0, 2.0, 5.0})
      if ((fine || factor == 1.0) && decade + std::log10(factor) >= y0 && decade + std::log10(factor) <= y1)
        ticks.push_back(decade + std::log10(factor));
  return ticks;
}

void vpPngPlot::dataRange(double &x0, double &x1, double &y0, double &y1) const
{
  x0 = y0 = std::numeric_limits<double>::infinity();
  x1 = y1 = -std::numeric_limits<double>::infinity();
  for (const Series &s : m_series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(plotY(s.y[i]))) {
        x0 = std::min(x0, s.x[i]);
        x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, plotY(s.y[i]));
        y1 = std::max(y1, plotY(s.y[i]));
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
  if (m_fixedY && std::isfinite(plotY(m_ymin)) && std::isfinite(plotY(m_ymax))) {
    y0 = plotY(m_ymin);
    y1 = plotY(m_ymax);
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
  for (const double v : yTicks(y0, y1)) {
    const vpImagePoint p = toPixel(x0, v);
    vpImageDraw::drawLine(I, vpImagePoint(p.get_i(), left), vpImagePoint(p.get_i(), right), grid);
    // On a log axis a tick at v stands for 10^v, labelled with the digits of its own decade.
    const double value = m_logY ? std::pow(10.0, v) : v;
    const std::string label = formatTick(value, m_logY ? value : sy);
    font.drawText(I, label, vpImagePoint(p.get_i() - 8, left - 8 - font.getMeasure(label).get_j()), axis);
  }
  vpImageDraw::drawRectangle(I, vpRect(vpImagePoint(top, left), vpImagePoint(bottom, right)), axis);

  // Data, clipped to the plot area; markers beyond a fixed y range are drawn on its edge.
  auto inside = [&](const vpImagePoint &p) {
    return p.get_i() >= top - 0.5 && p.get_i() <= bottom + 0.5 && p.get_j() >= left - 0.5 && p.get_j() <= right + 0.5;
  };
  auto insideColumns = [&](const vpImagePoint &p) { return p.get_j() >= left - 0.5 && p.get_j() <= right + 0.5; };
  std::vector<unsigned int> clipped(m_series.size(), 0);
  std::vector<double> labelEnds[2]; // the value labels of the markers beyond the range, top and bottom edges
  std::vector<vpImagePoint> drawn;  // every sample on the chart, where the legend should not go
  unsigned int shape = 0;
  for (size_t k = 0; k < m_series.size(); ++k) {
    const Series &s = m_series[k];
    const size_t n = std::min(s.x.size(), s.y.size());
    bool havePrevious = false;
    vpImagePoint previous;
    for (size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(plotY(s.y[i]))) {
        havePrevious = false;
        continue;
      }
      const vpImagePoint p = toPixel(s.x[i], plotY(s.y[i]));
      if (inside(p))
        drawn.push_back(p);
      if (s.markers) {
        if (inside(p)) {
          drawMarker(I, p, shape, s.color);
        } else if (m_fixedY && insideColumns(p)) {
          const bool above = p.get_i() < top;
          drawClipped(I, font, above ? top : bottom, p.get_j(), above, s.y[i], s.color, labelEnds[above ? 0 : 1]);
          drawn.push_back(vpImagePoint(above ? top + 12 : bottom - 12, p.get_j())); // the triangle and its value
          ++clipped[k];
        }
      } else if (havePrevious && inside(p) && inside(previous)) {
        vpImageDraw::drawLine(I, previous, p, s.color, 2);
      }
      previous = p;
      havePrevious = true;
    }
    shape += s.markers ? 1 : 0;
  }

  // Title, axis labels and legend.
  titleFont.drawText(I, m_title, vpImagePoint(10, (m_width - titleFont.getMeasure(m_title).get_j()) / 2),
                     vpColor::black);
  font.drawText(I, m_xLabel, vpImagePoint(m_height - 24, (left + right - font.getMeasure(m_xLabel).get_j()) / 2),
                vpColor::black);
  font.drawText(I, m_yLabel, vpImagePoint(top - 20, 8), vpColor::black);
  // The legend goes into the corner of the chart that hides the fewest samples (top right on a tie), off
  // the bands along the top and bottom edges where markers beyond a fixed y range are drawn.
  const vpImagePoint size = legendSize(font, clipped);
  const double band = m_fixedY ? 28.0 : 6.0;
  const vpImagePoint corners[] = {vpImagePoint(top + band, right - size.get_j() - 6),
                                  vpImagePoint(top + band, left + 6),
                                  vpImagePoint(bottom - size.get_i() - band, right - size.get_j() - 6),
                                  vpImagePoint(bottom - size.get_i() - band, left + 6)};
  size_t best = 0, fewest = drawn.size() + 1;
  for (size_t c = 0; c < 4; ++c) {
    const vpRect box(corners[c], corners[c] + size);
    const size_t hidden = static_cast<size_t>(
        std::count_if(drawn.begin(), drawn.end(), [&](const vpImagePoint &p) { return box.isInside(p); }));
    if (hidden < fewest) {
      fewest = hidden;
      best = c;
    }
  }
  drawLegend(I, font, corners[best], clipped);
}

namespace
{
const double kLegendRowHeight = 20.0, kLegendSampleWidth = 30.0;
}

std::string vpPngPlot::legendName(size_t k, const std::vector<unsigned int> &clipped) const
{
  const std::string &name = m_series[k].name;
  return clipped[k] > 0 ? name + ", " + std::to_string(clipped[k]) + " off the chart" : name;
}

vpImagePoint vpPngPlot::legendSize(const vpFont &font, const std::vector<unsigned int> &clipped) const
{
  double nameWidth = 0.0;
  unsigned int rows = 0;
  for (size_t k = 0; k < m_series.size(); ++k)
    if (!m_series[k].name.empty()) {
      nameWidth = std::max(nameWidth, font.getMeasure(legendName(k, clipped)).get_j());
      ++rows;
    }
  if (rows == 0)
    return vpImagePoint(0, 0);
  return vpImagePoint(rows * kLegendRowHeight + 8, nameWidth + kLegendSampleWidth + 18);
}

void vpPngPlot::drawLegend(vpImage<vpRGBa> &I, const vpFont &font, const vpImagePoint &corner,
                           const std::vector<unsigned int> &clipped) const
{
  // One column of samples and one of names, on a white box that hides the data behind it.
  const vpImagePoint size = legendSize(font, clipped);
  if (size.get_i() <= 0.0)
    return;
  const vpRect box(corner, corner + size);
  vpImageDraw::drawRectangle(I, box, vpColor::white, true);
  vpImageDraw::drawRectangle(I, box, vpColor(180, 180, 180), false, 1);
  double row = corner.get_i() + 4;
  unsigned int shape = 0;
  for (size_t k = 0; k < m_series.size(); ++k) {
    const Series &s = m_series[k];
    const vpImagePoint sample(row + 8, corner.get_j() + 6 + kLegendSampleWidth / 2);
    if (s.markers)
      drawMarker(I, sample, shape++, s.color);
    else if (!s.name.empty())
      vpImageDraw::drawLine(I, sample - vpImagePoint(0, kLegendSampleWidth / 2),
                            sample + vpImagePoint(0, kLegendSampleWidth / 2), s.color, 3);
    if (s.name.empty())
      continue;
    font.drawText(I, legendName(k, clipped), vpImagePoint(row, corner.get_j() + kLegendSampleWidth + 12),
                  vpColor::black);
    row += kLegendRowHeight;
  }
}

void vpPngPlot::write(const std::string &filename) const
{
  vpImage<vpRGBa> I;
  render(I);
  vpImageIo::write(I, filename);
}
