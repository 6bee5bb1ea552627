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
#include <utility>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
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
    Dims \e I to grey (so that its red laser stripe cannot be mistaken for a drawing), then draws on it
    the trace with vpLaserConicPose::draw() (detected points red, inliers green, the conic \e conic,
    3x3 in pixel coordinates, x^T C x = 0, yellow when it is not empty), plus, when \e caption is not
    empty, that caption and a legend of the colours in the top-left corner.
  */
  static void draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption);
  /*!
    As above for a camera with lens distortion: \e conic is in the undistorted pixel image of \e cam
    (x = K x_n, as vpLaserConicPose::getImageConic() gives it), drawn through the camera model
    (vpMeterPixelConversion) so that it lies on the distorted trace.
  */
  static void draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inliers, const vpMatrix &conic, const vpCameraParameters &cam,
                   const std::string &caption);
  /*!
    Writes \e caption in the top-left corner of \e I and, below it, the \e legend entries side by
    side, each text in its colour (also used by the demo for its gravity-aided pose overlays).
  */
  static void drawCaption(vpImage<vpRGBa> &I, const std::string &caption,
                          const std::vector<std::pair<std::string, vpColor> > &legend);
};

#endif
