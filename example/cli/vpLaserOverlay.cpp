/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpLaserOverlay.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>

namespace
{
//! Real roots of a t^2 + b t + c = 0 (a may be 0); returns how many were written.
int solveQuadratic(double a, double b, double c, double roots[2])
{
  const double scale = std::fabs(a) + std::fabs(b) + std::fabs(c);
  if (scale == 0.0)
    return 0;
  if (std::fabs(a) < 1e-14 * scale) {
    if (std::fabs(b) < 1e-14 * scale)
      return 0;
    roots[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0)
    return 0;
  // Numerically stable form (no cancellation between -b and the square root).
  const double q = -0.5 * (b + (b >= 0.0 ? std::sqrt(disc) : -std::sqrt(disc)));
  roots[0] = q / a;
  roots[1] = (q != 0.0) ? c / q : roots[0];
  return 2;
}

/*!
  Colours pixel (u, v) when it lies in the image. Pixels are written directly: vpImageDraw::drawPoint()
  with a thickness of 1 draws an empty rectangle, i.e. nothing. One pixel is thin enough for the
  detected points (3 pixels wide) to show on both sides of the curve.
*/
void plot(vpImage<vpRGBa> &I, double u, double v, const vpColor &color)
{
  if (u >= 0.0 && v >= 0.0 && u < I.getWidth() && v < I.getHeight())
    I[static_cast<unsigned int>(v)][static_cast<unsigned int>(u)] = vpRGBa(color.R, color.G, color.B);
}

//! Replaces \e I by its dimmed grey level, so that every colour left in it is a drawing.
void dimToGrey(vpImage<vpRGBa> &I)
{
  for (unsigned int k = 0; k < I.getSize(); ++k) {
    vpRGBa &p = I.bitmap[k];
    const unsigned char grey = static_cast<unsigned char>(0.6 * (0.299 * p.R + 0.587 * p.G + 0.114 * p.B));
    p = vpRGBa(grey, grey, grey);
  }
}
} // namespace

void vpLaserOverlay::drawConic(vpImage<vpRGBa> &I, const vpMatrix &C, const vpColor &color)
{
  if (C.getRows() != 3 || C.getCols() != 3)
    return;
  // x^T C x with x = (u, v, 1): a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f.
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1];
  const double d = 0.5 * (C[0][2] + C[2][0]), e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  double roots[2];
  for (unsigned int v = 0; v < I.getHeight(); ++v) { // crossings of each row: quadratic in u
    const int n = solveQuadratic(a, 2.0 * (b * v + d), c * v * v + 2.0 * e * v + f, roots);
    for (int k = 0; k < n; ++k)
      plot(I, roots[k], v, color);
  }
  for (unsigned int u = 0; u < I.getWidth(); ++u) { // crossings of each column: quadratic in v
    const int n = solveQuadratic(c, 2.0 * (b * u + e), a * u * u + 2.0 * d * u + f, roots);
    for (int k = 0; k < n; ++k)
      plot(I, u, roots[k], color);
  }
}

void vpLaserOverlay::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                          const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption)
{
  // The red laser stripe of the image would read as outliers: the image is shown in grey.
  dimToGrey(I);
  for (const vpImagePoint &p : points)
    vpImageDraw::drawPoint(I, p, vpColor::red, 3);
  for (unsigned int index : inliers)
    if (index < points.size())
      vpImageDraw::drawPoint(I, points[index], vpColor::green, 3);
  // A light blue stands out on a dark floor and on the green points; drawn last and thinner, it stays
  // visible over the points it fits.
  const vpColor conicColor(70, 140, 255);
  drawConic(I, conic, conicColor);
  if (!caption.empty())
    drawCaption(I, caption,
                {{"detected points (outliers)", vpColor::red}, {"inliers", vpColor::green}, {"fitted conic", conicColor}});
}

void vpLaserOverlay::drawCaption(vpImage<vpRGBa> &I, const std::string &caption,
                                 const std::vector<std::pair<std::string, vpColor> > &legend)
{
  // The text height follows the image width, so that the caption stays readable on large images.
  const unsigned int height = std::max(16u, I.getWidth() / 64);
  const vpFont font(height);
  vpImagePoint at(8, 8);
  font.drawText(I, caption, at, vpColor::white, vpColor::black);
  at.set_i(at.get_i() + 1.4 * height);
  for (const auto &entry : legend) { // each entry in the colour it names, one text height apart
    font.drawText(I, entry.first, at, entry.second, vpColor::black);
    at.set_j(at.get_j() + font.getMeasure(entry.first).get_j() + height);
  }
}
