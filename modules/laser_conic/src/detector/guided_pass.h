/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file guided_pass.h
  \brief The conic-guided pass of the ridge detector (internal header): profiles across a predicted conic,
  a matched filter for a stripe of the observed width against the noise measured along each profile, the
  points that continue the curve, refits until the coverage stops growing.
*/
#ifndef VP_LASER_GUIDED_PASS_H
#define VP_LASER_GUIDED_PASS_H

#include <vector>

#include <Eigen/Core>

#include "laser_detector.h"

namespace vsp::laser_detector
{
//! Settings of the guided pass (see vpLaserConicDetector::setGuidedSearch()).
struct GuidedSettings
{
  double margin;   //!< half width (pixels, across the curve) of the band searched around the prediction
  int step;        //!< one profile every step-th image row or column crossed by the curve
  double factor;   //!< matched-filter response >= factor x its noise measured along the profile
  int maxWidth;    //!< widest stripe (pixels, half-maximum run along the profile)
  int saturation;  //!< saturated red level
  int stripeWidth; //!< width of the matched filter (pixels): the stripe's observed half-maximum width
  /*!
    Coverage (GuidedReport::coverage) under which the caller will not use the pass's points (a location it
    would not take): the pass then ends with its walks, without the final conic's refit, gaps and
    regularisation, and appends no point.
  */
  double usefulCoverage = 0.0;
};

//! What the guided pass measured.
struct GuidedReport
{
  int added = 0;          //!< points added
  int iterations = 0;     //!< refits
  double noise = 0.0;     //!< median of the noise measured along the profiles (grey levels)
  double threshold = 0.0; //!< median response threshold of the profiles (grey levels)
  bool ran = false;       //!< false when there was no usable prediction
  //! Share of the last walk's samples (in the search limit) that ended known or with a point kept
  double coverage = 0.0;
  //! Samples of the first walk, along the prediction itself, whose predicted crossing lies in the image (and in
  //! the search limit): the prediction's length in the image
  int predictionSamples = 0;
};

/*!
  Robust ellipse through \e points (pixel coordinates): the least-squares ellipse when it fits 90 % of them,
  else RANSAC over five-point conics (seeded, \e ransacTrials samples, Sampson distance within 2 px);
  refitted on its inliers (returned in \e inliers). False when fewer than
  \e minInliers points agree, their arc around the ellipse is under 60 degrees or the conic is no plausible
  image of the ring (not an ellipse, far larger than the image, or flatter than
  RidgeTuning::traceMinAxisRatio). With \e chainOf (the chain of each point, see keptChains()), RANSAC draws
  its samples chain by chain (ChainPp5Estimator).
*/
bool fitTraceEllipse(const std::vector<vpImagePoint> &points, int W, int H, int minInliers, int ransacTrials,
                     Eigen::Matrix3d &C, std::vector<int> &inliers, const std::vector<int> *chainOf = nullptr);

//! How many of \e points lie on the ellipse C as fitTraceEllipse() counts its inliers (Sampson distance within
//! RidgeTuning::traceInlierDistance).
size_t pointsOnTraceEllipse(const Eigen::Matrix3d &C, const std::vector<vpImagePoint> &points);

/*!
  The guided pass. \e prediction: the conic to search along (pixel coordinates); \e anchors: the points
  already found that lie on it (the first pass's inliers; they count as found and are not measured again).
  \e limit: when not null, only its spans are searched. Appends the points found to \e points and their
  runs to work.guided (for the mask).
*/
void guidedPass(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &prediction,
                const std::vector<vpImagePoint> &anchors, const RegionSpans *limit, std::vector<vpImagePoint> &points,
                RidgeWorkspace &work, GuidedReport &report);

/*!
  The stretches of the final conic measured as a whole (guided_stretches.cpp): at every settings.step pixels of
  arc, a stripe fitted to the mean brightness profile across the curve over RidgeTuning::stretchHalfLength
  pixels on each side; where it is significant and the crossings there lie elsewhere (or there is none), they
  are replaced by one point at its offset. Returns the points added.
*/
int measureStretches(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &conic,
                     const std::vector<vpImagePoint> &anchors, const std::vector<vpImagePoint> &faded,
                     std::vector<Crossing> &guided);

//! Median half-maximum width (pixels) of the crossings work.keep marks; \e fallback when there is none.
int observedStripeWidth(const RidgeWorkspace &work, int fallback);

/*!
  Median half-maximum width (pixels) of the guided pass's crossings (work.guided), each measured along the
  line, row or column, that crosses the stripe more steeply; \e fallback when there is none.
*/
int guidedStripeWidth(const RidgeWorkspace &work, int fallback);

/*!
  observedStripeWidth() of crossings measured along the rows whatever the stripe's slope (see
  detectRidgeRows()), of those among \e inliers (indices of the kept crossings, in order) only: each run
  converted, with the normal of the conic C at its centre, into the run along the line, row or column, that
  crosses the stripe more steeply, the width the guided pass's profiles see.
*/
int observedStripeWidth(const RidgeWorkspace &work, const Eigen::Matrix3d &C, const std::vector<int> &inliers,
                        int fallback);

/*!
  Of the sample of rows (see detectRidgeRows()) whose kept crossings are \e points and fit the conic C with
  \e inliers (indices into \e points): the inliers where a row crosses C more steeply than a column (the
  normal's u component the larger), returned; elsewhere a row's centroid lies off the centre line (near a
  tangent by up to half the stripe's width), and the guided pass measures those parts along the columns.
  The other crossings are no longer kept in work.keep (the mask draws them as rejected).
*/
std::vector<vpImagePoint> keepSteepRowCrossings(const std::vector<vpImagePoint> &points,
                                                const std::vector<int> &inliers, const Eigen::Matrix3d &C,
                                                RidgeWorkspace &work);

/*!
  Of the first pass's \e count points (the kept crossings of work, in order), keeps those of \e inliers
  (indices, increasing) in work.keep: the others are no longer kept (the mask draws them as rejected).
*/
void keepInlierCrossings(size_t count, const std::vector<int> &inliers, RidgeWorkspace &work);
} // namespace vsp::laser_detector

#endif
