/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file guided_detail.h
  \brief The pieces of the guided pass shared by its files (internal header): the samples of a conic
  along the image lines, and the measurement of one profile.
*/
#ifndef VP_LASER_GUIDED_DETAIL_H
#define VP_LASER_GUIDED_DETAIL_H

#include <vector>

#include <Eigen/Core>

#include "guided_pass.h"

namespace vsp::laser_detector
{
//! The fixed rules of the guided pass.
struct GuidedTuning
{
  //! Noise floor (grey levels) of a profile: 8-bit quantisation and JPEG leave at least this much, and a
  //! flat profile (a clipped dark floor) must not make every bump significant.
  static constexpr double noiseFloor = 0.5;
  //! Smallest matched-filter response (grey levels) whatever the noise: two quantisation steps.
  static constexpr double minResponse = 2.0;
  //! Pixels between the stripe box and its background boxes of the matched filter (the stripe's tails).
  static constexpr int gap = 1;
  //! A kept piece of curve is anchored to a point already found, or has at least this many points.
  static constexpr int minRun = 8;
  //! Consecutive samples without a point that still leave a piece of curve unbroken.
  static constexpr int maxMisses = 3;
  //! Largest change (pixels) of the offset to the prediction between consecutive points of a piece,
  //! plus perSampleJump per sample between them: the prediction is smooth, so is the true curve.
  static constexpr double maxJump = 1.0;
  //! See maxJump.
  static constexpr double perSampleJump = 0.5;
  //! Largest distance (pixels) of a second-pass point to the conic refitted on all the points: the first
  //! pass's inlier threshold (its centres are within a few tenths of a pixel of a conic trace).
  static constexpr double finalDistance = 2.0;
  //! Refits at most: the coverage stops growing after two or three on every case seen.
  static constexpr int maxIterations = 4;
  //! Side (2^cellShift pixels) of the cells that record where points were found (a sample near one is not
  //! measured again).
  static constexpr int cellShift = 2;
  //! A sample is known (not measured again) when a point found lies within knownAlong pixels of it along
  //! the predicted curve (half the spacing of the profiles, rounded up) and within knownAcross pixels across
  //! it (the prediction's error): a sample just beyond the end of a first-pass chain is measured.
  static constexpr double knownAlong = 1.0;
  //! See knownAlong (under 2^cellShift - knownAlong: the cells searched are those around the sample's).
  static constexpr double knownAcross = 3.0;
  //! The centres of the second pass are regularised along the curve: their offsets to the final conic are
  //! replaced by a straight-line fit of the offsets of the points within smoothRadius pixels (the true
  //! centre line is smooth over that length; the noise of one profile is not).
  static constexpr double smoothRadius = 20.0;
  //! Points a regularised centre needs in its neighbourhood (itself included), else it is left as measured.
  static constexpr int smoothMinPoints = 5;
  //! Offsets (pixels) farther than this from their neighbourhood's median are left out of its fit.
  static constexpr double smoothOutlier = 1.0;
  //! Image lines averaged into one profile (the line of the sample and its neighbours, shifted along the
  //! predicted curve): the noise falls by sqrt(lines), so a stripe 3 times the background noise stands out.
  static constexpr int lines = 3;
  //! Pixels of background on each side of the matched filter's stripe box, at least: the longer, the less
  //! noisy the background level.
  static constexpr int minFlank = 4;
};

//! One sample of the predicted conic: a profile along row (alongRow) or column `line` around `pos`.
struct GuidedSample
{
  bool alongRow;
  int line;
  double pos;        //!< predicted crossing along the line
  double halfWindow; //!< margin along the line (the margin across the curve / sine of the crossing angle)
  double toNormal;   //!< offset along the line x toNormal = offset across the curve
  double angle;      //!< around the conic's centre: the order along the curve
  double slope;      //!< d pos / d line of the predicted curve (the neighbouring lines' shift)
};

/*!
  The crossings of the conic C with every step-th row (where it crosses the rows more steeply than the
  columns) and column (elsewhere) of a W x H image, sorted along the curve. False when C is no ellipse.
*/
bool sampleConic(const Eigen::Matrix3d &C, int W, int H, double margin, int step, std::vector<GuidedSample> &samples);

//! Outcome of one profile.
struct ProfileResult
{
  bool found = false;
  Crossing crossing;   //!< the point and its half-maximum run
  double offset = 0.0; //!< across the curve from the prediction (pixels)
  double noise = 0.0, threshold = 0.0;
};

//! Buffers of the profile measurements, reused from sample to sample.
struct ProfileBuffers
{
  std::vector<int> value, dominance, prefix, diffs;
  std::vector<unsigned char> red;
};

/*!
  Regularises the centres of \e crossings (the second pass's points) along the conic C: each point is moved
  along the normal of C so that its offset to C is that of a straight line fitted to the offsets of the points
  within GuidedTuning::smoothRadius pixels (see GuidedTuning::smoothRadius).
*/
void smoothAlongCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings);

//! Measures the profile of sample s in the RGBA image I.
ProfileResult measureProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                             ProfileBuffers &buffers);
} // namespace vsp::laser_detector

#endif
