/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The conic-guided pass of the ridge detector: walks the predicted conic, measures a profile where no point
// is known yet, keeps the pieces of curve that continue it, refits and walks again until no point is added;
// then drops the points off the final conic and measures their profiles again at it.
#include "guided_detail.h"

#include <algorithm>
#include <cmath>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace vsp::laser_detector
{
namespace
{
// The points found (by either pass), in lists per cell of 2^cellShift pixels.
class FoundCells
{
public:
  FoundCells(int W, int H, RidgeWorkspace &work)
    : m_columns((W >> RidgeTuning::guidedCellShift) + 1), m_rows((H >> RidgeTuning::guidedCellShift) + 1),
      m_heads(work.guidedCells), m_next(work.guidedNext), m_points(work.guidedFound)
  {
    // Only the cells of the previous detection's points are reset when the grid is the same: clearing the
    // whole grid (half a megabyte at 1600 x 1200) cost a tenth of the tracking mode's time.
    const size_t cells = static_cast<size_t>(m_columns) * m_rows;
    if (m_heads.size() != cells || work.guidedColumns != m_columns)
      m_heads.assign(cells, -1);
    else
      for (const vpImagePoint &p : m_points) {
        int a = 0, b = 0;
        if (cellOf(p.get_u(), p.get_v(), a, b))
          m_heads[static_cast<size_t>(b) * m_columns + a] = -1;
      }
    work.guidedColumns = m_columns;
    m_next.clear();
    m_points.clear();
  }
  void mark(const vpImagePoint &p)
  {
    int a = 0, b = 0;
    if (!cellOf(p.get_u(), p.get_v(), a, b))
      return;
    int &head = m_heads[static_cast<size_t>(b) * m_columns + a];
    m_next.push_back(head);
    head = static_cast<int>(m_points.size());
    m_points.push_back(p);
  }
  // Whether a point found lies on the profile of sample s: within RidgeTuning::guidedKnownAlong pixels of it along
  // the predicted curve and RidgeTuning::guidedKnownAcross across it. \e offset: then that point's offset across
  // the predicted curve (as ProfileResult::offset).
  bool covers(const GuidedSample &s, double &offset) const
  {
    if (m_points.empty()) // the first walk of a tracking pass: nothing to look up in the grid
      return false;
    const double u = s.alongRow ? s.pos : s.line, v = s.alongRow ? s.line : s.pos;
    int a = 0, b = 0;
    if (!cellOf(u, v, a, b))
      return false;
    const double norm = std::sqrt(s.slope * s.slope + 1.0); // not std::hypot: a call per sample
    const double tu = (s.alongRow ? s.slope : 1.0) / norm, tv = (s.alongRow ? 1.0 : s.slope) / norm;
    // The sample's own cell first: a point that covers it is most often there.
    static const int around[9][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    for (const int *cell : around) {
      const int x = a + cell[0], y = b + cell[1];
      if (x < 0 || y < 0 || x >= m_columns || y >= m_rows)
        continue;
      for (int k = m_heads[static_cast<size_t>(y) * m_columns + x]; k >= 0; k = m_next[static_cast<size_t>(k)]) {
        const double du = m_points[static_cast<size_t>(k)].get_u() - u,
                     dv = m_points[static_cast<size_t>(k)].get_v() - v;
        if (std::fabs(du * tu + dv * tv) <= RidgeTuning::guidedKnownAlong &&
            std::fabs(du * tv - dv * tu) <= RidgeTuning::guidedKnownAcross) {
          offset = (s.alongRow ? du - s.slope * dv : dv - s.slope * du) * s.toNormal;
          return true;
        }
      }
    }
    return false;
  }

private:
  bool cellOf(double u, double v, int &a, int &b) const
  {
    if (!(u >= 0.0 && v >= 0.0))
      return false;
    a = static_cast<int>(u) >> RidgeTuning::guidedCellShift;
    b = static_cast<int>(v) >> RidgeTuning::guidedCellShift;
    return a < m_columns && b < m_rows;
  }
  int m_columns, m_rows;
  std::vector<int> &m_heads, &m_next;
  std::vector<vpImagePoint> &m_points;
};

// Whether (u, v) lies in the spans of \e limit (everywhere when null).
bool inLimit(const RegionSpans *limit, int H, double u, double v)
{
  if (limit == nullptr)
    return true;
  const int i = static_cast<int>(std::lround(v)), j = static_cast<int>(std::lround(u));
  if (i < 0 || i >= H)
    return false;
  for (const Span *s = limit->begin(i); s != limit->end(i); ++s)
    if (j >= s->first && j <= s->second)
      return true;
  return false;
}

enum SampleState { MISSED, FOUND, KNOWN };

// The pieces of curve along the samples (in their order): runs of found samples, broken by more than
// RidgeTuning::guidedMaxMisses missed samples in a row or by a jump of the offset to the prediction. A piece is
// kept when it touches a known point (a sample near a point already found) or has RidgeTuning::guidedMinRun
// points; \e keep marks the found samples of the kept pieces.
void keepContinuingPieces(const std::vector<SampleState> &state, const std::vector<ProfileResult> &results,
                          std::vector<unsigned char> &keep)
{
  keep.assign(state.size(), 0);
  std::vector<size_t> piece;
  bool anchored = false;
  int misses = 0;
  double lastOffset = 0.0;
  size_t lastIndex = 0;
  bool afterKnown = false;
  auto close = [&]() {
    if (anchored || static_cast<int>(piece.size()) >= RidgeTuning::guidedMinRun)
      for (size_t k : piece)
        keep[k] = 1;
    piece.clear();
    anchored = false;
  };
  for (size_t i = 0; i < state.size(); ++i) {
    if (state[i] == KNOWN) {
      anchored = true;
      afterKnown = true;
      misses = 0;
      lastOffset = 0.0;
      lastIndex = i;
    } else if (state[i] == FOUND) {
      // Next to a known point the offset is that point's, within the fit's inlier threshold of the curve.
      const double allowed =
          (afterKnown ? 2.0 : RidgeTuning::guidedMaxJump) + RidgeTuning::guidedPerSampleJump * (i - lastIndex);
      if ((anchored || !piece.empty()) && std::fabs(results[i].offset - lastOffset) > allowed)
        close();
      piece.push_back(i);
      afterKnown = false;
      misses = 0;
      lastOffset = results[i].offset;
      lastIndex = i;
    } else if (++misses > RidgeTuning::guidedMaxMisses) {
      close();
      afterKnown = false;
    }
  }
  close();
}

// The window of a follow: RidgeTuning::guidedFollowMargin around the offset of the neighbouring sample's point,
// its threshold from \e lineNoise (the noise of one image line); the sample's line alone along a strong stripe,
// RidgeTuning::guidedLines otherwise.
ProfileWindow followWindow(const GuidedSample &s, double offset, double lineNoise, bool strong, bool fittedHere)
{
  ProfileWindow follow;
  follow.centre = offset / s.toNormal;
  follow.halfWidth = RidgeTuning::guidedFollowMargin / s.toNormal;
  follow.lineNoise = lineNoise;
  follow.lines = strong ? 1 : RidgeTuning::guidedLines;
  follow.preferPrediction = fittedHere;
  return follow;
}

// The window within RidgeTuning::guidedMaxJump (across the curve) of sample s's predicted crossing.
ProfileWindow predictionWindow(const GuidedSample &s)
{
  ProfileWindow window;
  window.halfWidth = RidgeTuning::guidedMaxJump / s.toNormal;
  return window;
}

// The brightness profile (ProfileWindow::brightness) of sample s within \e window: three lines averaged then,
// where they find nothing, nine (as the red profile of a faint stripe); \e accept(result) decides which found
// point counts as found, before the nine lines are tried.
template <class Accept>
ProfileResult brightnessProfile(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                ProfileWindow window, ProfileBuffers &buffers, Accept accept)
{
  window.brightness = true;
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

// A follow whose red score found nothing, measured on the brightness (ProfileWindow::brightness) within the
// follow's window around \e offset, three lines averaged then, where they find nothing, nine (as the red
// profile of a faint stripe): its point is kept only within RidgeTuning::guidedMaxJump of that offset, so
// that it continues the piece of curve (keepContinuingPieces()) rather than ending it (kept within the
// window's 3 px, points 1-3 px off broke the faint shipped frame 56's runs into pieces too short to keep:
// 0.965 -> 0.952 of its ring at 3 sigma, against 0.973 so).
ProfileResult followOnBrightness(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                 double offset, bool fittedHere, ProfileBuffers &buffers)
{
  return brightnessProfile(I, s, settings, followWindow(s, offset, -1.0, false, fittedHere), buffers,
                           [offset](const ProfileResult &r) {
                             return std::fabs(r.offset - offset) <= RidgeTuning::guidedMaxJump;
                           });
}

// A sample whose red profile found nothing where the prediction crosses a colour edge, measured on its
// brightness within RidgeTuning::guidedMaxJump of the prediction (see RidgeTuning::guidedColourEdge), three
// lines averaged then, where they find nothing, nine; kept when the response of the profile that found it
// reaches RidgeTuning::guidedBrightnessStrength times its threshold (nine lines are not tried after three that
// found a weaker one: that took noise on the faint rings, second-pass RMS 0.30 px on one seed).
ProfileResult brightnessAtPrediction(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                     ProfileBuffers &buffers)
{
  ProfileResult r =
      brightnessProfile(I, s, settings, predictionWindow(s), buffers, [](const ProfileResult &) { return true; });
  r.found = r.found && r.response >= RidgeTuning::guidedBrightnessStrength * r.threshold;
  return r;
}

// The walk follows a stripe forwards only: where it is lost for a few samples (a dim stretch on a dark joint,
// whose whole-margin profiles find nothing) and found again, the samples in between are followed backwards
// from where it is found again, as the walk would have followed them coming the other way: with the noise
// that point was found against, as a follow reuses the noise of the profiles before it (the missed samples'
// own whole-margin profiles, whose noise a joint's edges raise: 95.15 % of the mosaic's ring found against
// 95.21 %). Returns the samples found so.
int followBackwards(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const std::vector<GuidedSample> &samples,
                    bool fittedHere, ProfileBuffers &buffers, std::vector<SampleState> &state,
                    std::vector<ProfileResult> &results)
{
  int found = 0;
  for (size_t i = samples.size() < 2 ? 0 : samples.size() - 1; i-- > 0;) {
    const ProfileResult &next = results[i + 1];
    // results[i].lines == 0: not measured (outside the search limit, or no profile fits in the image).
    if (state[i] != MISSED || state[i + 1] != FOUND || results[i].lines == 0)
      continue;
    ProfileResult back;
    if (!next.brightness) // a point found on the brightness has no noise of the red score to lend
      back = measureProfile(I, samples[i], settings,
                            followWindow(samples[i], next.offset, next.lineNoise(), false, fittedHere), buffers);
    if (!back.found)
      back = followOnBrightness(I, samples[i], settings, next.offset, fittedHere, buffers);
    if (!back.found)
      continue;
    results[i] = back;
    state[i] = FOUND;
    ++found;
  }
  return found;
}

// Measures the samples no point covers yet (in \e limit when not null) and sets their state and result; returns
// the samples missed. A sample next to one with a point is first searched within RidgeTuning::guidedFollowMargin
// of that point's offset, with the noise of the last full profile (see RidgeTuning::guidedFollowMargin); the
// full margin is searched when that finds nothing, with RidgeTuning::guidedFaintLines lines when three find
// nothing, and a followed stripe that all of these lose is searched on its brightness (followOnBrightness());
// then the missed samples before a point found are followed back from it (followBackwards()).
// \e noises and \e thresholds: those of the full profiles, per image line. \e fittedHere: the samples'
// conic was fitted to the points found over the whole image (ProfileWindow::preferPrediction).
int measureSamples(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const std::vector<GuidedSample> &samples,
                   const RegionSpans *limit, const FoundCells &found, ProfileBuffers &buffers,
                   std::vector<SampleState> &state, std::vector<ProfileResult> &results, std::vector<double> &noises,
                   std::vector<double> &thresholds, bool fittedHere)
{
  const int H = static_cast<int>(I.getHeight());
  int missed = 0, lastWithPoint = -2, noiseSample = 0;
  double lastOffset = 0.0, lineNoise = -1.0;
  bool strong = false;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const GuidedSample &s = samples[static_cast<size_t>(i)];
    // The pixels of a profile a few samples on are asked for now: a frame just captured is not in cache,
    // and the profiles' reads, a few dozen bytes a row, each wait for memory otherwise (a sixth of the
    // tracking mode's time).
    if (i + RidgeTuning::guidedPrefetchAhead < static_cast<int>(samples.size()))
      prefetchProfile(I, samples[static_cast<size_t>(i) + RidgeTuning::guidedPrefetchAhead],
                      RidgeTuning::guidedPrefetchReach);
    double offset = 0.0;
    if (found.covers(s, offset)) {
      state[static_cast<size_t>(i)] = KNOWN;
      lastOffset = offset;
      lastWithPoint = i;
      continue;
    }
    if (!inLimit(limit, H, s.alongRow ? s.pos : s.line, s.alongRow ? s.line : s.pos))
      continue;
    ProfileResult &r = results[static_cast<size_t>(i)];
    if (lastWithPoint == i - 1 && lineNoise >= 0.0 && i - noiseSample <= RidgeTuning::guidedNoiseReuse)
      r = measureProfile(I, s, settings, followWindow(s, lastOffset, lineNoise, strong, fittedHere), buffers);
    if (!r.found) {
      // The whole margin: the continuation was not found, or the noise is to be measured again. Along a
      // bright stripe that is followed, the sample's line alone gives that noise and finds the stripe (the
      // three lines read when it does not).
      ProfileWindow whole;
      whole.lines = strong && lastWithPoint == i - 1 ? 1 : RidgeTuning::guidedLines;
      r = measureProfile(I, s, settings, whole, buffers);
      if (!r.found && whole.lines == 1)
        r = measureProfile(I, s, settings, ProfileWindow(), buffers);
      if (!r.found) { // a faint stripe: a longer stretch of the curve averaged
        ProfileWindow faint;
        faint.lines = RidgeTuning::guidedFaintLines;
        const ProfileResult longer = measureProfile(I, s, settings, faint, buffers);
        if (longer.found)
          r = longer;
      }
      if (r.lines > 0) {
        lineNoise = r.lineNoise();
        noiseSample = i;
        strong = r.found && r.response >= RidgeTuning::guidedStrongStripe * r.threshold;
        noises.push_back(lineNoise);
        thresholds.push_back(r.threshold / r.lines);
      }
    }
    if (!r.found && lastWithPoint == i - 1) { // the followed stripe's colour lost (see ProfileWindow::brightness)
      const ProfileResult bright = followOnBrightness(I, s, settings, lastOffset, fittedHere, buffers);
      if (bright.found)
        r = bright;
    }
    if (!r.found && fittedHere && r.edgeAtPrediction >= RidgeTuning::guidedColourEdge * r.threshold) {
      const ProfileResult bright = brightnessAtPrediction(I, s, settings, buffers);
      if (bright.found)
        r = bright;
    }
    state[static_cast<size_t>(i)] = r.found ? FOUND : MISSED;
    if (r.found) {
      lastOffset = r.offset;
      lastWithPoint = i;
    } else
      ++missed;
  }
  return missed - followBackwards(I, settings, samples, fittedHere, buffers, state, results);
}

// Share of the samples (those in \e limit) that are known or whose point is kept; \e searched: how many.
double walkCoverage(const std::vector<GuidedSample> &samples, const RegionSpans *limit, int H,
                    const std::vector<SampleState> &state, const std::vector<unsigned char> &keep, size_t &searched)
{
  searched = 0;
  size_t covered = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const GuidedSample &s = samples[i];
    if (state[i] != KNOWN && !inLimit(limit, H, s.alongRow ? s.pos : s.line, s.alongRow ? s.line : s.pos))
      continue;
    ++searched;
    covered += state[i] == KNOWN || keep[i] ? 1 : 0;
  }
  return searched ? static_cast<double>(covered) / searched : 0.0;
}

// Least-squares ellipse through the points (a subsample of a few hundred). The subsample is chosen by
// position, and sorted when \e fromFirstPass (the points start with the first pass's): the same points in any
// order (the first pass's order depends on how it searched) give the same ellipse, to the last bit, and so
// the same regularised centres (smoothAlongCurve()). The pass's own points come in the order of its walks.
bool refit(const std::vector<vpImagePoint> &points, bool fromFirstPass, Eigen::Matrix3d &C)
{
  std::vector<Eigen::Vector2d> sample;
  positionSubsample(points, 600, fromFirstPass, sample);
  Eigen::Matrix3d c;
  if (sample.size() < 5 || !vpLaserSolvers::fitConic(sample.data(), static_cast<int>(sample.size()), c) ||
      !vpLaserSolvers::isEllipse(c))
    return false;
  C = c;
  return true;
}

// Drops the crossings farther than RidgeTuning::guidedFinalDistance pixels (Sampson distance) from the conic C
// refitted on all the points: a piece that continued the prediction of an early, extrapolated fit but not
// the curve that all the points make (a stripe-like texture near the curve). Those dropped go to \e dropped.
void keepOnTheFinalCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings, std::vector<Crossing> &dropped)
{
  size_t kept = 0;
  for (const Crossing &c : crossings) {
    if (vpLaserSolvers::sampsonDistance(C, Eigen::Vector2d(c.point.get_u(), c.point.get_v())) <=
        RidgeTuning::guidedFinalDistance)
      crossings[kept++] = c;
    else
      dropped.push_back(c);
  }
  crossings.resize(kept);
}

// A crossing's image line and its position along it, ordered by line.
struct LinePosition
{
  int line; // rows first, then columns (H + column)
  double pos;
  bool operator<(const LinePosition &o) const { return line < o.line || (line == o.line && pos < o.pos); }
};

std::vector<LinePosition> linePositions(const std::vector<Crossing> &crossings, int H)
{
  std::vector<LinePosition> positions;
  positions.reserve(crossings.size());
  for (const Crossing &c : crossings)
    positions.push_back({c.alongRow ? c.line : H + c.line, c.alongRow ? c.point.get_u() : c.point.get_v()});
  std::sort(positions.begin(), positions.end());
  return positions;
}

// Whether one of \e positions (sorted) lies on the line of sample s within its margin.
bool onSampleProfile(const std::vector<LinePosition> &positions, const GuidedSample &s, int H)
{
  const int line = s.alongRow ? s.line : H + s.line;
  auto it = std::lower_bound(positions.begin(), positions.end(), LinePosition{line, s.pos - s.halfWindow});
  return it != positions.end() && it->line == line && it->pos <= s.pos + s.halfWindow;
}

// Where a walk followed a neighbouring structure away from the ring, keepOnTheFinalCurve() drops the points it
// took there and leaves the ring without any: beside a red cable, the stripe's red dominance is a shoulder on
// the cable's flank, and a follow window moving a fraction of a pixel a sample slides onto the flank (data/
// laser_hard frame 27: the offset to the prediction growing to 9 px over 20 samples while the fitted conic
// stays within a pixel of the ring); on a mosaic, onto a joint's edge beside the stripe. The samples of the
// final conic C whose profile held such a dropped point and holds no kept one are measured again at C, within
// RidgeTuning::guidedMaxJump of it: on the red score (the stripe the follow left), then on the brightness
// (brightnessAtPrediction(), whose bump the stripe keeps beside a cable), each at its own strength (see
// RidgeTuning::guidedRemeasureStrength). A point found farther off is a flank, as where the image of the
// ring is not quite an ellipse (a lens's distortion) and C lies beside the stripe. Appends the points found
// to \e kept.
void remeasureWhereDropped(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &C,
                           const std::vector<Crossing> &dropped, ProfileBuffers &buffers, std::vector<Crossing> &kept)
{
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  std::vector<GuidedSample> samples;
  if (dropped.empty() || !sampleConic(C, W, H, settings.margin, settings.step, samples))
    return;
  const std::vector<LinePosition> droppedAt = linePositions(dropped, H), keptAt = linePositions(kept, H);
  // A point within guidedMaxJump of C whose response reaches \e strength times its threshold.
  const auto atConic = [](const ProfileResult &r, double strength) {
    return r.found && std::fabs(r.offset) <= RidgeTuning::guidedMaxJump && r.response >= strength * r.threshold;
  };
  for (const GuidedSample &s : samples) {
    if (!onSampleProfile(droppedAt, s, H) || onSampleProfile(keptAt, s, H))
      continue;
    const ProfileResult red = measureProfile(I, s, settings, predictionWindow(s), buffers);
    if (atConic(red, RidgeTuning::guidedRemeasureRedStrength)) {
      kept.push_back(red.crossing);
      continue;
    }
    const ProfileResult bright = brightnessAtPrediction(I, s, settings, buffers);
    if (atConic(bright, RidgeTuning::guidedRemeasureStrength))
      kept.push_back(bright.crossing);
  }
}

double median(std::vector<double> &values)
{
  if (values.empty())
    return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}
} // namespace

