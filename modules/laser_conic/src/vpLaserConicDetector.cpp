/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicDetector.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "detector/guided_pass.h"
#include "detector/laser_detector.h"
#include "detector/ridge_chains.h"
#include "detector/search_region.h"
#include "detector/straight_runs.h"
#include "laser_value_check.h"

namespace
{
//! The settings' check: every message begins with the class's name.
void check(bool ok, const char *message)
{
  vsp::laser_value_check::require(ok, std::string("vpLaserConicDetector: ") + message);
}

// \e value if it is finite and > 0, else the error \e message.
double positive(double value, const char *message)
{
  check(std::isfinite(value) && value > 0.0, message);
  return value;
}

// \e value if it is a margin the detector takes (> 0, at most vpLaserConicDetector::getMaxMargin(): beyond,
// the pixel positions a search window spans no longer fit its integers), else an error naming \e what and
// the bound (the message is built from the bound, so the two cannot disagree).
double validMargin(double value, const char *what)
{
  const double largest = vpLaserConicDetector::getMaxMargin();
  if (!(value > 0.0 && value <= largest))
    check(false, (std::string(what) + " must be positive and at most " + std::to_string(static_cast<long>(largest)) +
                  " pixels")
                     .c_str());
  return value;
}

// \e value if it is a step the detector takes (> 0, at most vpLaserConicDetector::getMaxStep(): beyond, the line
// indices and chain lengths it multiplies overflowed an int, and a detection hung or read outside the image),
// else an error naming \e what and the bound.
unsigned int validStep(unsigned int value, const char *what)
{
  const unsigned int largest = vpLaserConicDetector::getMaxStep();
  if (!(value > 0 && value <= largest))
    check(false, (std::string(what) + " must be positive and at most " + std::to_string(largest) + " lines").c_str());
  return value;
}

/*!
  The points of the conic C (its symmetric part: a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f = 0) on every row and
  column of a large image (vsp::laser_detector::sampleConicOnLines()), appended to \e points, or with \e points
  null whether there is one.
*/
bool sampleOnLines(const vpMatrix &C, double margin, std::vector<vpImagePoint> *points)
{
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1], d = 0.5 * (C[0][2] + C[2][0]),
               e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  return vsp::laser_detector::sampleConicOnLines(a, b, c, d, e, f, margin, points);
}
} // namespace

vpLaserConicDetector::vpLaserConicDetector()
  : m_method(DETECTION_RIDGE), m_minContrast(10.0), m_noiseFactor(5.0), m_minSegmentLength(50.0), m_maxStripeWidth(12),
    m_saturationLevel(250), m_step(1), m_instructions(INSTRUCTIONS_BEST), m_maxHueLow(10), m_minHueHigh(170),
    m_minSaturation(80), m_minValue(80), m_region(), m_regionMargin(0.0), m_regionGeneration(0), m_mask(),
    m_maskDirty(false), m_height(0), m_width(0), m_threshold(0.0), m_noise(0.0), m_guided(true), m_guidedMargin(12.0),
    m_guidedFactor(3.5), m_guidedStep(1), m_trackingStep(2), m_guidedCount(0), m_stripeWidth(0), m_regionIsConic(false),
    m_regionConic(3, 3, 0.0), m_work(), m_runs()
{
}

vpLaserConicDetector::vpWorkspace::vpWorkspace() : m_work(new vsp::laser_detector::RidgeWorkspace) {}

vpLaserConicDetector::vpWorkspace::vpWorkspace(const vpWorkspace &other) : vpWorkspace()
{
  *this = other; // empty buffers of its own, the last detection's crossings copied (see operator=)
}

vpLaserConicDetector::vpWorkspace &vpLaserConicDetector::vpWorkspace::operator=(const vpWorkspace &other)
{
  // The buffers are not state: each detector keeps its own. The rasterised region belongs to the settings
  // being replaced, whatever its generation number says. The last detection's crossings are state.
  if (this != &other) {
    m_work->regionValid = false;
    m_work->crossings = other.m_work->crossings;
    m_work->keep = other.m_work->keep;
    m_work->guided = other.m_work->guided;
  }
  return *this;
}

vpLaserConicDetector::vpWorkspace::~vpWorkspace() = default;

