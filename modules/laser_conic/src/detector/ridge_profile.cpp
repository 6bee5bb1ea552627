/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The profile test of the ridge detector: half-maximum run, width, white light, the scan direction that
// crosses the stripe more steeply, grazing lines, sub-pixel centre.
#include "ridge_profile.h"

namespace vsp::laser_detector
{
namespace
{
// Run of scores above `level` through (i, j) along the direction (di, dj), up to limit pixels per side:
// its length and its largest score.
struct Run
{
  int length, maxScore;
};
// (di, dj) is (1, 0) or (0, 1); \e above: the integer part of the level (the scores are integers: v > level
// is v > floor(level)).
Run runThrough(const unsigned char *score, int W, int H, int i, int j, int di, int dj, int above, int limit)
{
  const unsigned char *centre = score + static_cast<size_t>(i) * W + j;
  const ptrdiff_t stride = static_cast<ptrdiff_t>(di) * W + dj;
  const int before = std::min(limit, di ? i : j), after = std::min(limit, di ? H - 1 - i : W - 1 - j);
  Run run = {1, *centre};
  for (int k = 1; k <= before && centre[-k * stride] > above; ++k) {
    ++run.length;
    run.maxScore = std::max(run.maxScore, static_cast<int>(centre[-k * stride]));
  }
  for (int k = 1; k <= after && centre[k * stride] > above; ++k) {
    ++run.length;
    run.maxScore = std::max(run.maxScore, static_cast<int>(centre[k * stride]));
  }
  return run;
}

// The background of the peak p along s: the larger over the two sides of the lower of the scores d and
// d / 2 + 1 pixels away (a neighbouring red patch at d pixels does not hide a stripe whose surroundings at
// d / 2 + 1 are dark).
int background(const ScanLine &s, int p, int d)
{
  const int n = s.length(), dn = d / 2 + 1;
  auto side = [&](int sign) {
    const int a = p + sign * d, b = p + sign * dn;
    return std::min(a >= 0 && a < n ? s.at(a) : 0, b >= 0 && b < n ? s.at(b) : 0);
  };
  return std::max(side(-1), side(1));
}

// Whether the line through the peak (i, j) of s, whose run above aboveHalf is \e width long, is not the one
// to measure this part of the stripe: the other scan direction crosses it more steeply (a shorter run), or
// the line grazes the stripe's flank (nearly tangent to it: its contrast along the line is a fraction of the
// stripe's contrast across it, a sliver, not a crossing).
bool measuredAcross(const ScanLine &s, int i, int j, int width, int bg, int contrast, int aboveHalf, int d)
{
  const Run across = runThrough(s.score, s.W, s.H, i, j, s.alongRow ? 1 : 0, s.alongRow ? 0 : 1, aboveHalf, d + 1);
  if (across.length < width)
    return true;
  const int di = s.alongRow ? d : 0, dj = s.alongRow ? 0 : d;
  const int acrossBg =
      std::max(i - di >= 0 && j - dj >= 0 ? s.score[static_cast<size_t>(i - di) * s.W + (j - dj)] : 0,
               i + di < s.H && j + dj < s.W ? s.score[static_cast<size_t>(i + di) * s.W + (j + dj)] : 0);
  return across.maxScore - bg > RidgeTuning::grazingPeakRatio * contrast ||
         RidgeTuning::grazingContrastRatio * contrast < across.maxScore - acrossBg;
}

// The candidate test takes the first pixel of a saturated core's plateau of 255 for its peak: the middle of
// the plateau (at most d pixels of it) is where the stripe is, around which its background is sampled and its
// centroid's window is laid (from the first pixel, the window missed the far flank of a plateau 9-11 px wide).
int plateauMiddle(const ScanLine &s, int p, int d)
{
  if (s.at(p) != 255)
    return p;
  int last = p;
  while (last + 1 < s.length() && s.at(last + 1) == 255 && last - p < d)
    ++last;
  return (p + last) / 2;
}
} // namespace

Verdict analyse(const ScanLine &s, int candidate, const RidgeSettings &settings, int threshold, bool acrossScored,
                Crossing &out)
{
  const int n = s.length(), d = settings.maxWidth;
  const int p = plateauMiddle(s, candidate, d);
  const int peak = s.at(p);
  const int bg = background(s, p, d);
  const int contrast = peak - bg;
  if (contrast < threshold)
    return IGNORED;
  // Half-maximum run.
  const int aboveHalf = bg + contrast / 2; // floor(half): integer scores, s > half is s > floor(half)
  int a = p, b = p;
  while (a - 1 >= 0 && s.at(a - 1) > aboveHalf && p - a <= d)
    --a;
  while (b + 1 < n && s.at(b + 1) > aboveHalf && b - p <= d)
    ++b;
  out.alongRow = s.alongRow;
  out.line = s.line;
  out.first = a;
  out.last = b;
  if (b - a + 1 > settings.maxWidth)
    return REJECTED; // a wide red object, not a stripe
  if (whiteWithoutRedFlanks(s, a, b, settings.saturation, threshold))
    return REJECTED; // white light, not a laser
  const int i = s.alongRow ? s.line : p, j = s.alongRow ? p : s.line;
  if (acrossScored && measuredAcross(s, i, j, b - a + 1, bg, contrast, aboveHalf, d))
    return IGNORED;
  const double centre = stripeCentroid(s, p, a, b, bg, contrast, d);
  out.point = s.alongRow ? vpImagePoint(s.line, centre) : vpImagePoint(centre, s.line);
  return ACCEPTED;
}

int measureCandidate(const ScanLine &s, int p, const RidgeSettings &settings, int threshold, bool acrossScored,
                     RidgeWorkspace &work, std::vector<StripeRun> &runs)
{
  Crossing crossing;
  const Verdict verdict = analyse(s, p, settings, threshold, acrossScored, crossing);
  if (verdict == IGNORED)
    return -1;
  if (verdict == ACCEPTED)
    work.crossings.push_back(crossing);
  else
    runs.push_back(StripeRun{s.alongRow, crossing.line, crossing.first, crossing.last, false});
  return crossing.last;
}
} // namespace vsp::laser_detector
