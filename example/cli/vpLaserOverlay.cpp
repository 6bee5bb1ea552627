/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpLaserOverlay.h"

#include <algorithm>
#include <utility>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpFont.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

namespace
{
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

void vpLaserOverlay::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                          const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption)
{
  draw(I, points, inliers, conic, vpCameraParameters(1.0, 1.0, 0.0, 0.0), caption);
}

void vpLaserOverlay::draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                          const std::vector<unsigned int> &inliers, const vpMatrix &conic,
                          const vpCameraParameters &cam, const std::string &caption)
{
  // The red laser stripe of the image would read as outliers: the image is shown in grey.
  dimToGrey(I);
  vpLaserConicPose::draw(I, points, inliers, conic, cam, 1);
  if (!caption.empty())
    drawCaption(I, caption,
                {{"detected points (outliers)", vpColor::red},
                 {"inliers", vpColor::green},
                 {"fitted conic", vpColor::yellow}});
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