void vpLaserConicDetector::setMinContrast(double greyLevels)
{
  check(std::isfinite(greyLevels) && greyLevels >= 1.0 && greyLevels <= 255.0,
        "the minimum contrast must be in [1, 255]");
  m_minContrast = greyLevels;
}

void vpLaserConicDetector::setNoiseFactor(double factor)
{
  check(std::isfinite(factor) && factor >= 0.0, "the noise factor must be finite and >= 0");
  m_noiseFactor = factor;
}

void vpLaserConicDetector::setMaxStripeWidth(unsigned int pixels)
{
  check(pixels > 0 && pixels <= 100, "the maximum stripe width must be in [1, 100] pixels");
  m_maxStripeWidth = pixels;
  ++m_regionGeneration; // the scored band is the search band dilated by the stripe width
}

void vpLaserConicDetector::setSaturationLevel(unsigned int level)
{
  check(level >= 128 && level <= 255, "the saturation level must be in [128, 255]");
  m_saturationLevel = level;
}

void vpLaserConicDetector::setMinSegmentLength(double pixels)
{
  check(std::isfinite(pixels) && pixels >= 0.0, "the minimum segment length must be finite and >= 0");
  m_minSegmentLength = pixels;
}

void vpLaserConicDetector::setGuidedMargin(double pixels)
{
  m_guidedMargin = validMargin(pixels, "the guided search margin");
}

void vpLaserConicDetector::setGuidedStep(unsigned int lines)
{
  m_guidedStep = validStep(lines, "the guided search step");
}

void vpLaserConicDetector::setTrackingStep(unsigned int lines)
{
  m_trackingStep = validStep(lines, "the tracking step");
}

void vpLaserConicDetector::setGuidedThresholdFactor(double factor)
{
  m_guidedFactor = positive(factor, "the guided search threshold factor must be positive and finite");
}

void vpLaserConicDetector::setSamplingStep(unsigned int step) { m_step = validStep(step, "the sampling step"); }

vpLaserConicDetector::vpInstructionSet vpLaserConicDetector::getBestInstructionSet()
{
#if defined(__SSE2__)
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2)
    return INSTRUCTIONS_AVX2;
#endif
  return INSTRUCTIONS_SSE2;
#else
  return INSTRUCTIONS_SCALAR;
#endif
}

vpLaserConicDetector::vpInstructionSet vpLaserConicDetector::getInstructionSetUsed() const
{
  const vpInstructionSet best = getBestInstructionSet();
  return m_instructions == INSTRUCTIONS_BEST || m_instructions > best ? best : m_instructions;
}

void vpLaserConicDetector::setHueRange(int maxHueLow, int minHueHigh)
{
  check(maxHueLow >= 0 && maxHueLow <= 179 && minHueHigh >= 0 && minHueHigh <= 179,
        "hue bounds must be in [0, 179] (OpenCV scale)");
  m_maxHueLow = maxHueLow;
  m_minHueHigh = minHueHigh;
}

void vpLaserConicDetector::setMinSaturationValue(int minSaturation, int minValue)
{
  check(minSaturation >= 0 && minSaturation <= 255 && minValue >= 0 && minValue <= 255,
        "saturation and value bounds must be in [0, 255]");
  m_minSaturation = minSaturation;
  m_minValue = minValue;
}

void vpLaserConicDetector::setSearchRegion(const std::vector<vpImagePoint> &trace, double margin)
{
  validMargin(margin, "the search margin");
  check(!trace.empty(), "the search region needs at least one point");
  for (const vpImagePoint &p : trace)
    check(std::isfinite(p.get_u()) && std::isfinite(p.get_v()), "a point of the search region is not finite");
  m_region = trace;
  m_regionIsConic = false;
  m_regionMargin = margin;
  ++m_regionGeneration;
}

