/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_detector.h
  \brief The two laser stripe detectors behind vpLaserConicDetector (internal header): the ridge of a
  red-dominance score with an adaptive threshold, and the historical HSV thresholding.
*/
#ifndef VP_LASER_DETECTOR_H
#define VP_LASER_DETECTOR_H

#include <utility>
#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>

namespace vpLaserDetector
{
//! Column intervals [first, last] of each image row (a search region); rows without interval are skipped.
typedef std::vector<std::vector<std::pair<int, int> > > RowIntervals;

//! Settings of the ridge detector (see vpLaserConicDetector).
struct RidgeSettings
{
  double minContrast;   //!< grey levels
  double noiseFactor;   //!< threshold = max(minContrast, noiseFactor x noise)
  int maxWidth;         //!< widest stripe and background distance d, pixels
  int saturation;       //!< saturated red level
  double minSegment;    //!< shortest chain, pixels
  int step;             //!< sampling step of the scan lines
};

//! What the ridge detector measured besides the points.
struct RidgeReport
{
  double threshold = 0.0; //!< contrast threshold used
  double noise = 0.0;     //!< estimated score noise
};

//! A stripe run measured along a scan line, for the diagnostic mask: along row `line` when alongRow (else
//! along column `line`), its half-maximum run [first, last], accepted (a returned point) or rejected.
typedef vpLaserConicDetectorRun StripeRun;

//! Fills \e mask (resized to H x W) from the runs: 255 on the accepted runs, 100 on the rejected ones.
void drawRuns(const std::vector<StripeRun> &runs, unsigned int H, unsigned int W, vpImage<unsigned char> &mask);

/*!
  Ridge detector. \e scoreRegion / \e searchRegion: null for the whole image, else the rows to score
  (the search region dilated by the background distance) and the rows to search. \e score is a work
  buffer; \e runs receives the measured stripe runs (see drawRuns()).
*/
std::vector<vpImagePoint> detectRidge(const vpImage<vpRGBa> &I, const RidgeSettings &settings,
                                      const RowIntervals *scoreRegion, const RowIntervals *searchRegion,
                                      std::vector<unsigned char> &score, std::vector<StripeRun> &runs,
                                      RidgeReport &report);

//! Settings of the HSV detector.
struct HsvSettings
{
  int maxHueLow, minHueHigh, minSaturation, minValue, maxWidth, step;
};

//! HSV thresholding detector (the historical one); \e mask is resized and filled (255 on the trace pixels).
std::vector<vpImagePoint> detectHsv(const vpImage<vpRGBa> &I, const HsvSettings &settings,
                                    vpImage<unsigned char> &mask);
} // namespace vpLaserDetector

#endif
