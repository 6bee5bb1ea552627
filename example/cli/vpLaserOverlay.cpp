/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpLaserOverlay.h"

#include <cmath>

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

void plot(vpImage<vpRGBa> &I, double u, double v, const vpColor &color)
{
  if (u >= 0.0 && v >= 0.0 && u < I.getWidth() && v < I.getHeight())
    vpImageDraw::drawPoint(I, vpImagePoint(v, u), color, 1);
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
  for (const vpImagePoint &p : points)
    vpImageDraw::drawPoint(I, p, vpColor::red, 3);
  for (unsigned int index : inliers)
    if (index < points.size())
      vpImageDraw::drawPoint(I, points[index], vpColor::green, 3);
  drawConic(I, conic, vpColor::blue); // last, thinner: visible over the points it fits
  if (!caption.empty()) {
    vpFont font(16);
    font.drawText(I, caption, vpImagePoint(8, 8), vpColor::white, vpColor::black);
  }
}
