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

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "guided_pass.h"
#include "ridge_tuning.h"

namespace vsp::laser_detector
{
class FoundCells;

//! One sample of the predicted conic: a profile along row (alongRow) or column `line` around `pos`.
struct GuidedSample
{
  bool alongRow;
  /*!
    +1 or -1: an offset along the line times toNormal times \e side is the offset across the curve, positive on
    the same side of it all round (where the conic's value grows). Along the line alone, the sign of an offset
    flips between a row's sample and the next column's where the curve's normal points up and right or down and
    left, and the offsets that the walks, their pieces and the gaps carry from one sample to the next were read
    on the wrong side there. (One byte beside alongRow: the samples are merged and copied by value, 48 bytes.)
  */
  signed char side;
  int line;
  double pos;        //!< predicted crossing along the line
  double halfWindow; //!< margin along the line (the margin across the curve / sine of the crossing angle)
  double toNormal;   //!< |offset across the curve| / |offset along the line| (> 0)
  double angle;      //!< around the conic's centre, as curveOrder(): the order along the curve
  double slope;      //!< d pos / d line of the predicted curve (the neighbouring lines' shift)
};

//! The offset across the curve of the point \e along pixels along sample s's line from its predicted crossing.
inline double acrossOf(const GuidedSample &s, double along) { return along * s.toNormal * s.side; }

//! The distance along sample s's line from its predicted crossing of the point \e offset across the curve.
inline double alongOf(const GuidedSample &s, double offset) { return offset * s.side / s.toNormal; }

//! The image point at \e along on sample s's line (its predicted crossing at s.pos).
inline vpImagePoint samplePoint(const GuidedSample &s, double along)
{
  return s.alongRow ? vpImagePoint(s.line, along) : vpImagePoint(along, s.line);
}

/*!
  A number that orders directions (dx, dy) as std::atan2(dy, dx) does, from -pi (excluded) to pi, without a
  transcendental function (the order of the points along the curve was a tenth of the tracking mode's time):
  dy / (|dx| + |dy|) on the right half plane, continued monotonically to (-2, 2] on the left one.
*/
inline double curveOrder(double dx, double dy)
{
  const double sum = std::fabs(dx) + std::fabs(dy);
  if (!(sum > 0.0))
    return 0.0;
  const double d = dy / sum; // -1 .. 1
  if (dx >= 0.0)
    return d;
  return dy >= 0.0 ? 2.0 - d : -2.0 - d;
}

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
  double response = 0.0; //!< the matched filter's best response
  //! |left - right| of the matched filter's two background means where the prediction crosses the line (grey
  //! levels of the summed lines; negative when its boxes leave the profile, or when the stripe was found): a
  //! colour edge along the curve
  double edgeAtPrediction = -1.0;
  //! |left - right| of the matched filter's two background means at the stripe found on the brightness
  //! (ProfileWindow::brightness; grey levels of the summed lines; negative on the red score, or when its boxes
  //! leave the profile): the step of an edge the stripe runs along
  double stepAtStripe = -1.0;
  int lines = 0;           //!< image lines summed
  bool brightness = false; //!< measured on the brightness (ProfileWindow::brightness): its noise is not the red's
  //! The noise of one image line (lines > 0): the summed lines' noise grows as the square root of their number
  double lineNoise() const { return noise / std::sqrt(static_cast<double>(lines)); }
};

//! Buffers of the profile measurements, reused from sample to sample.
struct ProfileBuffers
{
  //! The profile's values and their prefix sums: the first n and n + 1 entries for a profile of n pixels (the
  //! vectors only grow); the differences its noise is measured on.
  std::vector<int> value, prefix, diffs;
  /*!
    The noise of the matched filter's response per unit of pixel noise, sqrt(1 / (2h + 1) + 1 / f), for a
    stripe box of 2h + 1 pixels and background boxes of f: computed when h or f changes only (a square root
    and two divisions per profile were a few percent of a tracked frame).
  */
  double filterGain(int h, int f)
  {
    if (h != m_gainH || f != m_gainF) {
      m_gain = std::sqrt(1.0 / (2 * h + 1) + 1.0 / f);
      m_gainH = h;
      m_gainF = f;
    }
    return m_gain;
  }

private:
  int m_gainH = -1, m_gainF = -1;
  double m_gain = 0.0;
};

/*!
  About \e target of \e points (all of them when fewer), chosen by their position (a hash of their pixel), in
  their order or, when \e byPosition, sorted by row then column: the same points in any order then give the
  same subsample in the same order, and so the same fit to the last bit. (Sorting is a tenth of a tracked
  frame: the guided pass's own points come in the order of its walk, which the same prediction repeats.)
*/
void positionSubsample(const std::vector<vpImagePoint> &points, size_t target, bool byPosition,
                       std::vector<Eigen::Vector2d> &sample);

//! The indices of the points positionSubsample() picks, sorted as it sorts them by position (then by index).
std::vector<int> positionSubsampleIndices(const std::vector<vpImagePoint> &points, size_t target);

