/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserOverlay.h
  \brief Overlay of a laser trace detection on its image: detected points, RANSAC inliers and the
  fitted image conic, drawn with vpImageDraw (no display needed).
*/
#ifndef VP_LASER_OVERLAY_H
#define VP_LASER_OVERLAY_H

#include <string>
#include <vector>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpRGBa.h>

/*!
  \brief Draws the result of a laser estimate on a copy of the image.
*/
class vpLaserOverlay
{
public:
  /*!
    Draws on \e I: every detected point as a red dot (outlier), the inliers in green over it, and the
    conic \e conic (3x3, pixel coordinates, x^T C x = 0) in blue when it is not empty, plus a text line.
  */
  static void draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption);
  //! Draws the image points where the conic crosses each image row and column (works for any conic type).
  static void drawConic(vpImage<vpRGBa> &I, const vpMatrix &conic, const vpColor &color);
};

#endif