void vpLaserConicDetector::setSearchRegion(const vpMatrix &C, double margin)
{
  check(C.getRows() == 3 && C.getCols() == 3, "the conic must be a 3x3 matrix");
  validMargin(margin, "the search margin");
  double norm = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j) {
      check(std::isfinite(C[i][j]), "the conic has a non-finite coefficient");
      norm = std::max(norm, std::fabs(C[i][j]));
    }
  check(norm > 0.0, "the conic is zero");
  check(sampleOnLines(C, margin, nullptr), "the conic has no real point near the image");
  // The band around the conic is sampled only when the first pass searches it (a lost track): a tracked
  // frame reads the conic alone, and sampling every row and column of the large image on every call added
  // about 110 us to a tracked frame's 270 us.
  m_region.clear();
  m_regionIsConic = true;
  m_regionConic = C;
  m_regionMargin = margin;
  ++m_regionGeneration;
}

void vpLaserConicDetector::rasteriseRegion(int H, int W)
{
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  if (work.regionValid && work.regionGeneration == m_regionGeneration &&
      work.regionHeight == static_cast<unsigned int>(H) && work.regionWidth == static_cast<unsigned int>(W))
    return;
  if (m_regionIsConic && m_region.empty())
    sampleOnLines(m_regionConic, m_regionMargin, &m_region);
  vsp::laser_detector::rasteriseBand(m_region, m_regionMargin, static_cast<int>(m_maxStripeWidth), H, W,
                                     work.searchRegion, work.scoreRegion);
  work.regionValid = true;
  work.regionGeneration = m_regionGeneration;
  work.regionHeight = static_cast<unsigned int>(H);
  work.regionWidth = static_cast<unsigned int>(W);
}

const vpImage<unsigned char> &vpLaserConicDetector::getMask() const
{
  if (m_maskDirty) {
    vsp::laser_detector::drawRuns(m_runs, m_work.get(), m_height, m_width, m_mask.image);
    m_maskDirty = false;
  }
  return m_mask.image;
}