/*!
  Regularises the centres of \e crossings (the second pass's points) along the conic C: each point is moved
  along the normal of C so that its offset to C is that of a straight line fitted to the offsets of the points
  within RidgeTuning::guidedSmoothRadius pixels (see RidgeTuning::guidedSmoothRadius). Returns the indices of
  the crossings in their order along the curve (empty when they are too few to be regularised).
*/
std::vector<int> smoothAlongCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings);

/*!
  Drops the pieces of \e crossings (the second pass's points, in \e order along the curve as
  smoothAlongCurve() gives it) that stand alone: fewer than RidgeTuning::guidedIsolatedRun points, no other of
  the pass's points or of \e anchors (the first pass's) within RidgeTuning::guidedGapLength of their ends (see
  RidgeTuning::guidedIsolatedRun).
*/
void dropIsolatedPieces(const std::vector<int> &order, const std::vector<vpImagePoint> &anchors,
                        std::vector<Crossing> &crossings);

/*!
  Counting sort of the items 0 .. key.size() - 1 by their key (each in [0, buckets)): the items of bucket b are
  members[start[b]] .. members[start[b + 1] - 1], in their order.
*/
inline void groupByKey(const std::vector<size_t> &key, size_t buckets, std::vector<size_t> &start,
                       std::vector<size_t> &members)
{
  start.assign(buckets + 1, 0);
  for (size_t k : key)
    ++start[k + 1];
  for (size_t b = 1; b < start.size(); ++b)
    start[b] += start[b - 1];
  std::vector<size_t> next(start.begin(), start.end() - 1);
  members.resize(key.size());
  for (size_t item = 0; item < key.size(); ++item)
    members[next[key[item]]++] = item;
}

//! The element of rank size / 2 of \e values (>= 0, not empty), as std::nth_element would place it.
int middleValue(std::vector<int> &values);

//! Where a profile searches: a window along its line, and the noise its threshold uses.
struct ProfileWindow
{
  double centre = 0.0;     //!< offset (pixels along the line) of the window's centre from the prediction
  double halfWidth = 0.0;  //!< half width along the line; 0: the sample's whole margin (GuidedSample::halfWindow)
  double lineNoise = -1.0; //!< noise of one line (grey levels); negative: measured along this profile
  int lines = RidgeTuning::guidedLines; //!< image lines averaged (odd): the sample's and its neighbours
  //! With halfWidth > 0: the prediction was fitted to the points found over the whole image, and a stripe near
  //! it is preferred to one more than RidgeTuning::guidedNearMargin off it when the window has drifted that far
  bool preferPrediction = false;
  /*!
    The profile of the brightness R + G + B instead of the red score, its noise measured along the sample's
    whole margin and its stripe searched within the window. For a follow whose red score finds nothing: a
    JPEG stores the colour at half resolution and coarser than the brightness, and beside a colour edge
    a dim red stripe's dominance is smeared into a plateau several pixels wide, while its brightness keeps
    the stripe's bump.
  */
  bool brightness = false;
  /*!
    The stripe's peak must lie inside the window: a best response at an end of the window with a larger one
    just beyond it is the flank of a stripe outside, not found. For the windows of a pixel or so around a
    prediction (predictionWindow()): where the prediction runs beside the stripe (the ellipse fitted to the
    trace of a distorted lens, 1-2 px inside it on a faint far side), the flank's point was placed on the
    prediction instead of on the stripe.
  */
  bool peakWithin = false;
};

//! The cache lines prefetchProfile() last asked for along a column: those of the columns of a sample (the
//! same in every row: \e block, that of the first row), from row \e from to row \e to (block -1: none).
struct PrefetchedColumns
{
  long long block = -1;
  int from = 0, to = -1;
};

/*!
  Asks the processor to bring to cache the pixels a profile of sample s reads, \e halfWidth along its line: on
  the sample's line and its two neighbours, or with \e oneLine on its line alone, all that the profiles of a
  strong stripe followed read (a row profile's neighbours are rows of their own: asking for them doubled the
  cache lines, and the pages, brought in along the rows of a tracked ring). Along a column, the rows that
  \e last already asked for in the same block of columns are not asked for again (the samples a few columns
  apart share their cache lines: a column profile asked for about 25 of them, mostly the same as the sample
  before it); \e last is updated.
*/
void prefetchProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, int halfWidth, bool oneLine,
                     PrefetchedColumns &last);

/*!
  Measures the profile of sample s in the RGBA image I within \e window (kept inside the sample's margin).
  ProfileResult::noise is that of the summed lines, whether measured or given.
*/
ProfileResult measureProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                             const ProfileWindow &window, ProfileBuffers &buffers);
//! What a sample of the guided pass's walk holds: no point (MISSED), a point it measured (FOUND), or a point
//! already known near it (KNOWN: the first pass's, an earlier walk's).
enum SampleState { MISSED, FOUND, KNOWN };

