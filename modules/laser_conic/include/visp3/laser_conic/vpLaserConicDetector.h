/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicDetector.h
  \brief Red laser trace segmentation in a colour image by HSV thresholding (Sec. 7.2 of the paper).
*/
#ifndef VP_LASER_CONIC_DETECTOR_H
#define VP_LASER_CONIC_DETECTOR_H

#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>

/*!
  \ingroup group_laser_conic
  \brief Extracts the image points of a red laser trace.

  The image is converted to HSV with OpenCV; a pixel belongs to the trace when its hue is within
  the red band (around 0/180 in OpenCV's 0-179 hue scale) and its saturation and value exceed their
  minimum. Each connected run of trace pixels along an image row and along an image column gives
  one sub-pixel point: the intensity-weighted centre of the stripe across its width.
*/
class VISP_EXPORT vpLaserConicDetector
{
public:
  vpLaserConicDetector();

  //! Hue band: a pixel is red when hue <= \e maxHueLow or hue >= \e minHueHigh (OpenCV scale 0-179).
  void setHueRange(int maxHueLow, int minHueHigh);
  //! Minimum saturation and value (0-255).
  void setMinSaturationValue(int minSaturation, int minValue);
  //! Runs wider than this many pixels are rejected (blobs, not a stripe); default 25.
  void setMaxStripeWidth(unsigned int pixels);
  //! Keep one point every \e step rows/columns (1 = every line); default 1.
  void setSamplingStep(unsigned int step);

  //! Detects the trace points of \e I (pixel coordinates, sub-pixel).
  std::vector<vpImagePoint> detect(const vpImage<vpRGBa> &I);
  //! Binary mask of the last detection (255 = trace), for display.
  const vpImage<unsigned char> &getMask() const { return m_mask; }

private:
  int m_maxHueLow, m_minHueHigh, m_minSaturation, m_minValue;
  unsigned int m_maxStripeWidth, m_step;
  vpImage<unsigned char> m_mask;
};

#endif