namespace
{
// Points of a guided pass that tell the track is kept (fewer: the first pass searches).
const int kMinGuidedPoints = 30;
// Points of a tracking pass per sample of the predicted conic that tell the track is kept (see trackConic()).
const double kMinTrackedShare = 0.4;
// Share of the samples along the ellipse located by the rows where the guided pass ends with a point, below
// which the whole search runs instead (see locateFromRows()): the rows are a shortcut for a ring found along
// most of its length. On the shipped hard sequence the frames located right cover 0.86-1; an ellipse through
// a red cable and an arc of a faint ring (frame 27) covers 0.60, one extrapolated from the bright side of a
// ring fading on a colourful floor (frame 41) 0.48.
const double kMinLocatedCoverage = 0.8;
// Share of those samples from which a location is trusted whatever else the image holds. Below it, the rows'
// ellipse must also hold half the sample's crossings (locateFromRows()), and the whole search is followed by
// the retry with short chains (locateFromShortChains()), whose ellipse must reach it. On the hard sequence
// rendered with seeds 1-12 (`make-laser-sequence --hard`, JPEG 60 and 80) the ring's own ellipses covered
// 0.98-1 wherever clutter outnumbered it; ellipses along a red cable, through a colourful floor's edges and
// an arc of the ring, or through the tiles of a frame without the laser covered 0.78-0.92, and they were
// located: a plane 0.48 m off with status ok, 623 points of a ring where no laser shone.
const double kTrustedCoverage = 0.95;
// See kTrustedCoverage: a ring of the sample of rows whose ellipse holds fewer of its crossings is among clutter.
const double kMinRowsShare = 0.5;
// The retry's ellipse replaces one the whole search located when its guided pass covers this much more of it.
const double kMinCoverageGain = 0.1;
// RANSAC samples of the ellipse through the sample of rows' crossings, which every whole-image detection
// fits: few (a trace that is most of the points needs few: 40 find a 60 % majority with 96 % probability).
const int kRowsEllipseTrials = 40;
// Those of the ellipse through the whole search's points, which runs when the rows located no ring, on
// frames with clutter: a ring of half the points there (data/laser_hard frame 27, a red cable along it)
// was missed by 40 samples for an ellipse through arcs of both (755 of 1672 points on it, the pass along it
// finding 60 % of its length), found by 200 (977 points, 99.6 %).
const int kFullEllipseTrials = 200;
// Stripe width assumed before any detection has measured one (the rendered and photographed stripes).
const int kDefaultStripeWidth = 3;
// The retry when the whole search's location is not trusted (see locateFromShortChains()): chains this many
// times shorter than the minimum segment length. Through JPEG 60 a ring on a colourful floor is broken at nearly
// every patch into pieces of 16-45 px (the chroma at half resolution and coarsely quantised takes its red
// dominance under the threshold there), as a dim ring's near side is where its contrast hovers about the
// threshold; no chain reached 50 px on 19 of the 33 frames of `make-laser-sequence --hard --seed 1-12` (JPEG
// 60) where the default detector found under 95 % of the ring.
const double kShortChainDivisor = 3.0;
// RANSAC samples of the ellipse through the short chains: the ring is 20-55 % of their points on those
// colourful floors (clutter of the patches' red edges the rest); 200 samples picked an ellipse through clutter
// and an arc of the ring on 3 of 8 such frames, 2000 found the ring on each (the retry runs only on frames
// whose location is not trusted, see kTrustedCoverage). Half of its samples are drawn chain by chain
// (ChainPp5Estimator): where the ring was 22 % of the points, in 11 of 68 chains (held-out seed 35 at JPEG 60,
// frame 41), five points drawn one by one all lay on it once in 2000 samples, and the ellipse went through
// two of its arcs and the clutter (5.1 % of the ring found, no plane; 98.6 % now).
const int kShortChainEllipseTrials = 2000;
// The retry's ellipse is also taken when it holds this share of the short chains' points and the guided pass
// finds kMinShortChainCoverage of its samples, kMinCoverageGain more than the first search's did of its own: a
// faint ring alone in a dark scene, whose far side the compressed image no longer holds (the pass covers
// 0.61-0.72 of such an ellipse). The first search may have fitted an ellipse to the one arc whose chains were
// long enough: on the hard sequence of seed 22 at JPEG 60, frame 56, 40 degrees of the ring's near side
// (covered at 0.46, no plane: 19.8 % of the ring at 3 sigma) against the retry's 0.72 (96.9 %); only where the
// first search made no ellipse at all was the retry's taken before. Anywhere else its pass must cover
// kTrustedCoverage of it, and kMinCoverageGain more than the first search's did of its own: on the frames with
// red distractors, ellipses along a red cable and an arc of the ring covered 0.53-0.65, on a colourful floor
// without the laser 0.78.
const double kMinShortChainShare = 0.9;
// See kMinShortChainShare.
const double kMinShortChainCoverage = 0.5;
// A lone ellipse of the retry (kMinShortChainShare) whose pass covers no more than the whole search's did of its
// own is still taken when it holds this many times as many of the short chains' points as the whole search's
// ellipse: one fitted to a short arc, the only stretch whose chains were long enough, runs along that arc on both
// of its sides, and the pass along it covers it nearly all (hard sequence seed 38 at JPEG 60, frame 56: 0.94 of
// an ellipse through 25 degrees of a faint ring's near side, 13 % of the ring; the retry's ellipse held the 262
// short chains' points, covered at 0.71).
const double kMinSupportRatio = 2.0;

//! How many of \e points lie on the ellipse the whole search located (0 when it located none).
size_t pointsOnSearchEllipse(const std::vector<vpImagePoint> &points, const vsp::laser_detector::RidgeWorkspace &work)
{
  if (work.searchEllipse.size() != 9)
    return 0;
  return vsp::laser_detector::pointsOnTraceEllipse(Eigen::Map<const Eigen::Matrix3d>(work.searchEllipse.data()),
                                                   points);
}

/*!
  The coverage of its guided pass from which the retry with short chains takes its ellipse (see
  kMinShortChainShare): \e inliers of its \e samplePoints on the ellipse, \e onSearchEllipse of them on the whole
  search's, whose pass covered \e firstCoverage of it. A lone ellipse (kMinShortChainShare of the points) needs
  kMinShortChainCoverage, and kMinCoverageGain more than the first search's unless it holds kMinSupportRatio
  times its support; any other kTrustedCoverage and kMinCoverageGain more than the first search's.
*/
double retryCoverageTaken(double firstCoverage, size_t inliers, size_t samplePoints, size_t onSearchEllipse)
{
  const double gained = firstCoverage + kMinCoverageGain;
  if (static_cast<double>(inliers) < kMinShortChainShare * static_cast<double>(samplePoints))
    return std::max(kTrustedCoverage, gained);
  if (static_cast<double>(inliers) >= kMinSupportRatio * static_cast<double>(onSearchEllipse))
    return kMinShortChainCoverage;
  return std::max(kMinShortChainCoverage, gained);
}

//! The points of \e points at the indices \e indices, in their order.
std::vector<vpImagePoint> pointsAt(const std::vector<vpImagePoint> &points, const std::vector<int> &indices)
{
  std::vector<vpImagePoint> picked;
  picked.reserve(indices.size());
  for (int k : indices)
    picked.push_back(points[static_cast<size_t>(k)]);
  return picked;
}

Eigen::Matrix3d toEigen(const vpMatrix &C)
{
  Eigen::Matrix3d c;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      c(i, j) = C[i][j];
  return c;
}
} // namespace

