/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Display of a vpLaserConicPose estimate (like vpPose::display()): the detected points, inliers in
// green and outliers in red, the fitted conic, and an altitude / attitude caption. display() draws
// through vpDisplay (an open window), draw() into the image pixels with vpImageDraw and vpFont; the
// three share one painting of the trace and differ only in their painter.
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include "detector/search_region.h"
#include "laser_lens.h"

namespace
{
using vsp::laser_detector::quadraticRoots; // the detector's, which samples conics on the image lines too

typedef std::vector<std::pair<vpImagePoint, vpImagePoint> > vpSegments;

/*!
  Line segments along the conic C of the undistorted pixel image of \e cam (x^T C x = 0, x = (u, v, 1)),
  each end mapped into the image through the camera model (the exact inverse of vpPixelMeterConversion).
  An ellipse is a closed polyline of 360 points; any other conic (the trace seen with the horizon in
  view) is sampled by its crossings of the rows, then of the columns, of a region three times the image
  (W x H pixels), only the segments near the image being kept: the far branches of a hyperbola map to
  huge coordinates.
*/
vpSegments conicSegments(const vpMatrix &C, const vpCameraParameters &cam, double W, double H)
{
  vpSegments out;
  if (C.getRows() != 3 || C.getCols() != 3)
    return out;
  // a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f.
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1];
  const double d = 0.5 * (C[0][2] + C[2][0]), e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  // Undistorted pixel -> normalized -> the image pixel the detector measured (exact inverse of the
  // pixel-to-metre model the estimators used; NaN, hence never near the image, where none exists).
  auto toImage = [&cam](double u, double v) {
    double ud = 0.0, vd = 0.0;
    if (!vsp::laser_lens::pixelOfNormalized(cam, (u - cam.get_u0()) / cam.get_px(), (v - cam.get_v0()) / cam.get_py(),
                                            ud, vd))
      ud = vd = std::numeric_limits<double>::quiet_NaN();
    return vpImagePoint(vd, ud);
  };
  auto add = [&](const vpImagePoint &p, const vpImagePoint &q) {
    const bool near = std::fabs(p.get_u()) < 4 * W && std::fabs(p.get_v()) < 4 * H && std::fabs(q.get_u()) < 4 * W &&
                      std::fabs(q.get_v()) < 4 * H && vpImagePoint::distance(p, q) < 0.25 * (W + H);
    if (near)
      out.emplace_back(p, q);
  };
  const double det2 = a * c - b * b;
  if (det2 > 0.0) {
    // Ellipse (possibly imaginary): centre, then centre + R (r1 cos t, r2 sin t).
    const double u0 = (b * e - c * d) / det2, v0 = (b * d - a * e) / det2;
    const double k = -(a * u0 * u0 + 2 * b * u0 * v0 + c * v0 * v0 + 2 * d * u0 + 2 * e * v0 + f);
    const double trace = a + c, disc = std::sqrt(std::max(0.0, 0.25 * (a - c) * (a - c) + b * b));
    const double l1 = 0.5 * trace + disc, l2 = 0.5 * trace - disc; // eigenvalues, l1 >= l2 > 0
    if (!(k / l1 > 0.0) || !(k / l2 > 0.0))
      return out;
    const double r1 = std::sqrt(k / l1), r2 = std::sqrt(k / l2);
    const double theta = 0.5 * std::atan2(2.0 * b, a - c); // direction of the eigenvector of l1
    const double ct = std::cos(theta), st = std::sin(theta);
    vpImagePoint previous;
    for (int s = 0; s <= 360; ++s) {
      const double t = s * M_PI / 180.0, x = r1 * std::cos(t), y = r2 * std::sin(t);
      const vpImagePoint p = toImage(u0 + ct * x - st * y, v0 + st * x + ct * y);
      if (s > 0)
        add(previous, p);
      previous = p;
    }
    return out;
  }
  // Other conics: the crossings of every row (left and right roots) and of every column, joined per root.
  double roots[2];
  for (int pass = 0; pass < 2; ++pass) {
    const bool rows = pass == 0;
    const double extent = rows ? H : W;
    bool have[2] = {false, false};
    vpImagePoint last[2];
    for (double t = -extent; t <= 2.0 * extent; t += 1.0) {
      const int n = rows ? quadraticRoots(a, 2.0 * (b * t + d), c * t * t + 2.0 * e * t + f, roots)
                         : quadraticRoots(c, 2.0 * (b * t + e), a * t * t + 2.0 * d * t + f, roots);
      if (n == 2 && roots[0] > roots[1])
        std::swap(roots[0], roots[1]);
      for (int r = 0; r < 2; ++r) {
        if (r >= n) {
          have[r] = false;
          continue;
        }
        const vpImagePoint p = rows ? toImage(roots[r], t) : toImage(t, roots[r]);
        if (have[r])
          add(last[r], p);
        last[r] = p;
        have[r] = true;
      }
    }
  }
  return out;
}

//! "h = 1.234 m  roll = 1.2 deg  pitch = -3.4 deg", or the status message when no plane was found.
std::string caption(const vpLaserConicPose &estimator)
{
  if (estimator.getStatus() != vpLaserConicPose::STATUS_OK)
    return vpLaserConicPose::getStatusMessage(estimator.getStatus());
  char text[128];
  std::snprintf(text, sizeof(text), "h = %.3f m  roll = %.1f deg  pitch = %.1f deg", estimator.getAltitude(),
                vpMath::deg(estimator.getRoll()), vpMath::deg(estimator.getPitch()));
  return text;
}