//! The pieces of curve along the samples (in their order): runs of found samples, broken by more than
//! RidgeTuning::guidedMaxMisses missed samples in a row or by a jump of the offset to the prediction. A piece is
//! kept when it touches a known point (a sample near a point already found) or has RidgeTuning::guidedMinRun
//! points; \e keep marks the found samples of the kept pieces. \e closed: the samples go round the whole ring (the
//! last one next to the first, closedRing()), whose pieces are read round it from a place where one ends, so
//! that a piece through the first sample is not cut in two there.
void keepContinuingPieces(const std::vector<SampleState> &state, const std::vector<ProfileResult> &results,
                          std::vector<unsigned char> &keep, bool closed);

//! Pixels between the predicted crossings of samples a and b.
inline double samplesApart(const std::vector<GuidedSample> &samples, size_t a, size_t b)
{
  return vpImagePoint::distance(samplePoint(samples[a], samples[a].pos), samplePoint(samples[b], samples[b].pos));
}

//! Whether samples a and b of sampleConic() (every \e step-th line), next to each other in its order, are more
//! than 3 steps apart: the conic leaves the image between them.
inline bool leavesTheImageBetween(const std::vector<GuidedSample> &samples, size_t a, size_t b, int step)
{
  return samplesApart(samples, a, b) > 3.0 * std::max(1, step);
}

//! Whether \e samples (sampleConic(), every \e step-th line) go round the whole ring: the conic does not leave the
//! image between the last one and the first.
inline bool closedRing(const std::vector<GuidedSample> &samples, int step)
{
  return samples.size() >= 3 && !leavesTheImageBetween(samples, samples.size() - 1, 0, step);
}

/*!
  \e j modulo \e n for j < 2n: a position at most one turn past the end of a closed ring's \e n samples or points,
  by a comparison instead of the division of a modulo (the loops round the ring ran one or two divisions per
  sample: a few percent of a whole frame, most of dropIsolatedPieces()).
*/
inline size_t onTheRing(size_t j, size_t n) { return j >= n ? j - n : j; }

//! The window within RidgeTuning::guidedMaxJump (across the curve) of sample s's predicted crossing, moved by
//! \e offset across the curve (as ProfileResult::offset); the stripe's peak must lie inside it
//! (ProfileWindow::peakWithin).
ProfileWindow predictionWindow(const GuidedSample &s, double offset = 0.0);

//! \e window read on the brightness (ProfileWindow::brightness).
ProfileWindow onBrightness(ProfileWindow window);

//! The profile of sample s within \e window (its red score, or with ProfileWindow::brightness its brightness):
//! three lines averaged then, where they find nothing, nine (as a faint stripe's); \e accept(result) decides
//! which found point counts as found, before the nine lines are tried.
template <class Accept>
ProfileResult threeThenNineLines(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                 ProfileWindow window, ProfileBuffers &buffers, Accept accept)
{
  ProfileResult r;
  for (int lines : {RidgeTuning::guidedLines, RidgeTuning::guidedFaintLines}) {
    window.lines = lines;
    r = measureProfile(I, s, settings, window, buffers);
    r.found = r.found && accept(r);
    if (r.found)
      break;
  }
  return r;
}

//! Takes a point found within RidgeTuning::guidedMaxJump of \e offset (across the curve, as ProfileResult::offset)
//! whose response reaches \e strength times its threshold (the threshold itself at 0).
struct NearOffset
{
  double offset, strength;
  bool operator()(const ProfileResult &r) const
  {
    return std::fabs(r.offset - offset) <= RidgeTuning::guidedMaxJump && r.response >= strength * r.threshold;
  }
};

//! A sample whose red profile found nothing where the prediction crosses a colour edge, measured on its
//! brightness within \e window (predictionWindow(); see RidgeTuning::guidedColourEdge), three lines averaged
//! then, where they find nothing, nine; kept when the response of the profile that found it reaches
//! RidgeTuning::guidedBrightnessStrength times its threshold (nine lines are not tried after three that found
//! a weaker one: that took noise on the faint rings, second-pass RMS 0.30 px on one seed).
ProfileResult brightnessAtPrediction(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                     const ProfileWindow &window, ProfileBuffers &buffers);

//! The element of rank size / 2 of \e values (0 when empty), as std::nth_element would place it.
double median(std::vector<double> &values);

/*!
  The gaps of the final conic C that no point covers (the points: \e anchors, the first pass's, and \e guided,
  the pass's own, marked in \e found), measured once the walks along the refitted conics are done: the short
  ones again within a pixel of the ring (measureAlongTheFinalCurve()), then the long ones followed on the
  brightness from their dim ends (walkIntoLongGaps()). The points kept are appended to \e guided, the points of
  C in the gaps a walk started into (the ring fades there; a stripe strong at a gap's end was hidden instead)
  to \e faded. Returns how many of the centres appended were in \e guided already (a sample measured again).
*/
int measureTheFinalCurvesGaps(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &C,
                              const std::vector<vpImagePoint> &anchors, FoundCells &found, ProfileBuffers &buffers,
                              std::vector<Crossing> &guided, std::vector<vpImagePoint> &faded);
} // namespace vsp::laser_detector

#endif