vsp::laser_detector::GuidedSettings vpLaserConicDetector::guidedSettings(double margin, unsigned int step) const
{
  return {margin,
          static_cast<int>(step),
          m_guidedFactor,
          static_cast<int>(m_maxStripeWidth),
          static_cast<int>(m_saturationLevel),
          m_stripeWidth > 0 ? m_stripeWidth : kDefaultStripeWidth};
}

vsp::laser_detector::RidgeSettings vpLaserConicDetector::ridgeSettings() const
{
  return {m_minContrast,
          m_noiseFactor,
          static_cast<int>(m_maxStripeWidth),
          static_cast<int>(m_saturationLevel),
          m_minSegmentLength,
          static_cast<int>(m_step),
          getInstructionSetUsed()};
}

std::vector<vpImagePoint> vpLaserConicDetector::detectInTwoPasses(const vpImage<vpRGBa> &I, bool inRegion,
                                                                  double &coverage)
{
  coverage = 0.0;
  vsp::laser_detector::RidgeReport report;
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  if (inRegion)
    rasteriseRegion(H, W);
  std::vector<vpImagePoint> points =
      inRegion ? vsp::laser_detector::detectRidge(I, ridgeSettings(), &work.scoreRegion, &work.searchRegion, work,
                                                  m_runs, report)
               : vsp::laser_detector::detectRidge(I, ridgeSettings(), nullptr, nullptr, work, m_runs, report);
  m_threshold = report.threshold;
  m_noise = report.noise;
  m_stripeWidth = vsp::laser_detector::observedStripeWidth(work, m_stripeWidth);
  Eigen::Matrix3d C;
  std::vector<int> inliers;
  work.searchEllipse.clear();
  if (!m_guided ||
      !vsp::laser_detector::fitTraceEllipse(points, W, H, kMinGuidedPoints, kFullEllipseTrials, C, inliers))
    return points;
  work.searchEllipse.assign(C.data(), C.data() + 9);
  std::vector<vpImagePoint> anchors = pointsAt(points, inliers);
  const vsp::laser_detector::GuidedSettings guided = guidedSettings(m_guidedMargin, m_guidedStep);
  vsp::laser_detector::GuidedReport guidedReport;
  const size_t before = points.size();
  vsp::laser_detector::guidedPass(I, guided, C, anchors, inRegion ? &work.searchRegion : nullptr, points, work,
                                  guidedReport);
  m_guidedCount = static_cast<unsigned int>(points.size() - before);
  coverage = guidedReport.coverage;
  // Over the whole image, a ring found along most of its ellipse: the first pass's points off it (a red
  // cable, a floor's red edges, clutter) are not returned, as when the sample of rows located it.
  if (!inRegion && coverage >= kMinLocatedCoverage) {
    vsp::laser_detector::keepInlierCrossings(before, inliers, work);
    anchors.insert(anchors.end(), points.begin() + static_cast<std::ptrdiff_t>(before), points.end());
    points.swap(anchors);
  }
  return points;
}

