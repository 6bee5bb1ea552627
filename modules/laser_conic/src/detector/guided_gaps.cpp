/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The gaps of the guided pass's final conic that no point covers: the short ones measured again within a
// pixel of where the ring lies, the long ones followed from their dim ends on the brightness.
#include "guided_detail.h"
#include "guided_found_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vsp::laser_detector
{
namespace
{
// (i + step) modulo n, for i < n and step <= n (onTheRing()).
inline size_t around(size_t i, size_t step, size_t n) { return onTheRing(i + step, n); }

// The offsets across the final conic (as ProfileResult::offset) of the points that cover its samples
// (\e found: the first pass's and the kept ones; \e covered set there), and in the gaps between them the
// offsets interpolated from the covered samples on either side (the median of the RidgeTuning::guidedGapEnds
// nearest on each, along the closed curve): a ring imaged through a distorting lens is not an ellipse, and
// the ellipse lies up to 3-3.5 px beside it (data/laser_hard). NaN in a gap whose ends lie more than
// RidgeTuning::guidedGapLength apart: across it the ends say nothing of where the ring lies, which may have
// left the ellipse (its part on a box beside the floor, an object over it). Empty when no sample is covered.
std::vector<double> ringOffsets(const std::vector<GuidedSample> &samples, const FoundCells &found,
                                std::vector<unsigned char> &covered)
{
  const size_t n = samples.size();
  std::vector<double> offsets(n, std::numeric_limits<double>::quiet_NaN());
  covered.assign(n, 0);
  std::vector<size_t> coveredAt;
  for (size_t i = 0; i < n; ++i)
    if (found.covers(samples[i], offsets[i])) {
      covered[i] = 1;
      coveredAt.push_back(i);
    }
  if (coveredAt.empty())
    return std::vector<double>();
  const size_t m = coveredAt.size(), ends = std::min<size_t>(RidgeTuning::guidedGapEnds, m);
  std::vector<double> side;
  // The median offset of the \e ends covered samples from coveredAt[k] on, backwards or forwards.
  const auto sideOffset = [&](size_t k, bool backwards) {
    side.clear();
    for (size_t j = 0; j < ends; ++j)
      side.push_back(offsets[coveredAt[backwards ? around(k, m - j, m) : around(k, j, m)]]);
    return median(side);
  };
  for (size_t k = 0; k < m; ++k) { // the gap after coveredAt[k]
    const size_t from = coveredAt[k], to = coveredAt[around(k, 1, m)], gap = around(to, n - from, n);
    if (gap <= 1 || samplesApart(samples, from, to) > RidgeTuning::guidedGapLength)
      continue; // 0: a single covered sample, the gap goes round
    const double before = sideOffset(k, true), after = sideOffset(around(k, 1, m), false);
    for (size_t j = 1; j < gap; ++j)
      offsets[around(from, j, n)] = before + (after - before) * static_cast<double>(j) / gap;
  }
  return offsets;
}

// Whether the walk into a long gap (walkIntoLongGaps()) keeps the point of profile r, measured after \e misses
// samples in a row without one: at RidgeTuning::guidedBrightnessStrength times its threshold (4 sigma; at 6 the
// faint frames kept half the gain), and past a run of misses longer than RidgeTuning::guidedMaxMisses at
// RidgeTuning::guidedBridgeLevel grey levels a line too.
bool walkKeeps(const ProfileResult &r, int misses)
{
  return r.found && r.response >= RidgeTuning::guidedBrightnessStrength * r.threshold &&
         (misses <= RidgeTuning::guidedMaxMisses || r.response >= RidgeTuning::guidedBridgeLevel * r.lines);
}

// Appends to \e kept the crossings of the found samples in the pieces keepContinuingPieces() keeps; returns how
// many of their centres \e found holds already (a sample measured again, see dropRepeatedCentres()).
int appendKeptPieces(const std::vector<SampleState> &state, const std::vector<ProfileResult> &results,
                     const FoundCells &found, bool closed, std::vector<Crossing> &kept)
{
  std::vector<unsigned char> keep;
  keepContinuingPieces(state, results, keep, closed);
  for (size_t i = 0; i < keep.size(); ++i)
    if (keep[i])
      kept.push_back(results[i].crossing);
  return heldCentres(keep, results, found);
}

// The samples of the final conic (refitOnItsInliers()) that no point covers (\e found: the first pass's and
// the kept ones), in gaps of at most RidgeTuning::guidedGapLength, are measured once more within
// RidgeTuning::guidedMaxJump of where the ring lies across the conic (ringOffsets(): the conic itself on an
// undistorted image, to a few tenths of a pixel): where the walk lost the stripe (a dim stretch whose profiles
// over the whole margin found a stronger neighbour, a joint's edge beside it) or followed a neighbouring
// structure (a red cable's flank, a joint's edge: the points it took there dropped as off the final curve). On
// the red score (the stripe the walk left), then on the brightness (brightnessAtPrediction(), whose bump the
// stripe keeps beside a cable), each at its own strength (see RidgeTuning::guidedRemeasureStrength). The points
// found are kept as the walk's are, in pieces that continue a covered sample or are long enough
// (keepContinuingPieces()): a few isolated responses within a pixel of the conic are not the stripe (on an
// object that hid the ring in data/laser_hard frame 36, before the gaps were limited). Appends them to \e kept;
// returns how many of their centres \e found holds already.
int measureAlongTheFinalCurve(const vpImage<vpRGBa> &I, const GuidedSettings &settings,
                              const std::vector<GuidedSample> &samples, const FoundCells &found,
                              ProfileBuffers &buffers, std::vector<Crossing> &kept)
{
  std::vector<unsigned char> covered;
  const std::vector<double> offsets = ringOffsets(samples, found, covered);
  std::vector<SampleState> state(offsets.size());
  std::vector<ProfileResult> results(offsets.size());
  for (size_t i = 0; i < offsets.size(); ++i) {
    state[i] = covered[i] ? KNOWN : MISSED;
    if (covered[i] || std::isnan(offsets[i]))
      continue;
    const GuidedSample &s = samples[i];
    const double at = offsets[i];
    ProfileResult r = threeThenNineLines(I, s, settings, predictionWindow(s, at), buffers,
                                         NearOffset{at, RidgeTuning::guidedRemeasureRedStrength});
    if (!r.found) {
      r = brightnessAtPrediction(I, s, settings, predictionWindow(s, at), buffers);
      r.found = r.found && NearOffset{at, RidgeTuning::guidedRemeasureStrength}(r);
    }
    if (r.found) {
      state[i] = FOUND;
      results[i] = r;
      results[i].offset -= at;
    }
  }
  return appendKeptPieces(state, results, found, closedRing(samples, settings.step), kept);
}

// The final conic's samples in its long gaps (their covered ends more than RidgeTuning::guidedGapLength
// apart, where ringOffsets() gives no offset) followed from each covered end on the brightness: a fading ring
// through strong JPEG keeps little of its red dominance, the colour stored at half resolution and rounded
// away, but its brightness at full resolution (testLaserConicGuidedSearch's faint ring through JPEG 60: 89.29
// -> 92.10 % of the ring at 3 sigma on average, 93.80 % with RidgeTuning::guidedWalkGap). The walk starts at
// the median offset of the end's RidgeTuning::guidedGapEnds covered samples and holds the offset of its last
// point, as the ring leaves the ellipse (by several pixels through a wide distorted lens): each sample's
// profile of RidgeTuning::guidedFaintLines lines within RidgeTuning::guidedMaxJump of that offset, its point
// kept as walkKeeps() says, until RidgeTuning::guidedMaxMisses samples in a row have none or, once it has found
// the stripe past its end, until it has gone RidgeTuning::guidedWalkGap pixels past its last point. An end
// whose stripe is strong on the red score (RidgeTuning::guidedStrongStripe times its threshold) is not
// followed: a bright stripe that stops was hidden (an object over the ring, the floor's edge), not faded, and
// the walk took the object's edge (`make-laser-sequence --hard --seed 19 --quality 80`, frame 13, through
// `vsp-laser-altimeter --truth`: attitude 0.23 -> 0.93 degree). A walk from the other end of the gap stops at
// this one's points. Appends the points of the pieces kept as the walk's (keepContinuingPieces()) to \e kept, and
// returns how many of their centres \e found holds already. The samples of each gap a walk started into (the ring
// fades there) are appended to \e faded.
int walkIntoLongGaps(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const std::vector<GuidedSample> &samples,
                     const FoundCells &found, ProfileBuffers &buffers, std::vector<Crossing> &kept,
                     std::vector<vpImagePoint> &faded)
{
  std::vector<unsigned char> covered;
  const std::vector<double> offsets = ringOffsets(samples, found, covered);
  const size_t n = offsets.size();
  if (n < 3)
    return 0;
  std::vector<SampleState> state(n);
  std::vector<ProfileResult> results(n);
  std::vector<unsigned char> walked(n, 0);
  for (size_t i = 0; i < n; ++i)
    state[i] = covered[i] ? KNOWN : MISSED;
  std::vector<double> end;
  const auto walk = [&](size_t from, size_t direction) { // direction: 1 or n - 1 (backwards)
    end.clear();
    for (size_t k = from; end.size() < static_cast<size_t>(RidgeTuning::guidedGapEnds) && covered[k];
         k = around(k, n - direction, n))
      end.push_back(offsets[k]);
    const double start = median(end);
    const ProfileResult last =
        measureProfile(I, samples[from], settings, predictionWindow(samples[from], start), buffers);
    if (last.found && last.response >= RidgeTuning::guidedStrongStripe * last.threshold)
      return;
    for (size_t k = around(from, direction, n); !covered[k] && k != from; k = around(k, direction, n))
      faded.push_back(samplePoint(samples[k], samples[k].pos));
    double at = start;
    size_t lastFound = from;
    int misses = 0;
    for (size_t k = around(from, direction, n), prev = from; !covered[k] && !walked[k];
         prev = k, k = around(k, direction, n)) {
      if (leavesTheImageBetween(samples, prev, k, settings.step))
        break;
      const GuidedSample &s = samples[k];
      ProfileWindow window = onBrightness(predictionWindow(s, at));
      window.lines = RidgeTuning::guidedFaintLines;
      ProfileResult r = measureProfile(I, s, settings, window, buffers);
      if (walkKeeps(r, misses)) {
        at = r.offset;
        walked[k] = 1; // the walk from the gap's other end stops here (its misses past it are free to that walk)
        state[k] = FOUND;
        results[k] = r;
        results[k].offset -= start; // from the covered end's, as keepContinuingPieces() reads it
        lastFound = k;
        misses = 0;
      } else if (++misses > RidgeTuning::guidedMaxMisses &&
                 (lastFound == from || samplesApart(samples, lastFound, k) > RidgeTuning::guidedWalkGap))
        break;
    }
  };
  for (size_t i = 0; i < n; ++i) {
    if (!covered[i])
      continue;
    if (!covered[around(i, 1, n)] && std::isnan(offsets[around(i, 1, n)]))
      walk(i, 1);
    if (!covered[around(i, n - 1, n)] && std::isnan(offsets[around(i, n - 1, n)]))
      walk(i, n - 1);
  }
  return appendKeptPieces(state, results, found, closedRing(samples, settings.step), kept);
}
} // namespace

int measureTheFinalCurvesGaps(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &C,
                              const std::vector<vpImagePoint> &anchors, FoundCells &found, ProfileBuffers &buffers,
                              std::vector<Crossing> &guided, std::vector<vpImagePoint> &faded)
{
  // The samples the points cover: the first pass's and the pass's own, those measured at the final conic too.
  const auto markPoints = [&]() {
    found.clear();
    for (const vpImagePoint &p : anchors)
      found.mark(p);
    for (const Crossing &c : guided)
      found.mark(c.point);
  };
  std::vector<GuidedSample> samples;
  if (!sampleConic(C, static_cast<int>(I.getWidth()), static_cast<int>(I.getHeight()), settings.margin, settings.step,
                   samples))
    return 0;
  markPoints();
  const int repeated = measureAlongTheFinalCurve(I, settings, samples, found, buffers, guided);
  markPoints();
  return repeated + walkIntoLongGaps(I, settings, samples, found, buffers, guided, faded);
}
} // namespace vsp::laser_detector
