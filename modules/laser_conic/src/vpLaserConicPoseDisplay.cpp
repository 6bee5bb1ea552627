/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Display of a vpLaserConicPose estimate (like vpPose::display()): the detected points, inliers in
// green and outliers in red, the fitted conic, and an altitude / attitude caption. display() draws
// through vpDisplay (an open window), draw() into the image pixels with vpImageDraw and vpFont.
#include <visp3/laser_conic/vpLaserConicPose.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>

namespace
{
//! Points sampled along the conic drawn for an estimate.
const int kConicSamples = 180;

/*!
  Points of the ellipse of a pixel conic (undistorted image, x^T C x = 0), mapped into the image
  through the camera model (distortion included): the undistorted pixels are taken back to normalized
  coordinates with K^-1 and projected with vpMeterPixelConversion. Empty when C is not an ellipse.
*/
std::vector<vpImagePoint> conicPolyline(const vpMatrix &conic, const vpCameraParameters &cam)
{
  std::vector<vpImagePoint> out;
  if (conic.getRows() != 3 || conic.getCols() != 3)
    return out;
  Eigen::Matrix3d C;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      C(i, j) = conic[i][j];
  if (C(0, 0) < 0.0)
    C = -C;
  const Eigen::Matrix2d A = C.topLeftCorner<2, 2>();
  const Eigen::LLT<Eigen::Matrix2d> llt(A);
  if (llt.info() != Eigen::Success)
    return out;
  const Eigen::Vector2d centre = -A.inverse() * C.topRightCorner<2, 1>();
  const double k = centre.dot(A * centre) - C(2, 2);
  if (!(k > 0.0) || !std::isfinite(k))
    return out;
  const Eigen::Matrix2d Uinv = Eigen::Matrix2d(llt.matrixU()).inverse(); // A = U^T U
  for (int s = 0; s <= kConicSamples; ++s) {
    const double t = 2.0 * M_PI * s / kConicSamples;
    const Eigen::Vector2d p = centre + std::sqrt(k) * Uinv * Eigen::Vector2d(std::cos(t), std::sin(t));
    const double x = (p(0) - cam.get_u0()) / cam.get_px(), y = (p(1) - cam.get_v0()) / cam.get_py();
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(cam, x, y, ip);
    out.push_back(ip);
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

//! Inlier flags of the points (none when the estimate failed).
std::vector<bool> inlierFlags(const vpLaserConicPose &estimator, size_t n)
{
  std::vector<bool> flags(n, false);
  if (estimator.getStatus() == vpLaserConicPose::STATUS_OK)
    for (unsigned int i : estimator.getRansacInlierIndex())
      if (i < n)
        flags[i] = true;
  return flags;
}

//! Draws with vpDisplay (gray or colour image alike).
template <class Image>
void displayImpl(const Image &I, const vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points,
                 unsigned int thickness)
{
  const std::vector<bool> inlier = inlierFlags(estimator, points.size());
  for (size_t i = 0; i < points.size(); ++i)
    vpDisplay::displayCross(I, points[i], 3 + 2 * thickness, inlier[i] ? vpColor::green : vpColor::red, thickness);
  if (estimator.getStatus() == vpLaserConicPose::STATUS_OK) {
    const std::vector<vpImagePoint> line = conicPolyline(estimator.getImageConic(), estimator.getCameraParameters());
    for (size_t k = 1; k < line.size(); ++k)
      vpDisplay::displayLine(I, line[k - 1], line[k], vpColor::yellow, thickness);
  }
  vpDisplay::displayText(I, vpImagePoint(20, 10), caption(estimator),
                         estimator.getStatus() == vpLaserConicPose::STATUS_OK ? vpColor::yellow : vpColor::red);
}

//! Colour of each element drawn into a gray image (no colours: outliers darker, inliers and conic white).
struct GrayPalette
{
  unsigned char inlier = 255, outlier = 96, conic = 255, text = 255;
};

void drawImpl(vpImage<unsigned char> &I, const vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points,
              unsigned int thickness)
{
  const GrayPalette palette;
  const std::vector<bool> inlier = inlierFlags(estimator, points.size());
  for (size_t i = 0; i < points.size(); ++i)
    vpImageDraw::drawCross(I, points[i], 3 + 2 * thickness, inlier[i] ? palette.inlier : palette.outlier, thickness);
  if (estimator.getStatus() == vpLaserConicPose::STATUS_OK) {
    const std::vector<vpImagePoint> line = conicPolyline(estimator.getImageConic(), estimator.getCameraParameters());
    for (size_t k = 1; k < line.size(); ++k)
      vpImageDraw::drawLine(I, line[k - 1], line[k], palette.conic, thickness);
  }
  vpFont font(16, vpFont::GENERIC_MONOSPACE);
  font.drawText(I, caption(estimator), vpImagePoint(10, 10), palette.text, 0);
}

void drawImpl(vpImage<vpRGBa> &I, const vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points,
              unsigned int thickness)
{
  const std::vector<bool> inlier = inlierFlags(estimator, points.size());
  for (size_t i = 0; i < points.size(); ++i)
    vpImageDraw::drawCross(I, points[i], 3 + 2 * thickness, inlier[i] ? vpColor::green : vpColor::red, thickness);
  if (estimator.getStatus() == vpLaserConicPose::STATUS_OK) {
    const std::vector<vpImagePoint> line = conicPolyline(estimator.getImageConic(), estimator.getCameraParameters());
    for (size_t k = 1; k < line.size(); ++k)
      vpImageDraw::drawLine(I, line[k - 1], line[k], vpColor::yellow, thickness);
  }
  vpFont font(16, vpFont::GENERIC_MONOSPACE);
  font.drawText(I, caption(estimator), vpImagePoint(10, 10),
                estimator.getStatus() == vpLaserConicPose::STATUS_OK ? vpColor::yellow : vpColor::red, vpColor::black);
}
} // namespace

void vpLaserConicPose::display(const vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                               const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  displayImpl(I, estimator, points, thickness);
}

void vpLaserConicPose::display(const vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                               const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  displayImpl(I, estimator, points, thickness);
}

void vpLaserConicPose::draw(vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                            const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  drawImpl(I, estimator, points, thickness);
}

void vpLaserConicPose::draw(vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                            const std::vector<vpImagePoint> &points, unsigned int thickness)
{
  drawImpl(I, estimator, points, thickness);
}
