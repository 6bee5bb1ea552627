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
  the red band (around 0/180 in OpenCV's 0-179 hue scale) and its saturation and value reach their
  minimum. Each run of consecutive trace pixels along an image row, and along an image column, gives
  one sub-pixel point: the centre of the run weighted by the brightness (V - minValue + 1) of its pixels,
  i.e. the centre of the stripe across its width.

  A run is kept only when the stripe crosses its scan line at least as steeply as the other
  scan direction (the run is not longer than the run of the other direction through its centre):
  a row measures the parts of the curve closer to vertical, a column the parts closer to horizontal,
  so the centre of a run along a nearly tangent line, which would lie off the curve, is never returned.
  Where the curve is at 45 degrees a point may thus be measured by both a row and a column. A run whose
  brightest pixel is less than half as bright as the brightest pixel of the run across it is a sliver
  along the dim edge of the stripe (mask flicker at the threshold), not a crossing, and is rejected too.
  Runs longer than setMaxStripeWidth() (blobs) and runs touching the image border (truncated) are
  rejected. An empty image gives no point and an empty mask.

  \code
  vpLaserConicDetector detector;
  detector.setHueRange(10, 170);
  std::vector<vpImagePoint> points = detector.detect(I); // I: vpImage<vpRGBa>
  \endcode
*/
class VISP_EXPORT vpLaserConicDetector
{
public:
  //! Detector with the default thresholds: hue <= 10 or >= 170, saturation >= 80, value >= 80, runs of
  //! at most 25 pixels, every row and column.
  vpLaserConicDetector();

  /*!
    Hue band: a pixel is red when hue <= \e maxHueLow or hue >= \e minHueHigh (OpenCV scale 0-179).
    \exception vpException::badValue when a bound is outside [0, 179].
  */
  void setHueRange(int maxHueLow, int minHueHigh);
  /*!
    Minimum saturation and value (0-255).
    \exception vpException::badValue when a bound is outside [0, 255].
  */
  void setMinSaturationValue(int minSaturation, int minValue);
  /*!
    Runs wider than this many pixels are rejected (blobs, not a stripe); default 25.
    \exception vpException::badValue on 0.
  */
  void setMaxStripeWidth(unsigned int pixels);
  /*!
    Scans one row/column every \e step (1 = every line); default 1.
    \exception vpException::badValue on 0.
  */
  void setSamplingStep(unsigned int step);

  //! Detects the trace points of \e I (pixel coordinates, sub-pixel); empty for an empty image.
  std::vector<vpImagePoint> detect(const vpImage<vpRGBa> &I);
  //! Binary mask of the last detection (255 = trace, 0 = other), for display.
  const vpImage<unsigned char> &getMask() const { return m_mask; }

private:
  int m_maxHueLow, m_minHueHigh, m_minSaturation, m_minValue;
  unsigned int m_maxStripeWidth, m_step;
  vpImage<unsigned char> m_mask;
};

#endif