//! Inlier flags of \e n points from their indices (indices out of range ignored).
std::vector<bool> inlierFlags(const std::vector<unsigned int> &inlierIndex, size_t n)
{
  std::vector<bool> flags(n, false);
  for (unsigned int i : inlierIndex)
    if (i < n)
      flags[i] = true;
  return flags;
}

//! Draws through vpDisplay (the image is shown in a window), gray or colour image alike.
template <class Image> struct DisplayPainter
{
  const Image &I;
  unsigned int thickness;
  void cross(const vpImagePoint &p, bool inlier) const
  {
    vpDisplay::displayCross(I, p, 3 + 2 * thickness, inlier ? vpColor::green : vpColor::red, thickness);
  }
  void line(const vpImagePoint &p, const vpImagePoint &q) const
  {
    vpDisplay::displayLine(I, p, q, vpColor::yellow, thickness);
  }
  void text(const std::string &t, bool ok) const
  {
    vpDisplay::displayText(I, vpImagePoint(20, 10), t, ok ? vpColor::yellow : vpColor::red);
  }
};

//! Draws into the pixels of a gray image: no colours, so outliers darker, inliers, conic and text white.
struct GrayPainter
{
  vpImage<unsigned char> &I;
  unsigned int thickness;
  void cross(const vpImagePoint &p, bool inlier) const
  {
    vpImageDraw::drawCross(I, p, 3 + 2 * thickness, inlier ? 255 : 96, thickness);
  }
  void line(const vpImagePoint &p, const vpImagePoint &q) const { vpImageDraw::drawLine(I, p, q, 255, thickness); }
  void text(const std::string &t, bool) const
  {
    vpFont font(16, vpFont::GENERIC_MONOSPACE);
    font.drawText(I, t, vpImagePoint(10, 10), 255, 0);
  }
};

//! Draws into the pixels of a colour image: inliers green, outliers red, conic yellow.
struct ColourPainter
{
  vpImage<vpRGBa> &I;
  unsigned int thickness;
  void cross(const vpImagePoint &p, bool inlier) const
  {
    vpImageDraw::drawCross(I, p, 3 + 2 * thickness, inlier ? vpColor::green : vpColor::red, thickness);
  }
  void line(const vpImagePoint &p, const vpImagePoint &q) const
  {
    vpImageDraw::drawLine(I, p, q, vpColor::yellow, thickness);
  }
  void text(const std::string &t, bool ok) const
  {
    vpFont font(16, vpFont::GENERIC_MONOSPACE);
    font.drawText(I, t, vpImagePoint(10, 10), ok ? vpColor::yellow : vpColor::red, vpColor::black);
  }
};

//! The points (crosses, inliers first-class), then the conic over them.
template <class Painter, class Image>
void paintTrace(const Painter &painter, const Image &I, const std::vector<vpImagePoint> &points,
                const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic, const vpCameraParameters &cam)
{
  const std::vector<bool> inlier = inlierFlags(inlierIndex, points.size());
  for (size_t i = 0; i < points.size(); ++i)
    painter.cross(points[i], inlier[i]);
  for (const auto &segment : conicSegments(imageConic, cam, I.getWidth(), I.getHeight()))
    painter.line(segment.first, segment.second);
}

//! The overlay of an estimate: its inliers and conic when it succeeded (all points red otherwise) and the caption.
template <class Painter, class Image>
void paintEstimate(const Painter &painter, const Image &I, const vpLaserConicPose &estimator,
                   const std::vector<vpImagePoint> &points)
{
  const bool ok = estimator.getStatus() == vpLaserConicPose::STATUS_OK;
  paintTrace(painter, I, points, ok ? estimator.getRansacInlierIndex() : std::vector<unsigned int>(),
             ok ? estimator.getImageConic() : vpMatrix(), estimator.getCameraParameters());
  painter.text(caption(estimator), ok);
}
} // namespace

void vpLaserConicPose::display(const vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                               const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  paintEstimate(DisplayPainter<vpImage<unsigned char> >{I, thickness}, I, estimator, points);
}

void vpLaserConicPose::display(const vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                               const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  paintEstimate(DisplayPainter<vpImage<vpRGBa> >{I, thickness}, I, estimator, points);
}

void vpLaserConicPose::draw(vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                            const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  paintEstimate(GrayPainter{I, thickness}, I, estimator, points);
}

void vpLaserConicPose::draw(vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                            const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  paintEstimate(ColourPainter{I, thickness}, I, estimator, points);
}

void vpLaserConicPose::draw(vpImage<unsigned char> &I, const std::vector<vpImagePoint> &points,
                            const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                            const vpCameraParameters &cam, unsigned int thickness)
{
  paintTrace(GrayPainter{I, thickness}, I, points, inlierIndex, imageConic, cam);
}

void vpLaserConicPose::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                            const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                            const vpCameraParameters &cam, unsigned int thickness)
{
  paintTrace(ColourPainter{I, thickness}, I, points, inlierIndex, imageConic, cam);
}