bool vpLaserConicDetector::locateFromShortChains(const vpImage<vpRGBa> &I, double firstCoverage,
                                                 std::vector<vpImagePoint> &points)
{
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  vsp::laser_detector::RidgeSettings settings = ridgeSettings();
  settings.minSegment /= kShortChainDivisor;
  vsp::laser_detector::RidgeReport report;
  const std::vector<vpImagePoint> sample =
      vsp::laser_detector::detectRidge(I, settings, nullptr, nullptr, work, m_runs, report);
  // The ring's ellipse is sought among the points off long straight runs (a red cable, tape on the floor),
  // which outnumber the arcs of a broken ring; the points on them are not returned.
  const std::vector<int> candidates = vsp::laser_detector::offStraightRuns(sample);
  const std::vector<int> chains = vsp::laser_detector::keptChains(work);
  std::vector<int> candidateChains;
  if (chains.size() == sample.size())
    for (int k : candidates)
      candidateChains.push_back(chains[static_cast<size_t>(k)]);
  Eigen::Matrix3d C;
  std::vector<int> inliers;
  if (!vsp::laser_detector::fitTraceEllipse(pointsAt(sample, candidates), W, H, kMinGuidedPoints,
                                            kShortChainEllipseTrials, C, inliers, &candidateChains))
    return false;
  for (int &k : inliers)
    k = candidates[static_cast<size_t>(k)];
  const std::vector<vpImagePoint> anchors = pointsAt(sample, inliers);
  vsp::laser_detector::GuidedSettings guided = guidedSettings(m_guidedMargin, m_guidedStep);
  guided.stripeWidth = vsp::laser_detector::observedStripeWidth(work, m_stripeWidth);
  guided.usefulCoverage =
      retryCoverageTaken(firstCoverage, inliers.size(), sample.size(), pointsOnSearchEllipse(sample, work));
  vsp::laser_detector::GuidedReport guidedReport;
  work.guided.clear();
  points = anchors;
  vsp::laser_detector::guidedPass(I, guided, C, anchors, nullptr, points, work, guidedReport);
  if (guidedReport.coverage < guided.usefulCoverage)
    return false;
  vsp::laser_detector::keepInlierCrossings(sample.size(), inliers, work);
  m_stripeWidth = guided.stripeWidth;
  m_guidedCount = static_cast<unsigned int>(points.size() - anchors.size());
  return true;
}

bool vpLaserConicDetector::retryWithShortChains(const vpImage<vpRGBa> &I, double firstCoverage,
                                                std::vector<vpImagePoint> &points)
{
  // The first search's state (the mask's runs, the crossings a tracking region or a copy starts from) is put
  // back when the retry locates nothing either.
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  const std::vector<vsp::laser_detector::Crossing> crossings(work.crossings), guided(work.guided);
  const std::vector<unsigned char> keep(work.keep);
  const std::vector<vpLaserConicDetectorRun> runs(m_runs);
  const unsigned int guidedCount = m_guidedCount;
  if (locateFromShortChains(I, firstCoverage, points))
    return true;
  work.crossings = crossings;
  work.guided = guided;
  work.keep = keep;
  m_runs = runs;
  m_guidedCount = guidedCount;
  return false;
}

bool vpLaserConicDetector::locateFromRows(const vpImage<vpRGBa> &I, std::vector<vpImagePoint> &points)
{
  vsp::laser_detector::RidgeReport report;
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  const std::vector<vpImagePoint> sample =
      vsp::laser_detector::detectRidgeRows(I, ridgeSettings(), work, m_runs, report);
  Eigen::Matrix3d C;
  std::vector<int> inliers;
  if (!vsp::laser_detector::fitTraceEllipse(sample, W, H, kMinGuidedPoints, kRowsEllipseTrials, C, inliers))
    return false;
  const int stripeWidth = vsp::laser_detector::observedStripeWidth(work, C, inliers, m_stripeWidth);
  // The sample's crossings off the ellipse (clutter, a red cable) are not returned: the whole search would
  // have measured them against its own, stricter, chain length. Nor those where a column crosses the curve
  // more steeply: the guided pass measures there.
  const std::vector<vpImagePoint> anchors = vsp::laser_detector::keepSteepRowCrossings(sample, inliers, C, work);
  points = anchors;
  vsp::laser_detector::GuidedSettings guided = guidedSettings(m_guidedMargin, m_guidedStep);
  guided.stripeWidth = stripeWidth;
  // An ellipse through a few arcs of a faint ring, or through clutter and a piece of the ring, is extrapolated
  // far from the rest of it: the pass then finds little along it, and the whole search decides. So it does
  // when the ellipse is a minority of the sample and not found nearly all round (a red cable, the edges of a
  // colourful floor: the pass finds stripe-like profiles along most curves there).
  guided.usefulCoverage = static_cast<double>(inliers.size()) >= kMinRowsShare * sample.size() ? kMinLocatedCoverage
                                                                                               : kTrustedCoverage;
  vsp::laser_detector::GuidedReport guidedReport;
  vsp::laser_detector::guidedPass(I, guided, C, anchors, nullptr, points, work, guidedReport);
  if (guidedReport.coverage < guided.usefulCoverage)
    return false;
  m_threshold = report.threshold;
  m_noise = report.noise;
  m_stripeWidth = stripeWidth;
  m_guidedCount = static_cast<unsigned int>(points.size() - anchors.size());
  return true;
}

