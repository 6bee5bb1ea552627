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
#include <visp3/core/vpMeterPixelConversion.h>

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
  drawConic(I, C, vpCameraParameters(1.0, 1.0, 0.0, 0.0), color); // identity K: pixels are the coordinates
}

void vpLaserOverlay::drawConic(vpImage<vpRGBa> &I, const vpMatrix &C, const vpCameraParameters &cam,
                               const vpColor &color)
{
  if (C.getRows() != 3 || C.getCols() != 3)
    return;
  // x^T C x with x = (u, v, 1) in the undistorted pixel image: a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f.
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1];
  const double d = 0.5 * (C[0][2] + C[2][0]), e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  // Undistorted pixel -> image pixel through the camera's model.
  auto toImage = [&cam](double u, double v) {
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(cam, (u - cam.get_u0()) / cam.get_px(), (v - cam.get_v0()) / cam.get_py(), ip);
    return ip;
  };
  const double W = I.getWidth(), H = I.getHeight();
  auto drawSegment = [&](const vpImagePoint &p, const vpImagePoint &q) {
    // Only the segments near the image (a hyperbola's far branches map to huge coordinates).
    const bool near = std::fabs(p.get_u()) < 4 * W && std::fabs(p.get_v()) < 4 * H && std::fabs(q.get_u()) < 4 * W &&
                      std::fabs(q.get_v()) < 4 * H && vpImagePoint::distance(p, q) < 0.25 * (W + H);
    if (near)
      vpImageDraw::drawLine(I, p, q, color, 1);
  };
  const double det2 = a * c - b * b;
  if (det2 > 0.0) {
    // Ellipse (possibly imaginary): centre, then the points centre + R (r1 cos t, r2 sin t).
    const double u0 = (b * e - c * d) / det2, v0 = (b * d - a * e) / det2;
    const double k = -(a * u0 * u0 + 2 * b * u0 * v0 + c * v0 * v0 + 2 * d * u0 + 2 * e * v0 + f);
    const double trace = a + c, disc = std::sqrt(std::max(0.0, 0.25 * (a - c) * (a - c) + b * b));
    const double l1 = 0.5 * trace + disc, l2 = 0.5 * trace - disc; // eigenvalues, l1 >= l2 > 0
    if (!(k / l1 > 0.0) || !(k / l2 > 0.0))
      return;
    const double r1 = std::sqrt(k / l1), r2 = std::sqrt(k / l2);
    const double theta = 0.5 * std::atan2(2.0 * b, a - c); // direction of the eigenvector of l1
    const double ct = std::cos(theta), st = std::sin(theta);
    vpImagePoint previous;
    for (int s = 0; s <= 360; ++s) {
      const double t = s * M_PI / 180.0, x = r1 * std::cos(t), y = r2 * std::sin(t);
      const vpImagePoint p = toImage(u0 + ct * x - st * y, v0 + st * x + ct * y);
      if (s > 0)
        drawSegment(previous, p);
      previous = p;
    }
    return;
  }
  // Other conics: the crossings of every row (left and right roots) and of every column, joined per root.
  double roots[2];
  for (int pass = 0; pass < 2; ++pass) {
    const bool rows = pass == 0;
    const double extent = rows ? H : W;
    bool have[2] = {false, false};
    vpImagePoint last[2];
    for (double t = -extent; t <= 2.0 * extent; t += 1.0) {
      const int n = rows ? solveQuadratic(a, 2.0 * (b * t + d), c * t * t + 2.0 * e * t + f, roots)
                         : solveQuadratic(c, 2.0 * (b * t + e), a * t * t + 2.0 * d * t + f, roots);
      if (n == 2 && roots[0] > roots[1])
        std::swap(roots[0], roots[1]);
      for (int r = 0; r < 2; ++r) {
        if (r >= n) {
          have[r] = false;
          continue;
        }
        const vpImagePoint p = rows ? toImage(roots[r], t) : toImage(t, roots[r]);
        if (have[r])
          drawSegment(last[r], p);
        last[r] = p;
        have[r] = true;
      }
    }
  }
}

void vpLaserOverlay::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                          const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption)
{
  draw(I, points, inliers, conic, vpCameraParameters(1.0, 1.0, 0.0, 0.0), caption);
}

void vpLaserOverlay::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                          const std::vector<unsigned int> &inliers, const vpMatrix &conic, const vpCameraParameters &cam,
                          const std::string &caption)
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
  drawConic(I, conic, cam, conicColor);
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