void guidedPass(const vpImage<vpRGBa> &I, const GuidedSettings &settings, const Eigen::Matrix3d &prediction,
                const std::vector<vpImagePoint> &anchors, const RegionSpans *limit, std::vector<vpImagePoint> &points,
                RidgeWorkspace &work, GuidedReport &report)
{
  report = GuidedReport();
  work.guided.clear();
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  FoundCells found(W, H, work);
  for (const vpImagePoint &p : anchors)
    found.mark(p);
  std::vector<vpImagePoint> fitPoints = anchors;
  std::vector<GuidedSample> samples;
  std::vector<SampleState> state;
  std::vector<ProfileResult> results;
  std::vector<unsigned char> keep;
  std::vector<double> noises, thresholds;
  ProfileBuffers buffers;
  Eigen::Matrix3d C = prediction;
  report.ran = true;
  // Over the whole image the prediction is the ellipse of the first pass's points (the anchors), then its
  // refits. Not in tracking: the previous frame's conic, then refits on the pass's own points, which may hold
  // one arc of a fading ring (data/laser_hard tracked: pitch errors of 1.1-1.4 deg on frames 50 and 53 when
  // refits counted as fitted here, against 0.04-0.07).
  const bool fittedHere = !anchors.empty();
  for (int iteration = 0; iteration < RidgeTuning::guidedMaxIterations; ++iteration) {
    if (!sampleConic(C, W, H, settings.margin, settings.step, samples))
      break;
    ++report.iterations;
    fitPoints.reserve(fitPoints.size() + samples.size());
    state.assign(samples.size(), MISSED);
    results.assign(samples.size(), ProfileResult());
    const int missed =
        measureSamples(I, settings, samples, limit, found, buffers, state, results, noises, thresholds, fittedHere);
    keepContinuingPieces(state, results, keep);
    size_t searched = 0;
    report.coverage = walkCoverage(samples, limit, H, state, keep, searched);
    if (iteration == 0)
      report.predictionSamples = static_cast<int>(searched);
    int added = 0;
    for (size_t i = 0; i < samples.size(); ++i)
      if (keep[i]) {
        fitPoints.push_back(results[i].crossing.point);
        work.guided.push_back(results[i].crossing);
        found.mark(results[i].crossing.point);
        ++added;
      }
    // The walk stops when the coverage stops growing, when no sample was missed (another walk along the
    // refitted conic would measure nothing) or when there is no better prediction. The conic is refitted
    // even then, as the points' (sorted) fit whatever the order the first pass returned them in: it is the
    // final conic the pass's points are checked against and regularised along. A pass without points of
    // its own needs no final conic.
    if (added == 0 && work.guided.empty())
      break;
    const bool refitted = refit(fitPoints, !anchors.empty(), C);
    if (added == 0 || missed == 0 || !refitted)
      break;
  }
  std::vector<Crossing> dropped;
  keepOnTheFinalCurve(C, work.guided, dropped);
  if (fittedHere)
    remeasureWhereDropped(I, settings, C, dropped, buffers, work.guided);
  smoothAlongCurve(C, work.guided);
  points.reserve(points.size() + work.guided.size());
  for (const Crossing &c : work.guided)
    points.push_back(c.point);
  report.added = static_cast<int>(work.guided.size());
  report.noise = median(noises);
  report.threshold = median(thresholds);
}
} // namespace vsp::laser_detector