bool vpLaserConicDetector::trackConic(const vpImage<vpRGBa> &I, std::vector<vpImagePoint> &points)
{
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  work.crossings.clear();
  work.keep.clear();
  const vsp::laser_detector::GuidedSettings guided = guidedSettings(m_regionMargin, m_trackingStep);
  vsp::laser_detector::GuidedReport report;
  points.clear();
  vsp::laser_detector::guidedPass(I, guided, toEigen(m_regionConic), std::vector<vpImagePoint>(), nullptr, points, work,
                                  report);
  m_guidedCount = static_cast<unsigned int>(points.size());
  m_noise = report.noise;
  m_threshold = report.threshold;
  // The track is kept when the points cover a good part of the prediction's length (a tracked ring: 0.77-1 of
  // its samples from frame to frame of the shipped hard sequence). Where the laser is
  // off, thin wedges of patch colour between the dark joints of a mosaic have a stripe's profile, and pieces
  // of a few of them continue a curve: up to 0.16 of the samples, all round the prediction, from which GP-3
  // made a plane 1.4 m off. Else the first pass searches the band, as when the track is lost.
  if (static_cast<int>(points.size()) < kMinGuidedPoints ||
      points.size() < kMinTrackedShare * static_cast<double>(report.predictionSamples))
    return false;
  // The next frame's matched filter takes the width measured here: climbing, the stripe narrows in the image
  // (a 7 px stripe's box kept on a 3 px one: RMS 0.084 px against 0.051, TrackingFollowsTheStripesWidth).
  m_stripeWidth = vsp::laser_detector::guidedStripeWidth(work, m_stripeWidth);
  return true;
}

std::vector<vpImagePoint> vpLaserConicDetector::detect(const vpImage<vpRGBa> &I)
{
  m_threshold = 0.0;
  m_noise = 0.0;
  m_runs.clear();
  m_height = I.getHeight();
  m_width = I.getWidth();
  m_maskDirty = m_method == DETECTION_RIDGE;
  // No point of the guided pass yet (none at all by the HSV method).
  m_guidedCount = 0;
  m_work.get().guided.clear();
  if (m_method == DETECTION_HSV) {
    const vsp::laser_detector::HsvSettings settings = {m_maxHueLow,
                                                       m_minHueHigh,
                                                       m_minSaturation,
                                                       m_minValue,
                                                       static_cast<int>(m_maxStripeWidth),
                                                       static_cast<int>(m_step)};
    return vsp::laser_detector::detectHsv(I, settings, m_mask.image);
  }
  if (I.getSize() == 0) {
    double coverage = 0.0;
    return detectInTwoPasses(I, false, coverage);
  }
  std::vector<vpImagePoint> points;
  if (m_regionIsConic && trackConic(I, points))
    return points;
  m_work.get().guided.clear();
  m_guidedCount = 0;
  if (!hasSearchRegion() && m_guided && locateFromRows(I, points))
    return points;
  m_work.get().guided.clear();
  double coverage = 0.0;
  points = detectInTwoPasses(I, hasSearchRegion(), coverage);
  // A ring whose pieces are all shorter than the minimum segment (through strong JPEG, on a colourful floor or
  // where a dim stripe hovers about the threshold) is located from shorter chains, as is one whose location
  // is not trusted (an ellipse extrapolated from a few arcs, clutter along the rest).
  std::vector<vpImagePoint> retried;
  if (!hasSearchRegion() && m_guided && coverage < kTrustedCoverage && retryWithShortChains(I, coverage, retried))
    return retried;
  return points;
}
