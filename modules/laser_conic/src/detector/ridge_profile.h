/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_profile.h
  \brief The profile test of the ridge detector (internal header): the stripe's shape around a candidate
  peak along its scan line, and its sub-pixel centre.
*/
#ifndef VP_LASER_RIDGE_PROFILE_H
#define VP_LASER_RIDGE_PROFILE_H

#include <algorithm>
#include <cstddef>
#include <vector>

#include "laser_detector.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
/*!
  Access to the score and the pixels along one scan line: pointers to its first pixel and the stride
  between its pixels, set once per candidate (the accesses of the profile tests are then one multiply-add).
*/
struct ScanLine
{
  const unsigned char *score;                //!< the whole score image
  int W, H;                                  //!< its size
  bool alongRow;                             //!< a row (else a column)
  int line;                                  //!< its index
  const unsigned char *lineScore, *lineRgba; //!< pixel 0 of the line in the score and in the RGBA buffer
  ptrdiff_t stride;                          //!< pixels between two consecutive pixels of the line
  int n;                                     //!< length of the line
  ScanLine(const unsigned char *score_, const unsigned char *rgba, int W_, int H_, bool alongRow_, int line_)
    : score(score_), W(W_), H(H_), alongRow(alongRow_), line(line_),
      lineScore(score_ + (alongRow_ ? static_cast<size_t>(line_) * W_ : static_cast<size_t>(line_))),
      lineRgba(rgba + 4 * (alongRow_ ? static_cast<size_t>(line_) * W_ : static_cast<size_t>(line_))),
      stride(alongRow_ ? 1 : W_), n(alongRow_ ? W_ : H_)
  {
  }
  int length() const { return n; }                          //!< pixels along the line
  int at(int pos) const { return lineScore[pos * stride]; } //!< score of a pixel
  //! Unclipped red dominance of the pixel (negative for grey or other colours).
  int dominance(int pos) const
  {
    const unsigned char *p = lineRgba + 4 * pos * stride;
    return p[0] - std::max(p[1], p[2]);
  }
  int red(int pos) const { return lineRgba[4 * pos * stride]; } //!< red channel of a pixel
};

//! Outcome of the profile test of a candidate.
enum Verdict {
  ACCEPTED,
  REJECTED, //!< shape, width or white light: mark the run
  IGNORED   //!< not measured by this direction (the other direction crosses more steeply)
};

/*!
  Whether the white pixels of the run [a, b] of the profile \e s (red channel in the saturation ramp or
  above, low dominance) lack red flanks: a saturated core has red pixels on both sides, white light (a
  lamp's reflection, white tiles) has not. \e Profile: ScanLine, or any type with its length(), red() and
  dominance().
*/
template <class Profile> bool whiteWithoutRedFlanks(const Profile &s, int a, int b, int saturation, int threshold)
{
  const int n = s.length();
  int firstWhite = -1, lastWhite = -1;
  for (int k = a; k <= b; ++k)
    if (s.red(k) >= saturation - RidgeTuning::saturationRamp && s.dominance(k) < threshold) {
      if (firstWhite < 0)
        firstWhite = k;
      lastWhite = k;
    }
  if (firstWhite < 0)
    return false;
  bool redLeft = false, redRight = false;
  for (int k = std::max(0, a - RidgeTuning::whiteFlankReach); k < firstWhite && !redLeft; ++k)
    redLeft = s.dominance(k) >= threshold;
  for (int k = lastWhite + 1; k <= std::min(n - 1, b + RidgeTuning::whiteFlankReach) && !redRight; ++k)
    redRight = s.dominance(k) >= threshold;
  return !redLeft || !redRight;
}

/*!
  Sub-pixel centre of the stripe of peak \e p, background \e bg and contrast \e contrast along the profile
  \e s, whose half-maximum run is [a, b]: the centroid of the score above bg + contrast /
  RidgeTuning::centroidLevelDivisor over the connected part around the peak, within d - 1 pixels of it (a
  saturated core is a plateau of 255: the centre is the centre of the whole profile). \e Profile: ScanLine,
  or any type with its length() and at().
*/
template <class Profile> double stripeCentroid(const Profile &s, int p, int a, int b, int bg, int contrast, int d)
{
  const int n = s.length();
  const double level = bg + static_cast<double>(contrast) / RidgeTuning::centroidLevelDivisor;
  const int aboveLevel = bg + contrast / RidgeTuning::centroidLevelDivisor; // floor(level)
  int lo = a, hi = b;
  while (lo - 1 >= 0 && s.at(lo - 1) > aboveLevel && p - lo < d - 1)
    --lo;
  while (hi + 1 < n && s.at(hi + 1) > aboveLevel && hi - p < d - 1)
    ++hi;
  double sumW = 0.0, sumWk = 0.0;
  for (int k = lo; k <= hi; ++k) {
    const double w = s.at(k) - level;
    if (w > 0.0) {
      sumW += w;
      sumWk += w * k;
    }
  }
  return sumW > 0.0 ? sumWk / sumW : p;
}

/*!
  How far along and across its scan line analyse() reads the score around a candidate, for a maximum stripe
  width \e d: d + 1 pixels around the peak, which lies up to d / 2 pixels past the candidate (the middle of a
  saturated plateau, whose first pixel is the candidate). The streamed rows and a search region's scored
  blocks reach this far beyond the candidates.
*/
inline int profileReach(int d) { return d + 1 + d / 2; }

/*!
  Checks the profile around the peak \e candidate of the scan line \e s against \e threshold (the contrast of
  a stripe above the background at the stripe width), and measures its sub-pixel centre and half-maximum run
  into \e out (the run also when REJECTED); a saturated core is measured from the middle of its plateau.
  \e acrossScored: the score across the line (profileReach() lines on each side) is there, and a crossing the
  other direction measures better is IGNORED; when false (a sample of rows alone) every stripe crossing the
  line is measured.
*/
Verdict analyse(const ScanLine &s, int candidate, const RidgeSettings &settings, int threshold, bool acrossScored,
                Crossing &out);

/*!
  analyse() of the candidate peak \e p of \e s, filed: an accepted crossing into work.crossings, a rejected
  run into \e runs (for the mask). Returns the last pixel of the run measured, or -1 when IGNORED (a later
  peak inside that run is the same stripe).
*/
int measureCandidate(const ScanLine &s, int p, const RidgeSettings &settings, int threshold, bool acrossScored,
                     RidgeWorkspace &work, std::vector<StripeRun> &runs);
} // namespace vsp::laser_detector

#endif
