/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The conic-guided pass of the ridge detector: walks the predicted conic, measures a profile where no point
// is known yet, keeps the pieces of curve that continue it, refits and walks again until no point is added;
// then refits the final conic on the points near it and drops those off it (its gaps: guided_gaps.cpp).
#include "guided_detail.h"
#include "guided_found_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace vsp::laser_detector
{
namespace
{
// Where the pieces of a closed ring's samples are read from: after its first run of more than
// RidgeTuning::guidedMaxMisses missed samples (a piece ends there whatever the start), else at its first known
// sample (a piece through it is kept whatever its length), else at 0.
size_t ringStart(const std::vector<SampleState> &state)
{
  const size_t n = state.size();
  int misses = 0;
  for (size_t k = 0; k < 2 * n; ++k) {
    if (state[onTheRing(k, n)] != MISSED)
      misses = 0;
    else if (++misses > RidgeTuning::guidedMaxMisses)
      return (k + 1) % n; // once per call
  }
  for (size_t k = 0; k < n; ++k)
    if (state[k] == KNOWN)
      return k;
  return 0;
}
} // namespace

void keepContinuingPieces(const std::vector<SampleState> &state, const std::vector<ProfileResult> &results,
                          std::vector<unsigned char> &keep, bool closed)
{
  keep.assign(state.size(), 0);
  const size_t n = state.size(), first = closed && n > 0 ? ringStart(state) : 0;
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
  // Position p along the samples from \e first (round the ring when closed), sample i.
  for (size_t p = 0; p < n; ++p) {
    const size_t i = onTheRing(first + p, n);
    if (state[i] == KNOWN) {
      anchored = true;
      afterKnown = true;
      misses = 0;
      lastOffset = 0.0;
      lastIndex = p;
    } else if (state[i] == FOUND) {
      // Next to a known point the offset is that point's, within the fit's inlier threshold of the curve.
      const double allowed =
          (afterKnown ? 2.0 : RidgeTuning::guidedMaxJump) + RidgeTuning::guidedPerSampleJump * (p - lastIndex);
      if ((anchored || !piece.empty()) && std::fabs(results[i].offset - lastOffset) > allowed)
        close();
      piece.push_back(i);
      afterKnown = false;
      misses = 0;
      lastOffset = results[i].offset;
      lastIndex = p;
    } else if (++misses > RidgeTuning::guidedMaxMisses) {
      close();
      afterKnown = false;
    }
  }
  close();
}

ProfileWindow predictionWindow(const GuidedSample &s, double offset)
{
  ProfileWindow window;
  window.centre = alongOf(s, offset);
  window.halfWidth = RidgeTuning::guidedMaxJump / s.toNormal;
  window.peakWithin = true;
  return window;
}

ProfileWindow onBrightness(ProfileWindow window)
{
  window.brightness = true;
  return window;
}

ProfileResult brightnessAtPrediction(const vpImage<vpRGBa> &I, const GuidedSample &s, const GuidedSettings &settings,
                                     const ProfileWindow &window, ProfileBuffers &buffers)
{
  ProfileResult r =
      threeThenNineLines(I, s, settings, onBrightness(window), buffers, [](const ProfileResult &) { return true; });
  r.found = r.found && r.response >= RidgeTuning::guidedBrightnessStrength * r.threshold &&
            r.response >= RidgeTuning::guidedEdgeBump * r.stepAtStripe;
  return r;
}

double median(std::vector<double> &values)
{
  if (values.empty())
    return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

namespace
{
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

// The window of a follow: RidgeTuning::guidedFollowMargin around the offset of the neighbouring sample's point,
// its threshold from \e lineNoise (the noise of one image line); the sample's line alone along a strong stripe,
// RidgeTuning::guidedLines otherwise.
ProfileWindow followWindow(const GuidedSample &s, double offset, double lineNoise, bool strong, bool fittedHere)
{
  ProfileWindow follow;
  follow.centre = alongOf(s, offset);
  follow.halfWidth = RidgeTuning::guidedFollowMargin / s.toNormal;
  follow.lineNoise = lineNoise;
  follow.lines = strong ? 1 : RidgeTuning::guidedLines;
  follow.preferPrediction = fittedHere;
  return follow;
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
  return threeThenNineLines(I, s, settings, onBrightness(followWindow(s, offset, -1.0, false, fittedHere)), buffers,
                            NearOffset{offset, 0.0});
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
  PrefetchedColumns prefetched;
  double lastOffset = 0.0, lineNoise = -1.0;
  bool strong = false;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const GuidedSample &s = samples[static_cast<size_t>(i)];
    // The pixels of a profile a few samples on are asked for now: a frame just captured is not in cache,
    // and the profiles' reads, a few dozen bytes a row, each wait for memory otherwise (a sixth of the
    // tracking mode's time). Along a strong stripe, the profiles read the sample's line alone.
    if (i + RidgeTuning::guidedPrefetchAhead < static_cast<int>(samples.size()))
      prefetchProfile(I, samples[static_cast<size_t>(i) + RidgeTuning::guidedPrefetchAhead],
                      RidgeTuning::guidedPrefetchReach, strong, prefetched);
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
      const ProfileResult bright = brightnessAtPrediction(I, s, settings, predictionWindow(s), buffers);
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

// Share of the samples (those in \e limit) that are known or whose point is kept.
double walkCoverage(const std::vector<GuidedSample> &samples, const RegionSpans *limit, int H,
                    const std::vector<SampleState> &state, const std::vector<unsigned char> &keep)
{
  size_t searched = 0, covered = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const GuidedSample &s = samples[i];
    if (state[i] != KNOWN && !inLimit(limit, H, s.alongRow ? s.pos : s.line, s.alongRow ? s.line : s.pos))
      continue;
    ++searched;
    covered += state[i] == KNOWN || keep[i] ? 1 : 0;
  }
  return searched ? static_cast<double>(covered) / searched : 0.0;
}

// Whether \e p lies on a pixel of the W x H image.
bool inTheImage(const vpImagePoint &p, int W, int H)
{
  const double u = p.get_u(), v = p.get_v();
  return u >= -0.5 && v >= -0.5 && u <= W - 0.5 && v <= H - 0.5;
}

// Samples (those in \e limit) whose predicted crossing lies in the W x H image: the predicted curve's length
// there, in samples (sampleConic() also keeps those up to the margin beyond the image's border).
int samplesInTheImage(const std::vector<GuidedSample> &samples, const RegionSpans *limit, int W, int H)
{
  int inside = 0;
  for (const GuidedSample &s : samples) {
    const vpImagePoint p = samplePoint(s, s.pos);
    inside += inTheImage(p, W, H) && inLimit(limit, H, p.get_u(), p.get_v()) ? 1 : 0;
  }
  return inside;
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

// The final conic: refitted on the points within RidgeTuning::guidedFinalDistance of the fit of them all,
// RidgeTuning::guidedFinalRefits times. The fit of them all is pulled by the pieces a walk took beside the
// ring (a joint's edge, a cable's flank, a few pixels off over a hundred): on the mosaic floor of the tests
// it lay 0.30-2.11 px from the true centre line at its worst point (seeds 73-102), against 0.06-0.35 px so
// (seed 93: 2.11 -> 0.17 px). The outliers were the cause, not the algebraic fit: the points weighted by the
// inverse of their gradient (the Sampson distance's) moved the worst point by 0.01 px at most (seeds 90-95,
// three refits at 1.5 px). The points dropped as off the final curve, the samples measured again at it and
// the centres regularised along it all read it. \e points start with the first pass's (see refit()).
void refitOnItsInliers(const std::vector<vpImagePoint> &points, Eigen::Matrix3d &C)
{
  std::vector<vpImagePoint> inliers;
  for (int round = 0; round < RidgeTuning::guidedFinalRefits; ++round) {
    inliers.clear();
    for (const vpImagePoint &p : points)
      if (vpLaserSolvers::sampsonDistance(C, Eigen::Vector2d(p.get_u(), p.get_v())) <= RidgeTuning::guidedFinalDistance)
        inliers.push_back(p);
    if (inliers.size() == points.size() || !refit(inliers, true, C))
      return;
  }
}

// Drops the crossings farther than RidgeTuning::guidedFinalDistance pixels (Sampson distance) from the final
// conic C: a piece that continued the prediction of an early, extrapolated fit but not the curve that all
// the points make (a stripe-like texture near the curve).
void keepOnTheFinalCurve(const Eigen::Matrix3d &C, std::vector<Crossing> &crossings)
{
  size_t kept = 0;
  for (const Crossing &c : crossings)
    if (vpLaserSolvers::sampsonDistance(C, Eigen::Vector2d(c.point.get_u(), c.point.get_v())) <=
        RidgeTuning::guidedFinalDistance)
      crossings[kept++] = c;
  crossings.resize(kept);
}

// Appends the points of the kept samples to \e fitPoints and their crossings to \e guided, and marks them in
// \e found when \e lookedUp; returns how many. The points found are looked up by the next walk only, and there is
// none when no sample was missed (the measurement along the final curve marks them again): a tracked frame's
// walk, which misses none, marks none.
int addKeptPoints(const std::vector<unsigned char> &keep, const std::vector<ProfileResult> &results, bool lookedUp,
                  std::vector<vpImagePoint> &fitPoints, std::vector<Crossing> &guided, FoundCells &found)
{
  int added = 0;
  for (size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) {
      fitPoints.push_back(results[i].crossing.point);
      guided.push_back(results[i].crossing);
      if (lookedUp)
        found.mark(results[i].crossing.point);
      ++added;
    }
  return added;
}

// Drops the crossings whose centre an earlier one of \e guided has already (\e found is cleared). A walk along a
// refitted conic measures again a sample whose prediction moved along its line by more than
// RidgeTuning::guidedKnownAlong (the dim side, where the refits move most) and finds the same centre; the walks and
// the gaps keep it each time, and the refits count it so (weighting the arcs they moved most), but it is one
// measurement: returned once, it does not count two to four times in an estimate from the points and its
// covariance (seed 117 of the faint ring through the wide lens: 29 centres twice or more).
void dropRepeatedCentres(FoundCells &found, std::vector<Crossing> &guided)
{
  found.clear();
  size_t kept = 0;
  for (const Crossing &c : guided)
    if (!found.holds(c.point)) {
      found.mark(c.point);
      guided[kept++] = c;
    }
  guided.resize(kept);
}

// Drops the crossings outside a W x H image. The regularisation moves a point along the curve's normal: beside the
// image's border it can move it out of the image (found by the detector's fuzz target: -0.58 px), where no pixel
// measured it.
void dropOutsideTheImage(int W, int H, std::vector<Crossing> &guided)
{
  guided.erase(std::remove_if(guided.begin(), guided.end(),
                              [W, H](const Crossing &c) { return !inTheImage(c.point, W, H); }),
               guided.end());
}

// The stretches of the final conic C of a ring that fades (\e faded: the points of C in the gaps it fades into)
// measured as a whole (measureStretches()), then again along C refitted on all the points, as long as points are
// added (RidgeTuning::stretchRounds rounds at most).
void measureFadingStretches(const vpImage<vpRGBa> &I, const GuidedSettings &settings,
                            const std::vector<vpImagePoint> &anchors, const std::vector<vpImagePoint> &faded,
                            Eigen::Matrix3d &C, std::vector<Crossing> &guided)
{
  for (int round = 0; round < RidgeTuning::stretchRounds; ++round) {
    if (measureStretches(I, settings, C, anchors, faded, guided) == 0 || round + 1 == RidgeTuning::stretchRounds)
      return;
    std::vector<vpImagePoint> all = anchors;
    for (const Crossing &c : guided)
      all.push_back(c.point);
    refitOnItsInliers(all, C);
  }
}

// Whether the walk along a refitted conic shows it wandering through clutter: it took points along much of the
// moved curve, measured again, for little more coverage (see RidgeTuning::guidedWanderShare).
bool wandersThroughClutter(int iteration, int added, size_t samples, double coverageGain)
{
  return iteration > 0 && added > RidgeTuning::guidedWanderShare * static_cast<double>(samples) &&
         coverageGain < RidgeTuning::guidedWanderGain;
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
  double previousCoverage = 0.0;
  int repeated = 0; // centres measured again (see dropRepeatedCentres())
  for (int iteration = 0; iteration < RidgeTuning::guidedMaxIterations; ++iteration) {
    if (!sampleConic(C, W, H, settings.margin, settings.step, samples))
      break;
    ++report.iterations;
    fitPoints.reserve(fitPoints.size() + samples.size());
    state.assign(samples.size(), MISSED);
    results.assign(samples.size(), ProfileResult());
    const int missed =
        measureSamples(I, settings, samples, limit, found, buffers, state, results, noises, thresholds, fittedHere);
    keepContinuingPieces(state, results, keep, closedRing(samples, settings.step));
    report.coverage = walkCoverage(samples, limit, H, state, keep);
    if (iteration == 0)
      report.predictionSamples = samplesInTheImage(samples, limit, W, H);
    // A later walk's repeats: its predecessor missed samples, so that its points are marked in found.
    if (iteration > 0)
      repeated += heldCentres(keep, results, found);
    const int added = addKeptPoints(keep, results, missed > 0, fitPoints, work.guided, found);
    const bool wanders = wandersThroughClutter(iteration, added, samples.size(), report.coverage - previousCoverage);
    previousCoverage = report.coverage;
    // The walk stops when the conic wanders, when no sample was missed (another walk along the
    // refitted conic would measure nothing) or when there is no better prediction. The conic is refitted
    // even then, as the points' (sorted) fit whatever the order the first pass returned them in: it is the
    // final conic the pass's points are checked against and regularised along. A pass without points of
    // its own needs no final conic, nor does one its caller will not use (RidgeTuning::guidedMaxCoverageGrowth).
    if ((added == 0 && work.guided.empty()) ||
        report.coverage + RidgeTuning::guidedMaxCoverageGrowth < settings.usefulCoverage)
      break;
    const bool refitted = refit(fitPoints, !anchors.empty(), C);
    if (added == 0 || missed == 0 || !refitted || wanders)
      break;
  }
  if (report.coverage < settings.usefulCoverage)
    return; // a location its caller will not take (on a frame without the laser: a tenth of its time)
  // Not in tracking, whose walks fit the pass's own points only (and whose time is short).
  if (fittedHere && !work.guided.empty())
    refitOnItsInliers(fitPoints, C);
  keepOnTheFinalCurve(C, work.guided);
  std::vector<vpImagePoint> faded;
  if (fittedHere)
    repeated += measureTheFinalCurvesGaps(I, settings, C, anchors, found, buffers, work.guided, faded);
  dropIsolatedPieces(smoothAlongCurve(C, work.guided), anchors, work.guided);
  if (!faded.empty())
    measureFadingStretches(I, settings, anchors, faded, C, work.guided);
  if (repeated > 0) // none on most frames, a single walk's (tracking) among them
    dropRepeatedCentres(found, work.guided);
  dropOutsideTheImage(W, H, work.guided);
  points.reserve(points.size() + work.guided.size());
  for (const Crossing &c : work.guided)
    points.push_back(c.point);
  report.added = static_cast<int>(work.guided.size());
  report.noise = median(noises);
  report.threshold = median(thresholds);
}
} // namespace vsp::laser_detector
