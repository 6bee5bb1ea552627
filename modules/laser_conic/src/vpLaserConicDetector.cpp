/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicDetector.h>

#include <algorithm>
#include <cmath>

#include "laser_detector.h"

namespace
{
void check(bool ok, const char *message)
{
  if (!ok)
    throw vpLaserConicException(vpLaserConicException::badValueError, std::string("vpLaserConicDetector: ") + message);
}

// Real roots of a t^2 + b t + c = 0 (a may be zero) appended to roots.
void solveQuadratic(double a, double b, double c, std::vector<double> &roots)
{
  const double scale = std::max(std::fabs(a), std::max(std::fabs(b), std::fabs(c)));
  if (scale == 0.0)
    return;
  if (std::fabs(a) <= 1e-14 * scale) {
    if (std::fabs(b) > 1e-14 * scale)
      roots.push_back(-c / b);
    return;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0)
    return;
  // Numerically stable form: no cancellation between b and the square root.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  roots.push_back(q / a);
  if (q != 0.0)
    roots.push_back(c / q);
}
} // namespace

vpLaserConicDetector::vpLaserConicDetector()
  : m_method(DETECTION_RIDGE), m_minContrast(10.0), m_noiseFactor(5.0), m_minSegmentLength(50.0),
    m_maxStripeWidth(12), m_saturationLevel(250), m_step(1), m_instructions(INSTRUCTIONS_BEST), m_maxHueLow(10), m_minHueHigh(170), m_minSaturation(80),
    m_minValue(80), m_region(), m_regionMargin(0.0), m_regionGeneration(0), m_mask(), m_maskDirty(false), m_height(0), m_width(0),
    m_threshold(0.0), m_noise(0.0), m_work(), m_runs()
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
  }
  return *this;
}

vpLaserConicDetector::vpWorkspace::~vpWorkspace() = default;

void vpLaserConicDetector::setMinContrast(double greyLevels)
{
  check(std::isfinite(greyLevels) && greyLevels >= 1.0 && greyLevels <= 255.0, "the minimum contrast must be in [1, 255]");
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

void vpLaserConicDetector::setSamplingStep(unsigned int step)
{
  check(step > 0, "the sampling step must be positive");
  m_step = step;
}

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
  check(std::isfinite(margin) && margin > 0.0, "the search margin must be positive and finite");
  check(!trace.empty(), "the search region needs at least one point");
  for (const vpImagePoint &p : trace)
    check(std::isfinite(p.get_u()) && std::isfinite(p.get_v()), "a point of the search region is not finite");
  m_region = trace;
  m_regionMargin = margin;
  ++m_regionGeneration;
}

void vpLaserConicDetector::setSearchRegion(const vpMatrix &C, double margin)
{
  check(C.getRows() == 3 && C.getCols() == 3, "the conic must be a 3x3 matrix");
  check(std::isfinite(margin) && margin > 0.0, "the search margin must be positive and finite");
  double norm = 0.0;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j) {
      check(std::isfinite(C[i][j]), "the conic has a non-finite coefficient");
      norm = std::max(norm, std::fabs(C[i][j]));
    }
  check(norm > 0.0, "the conic is zero");
  // Symmetric part: a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f = 0.
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1], d = 0.5 * (C[0][2] + C[2][0]),
               e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  // Sampled at every row and every column of a large image (16384 px): points outside the image are ignored
  // when the region is rasterised.
  std::vector<vpImagePoint> points;
  std::vector<double> roots;
  const int extent = 16384;
  for (int t = -static_cast<int>(margin) - 1; t < extent; ++t) {
    roots.clear();
    solveQuadratic(a, 2.0 * (b * t + d), c * t * t + 2.0 * e * t + f, roots); // row v = t: roots in u
    for (double u : roots)
      if (u > -margin - 1.0 && u < extent)
        points.push_back(vpImagePoint(t, u));
    roots.clear();
    solveQuadratic(c, 2.0 * (b * t + e), a * t * t + 2.0 * d * t + f, roots); // column u = t: roots in v
    for (double v : roots)
      if (v > -margin - 1.0 && v < extent)
        points.push_back(vpImagePoint(v, t));
  }
  check(!points.empty(), "the conic has no real point near the image");
  m_region = points;
  m_regionMargin = margin;
  ++m_regionGeneration;
}

namespace
{
// Marks the blocks of 16 columns by bands of 8 rows (the width the scans and the block flags process at once,
// the height of the bands of spans) that meet the points' squares of half side m: \e marked, nbY x nbX.
void markBlocks(const std::vector<vpImagePoint> &region, double margin, double m, int H, int W, int nbX,
                std::vector<unsigned char> &marked)
{
  const int blockW = 16, blockH = vsp::laser_detector::RegionSpans::bandHeight, nbY = (H + blockH - 1) / blockH;
  marked.assign(static_cast<size_t>(nbX) * nbY, 0);
  // One point per cell of a quarter of the margin marks its square: more points in the cell add little
  // (every point is within a cell diagonal, 0.36 margin, of the point marked for its cell, so the band
  // reaches at least m - 0.36 margin around every point).
  const double cellSize = std::max(1.0, 0.25 * margin);
  const int cellColumns = static_cast<int>((W + 2 * m) / cellSize) + 2, cellRows = static_cast<int>((H + 2 * m) / cellSize) + 2;
  std::vector<unsigned char> used(static_cast<size_t>(cellColumns) * cellRows, 0);
  for (const vpImagePoint &p : region) {
    const double u = p.get_u(), v = p.get_v();
    if (u < -m || v < -m || u > W - 1 + m || v > H - 1 + m)
      continue; // the square does not meet the image
    unsigned char &cell = used[static_cast<size_t>((v + m) / cellSize) * cellColumns + static_cast<size_t>((u + m) / cellSize)];
    if (cell)
      continue;
    cell = 1;
    const int i0 = std::max(0, static_cast<int>(std::floor(v - m))), i1 = std::min(H - 1, static_cast<int>(std::ceil(v + m)));
    const int j0 = std::max(0, static_cast<int>(std::floor(u - m))), j1 = std::min(W - 1, static_cast<int>(std::ceil(u + m)));
    for (int bi = i0 / blockH; bi <= i1 / blockH; ++bi)
      std::fill(&marked[static_cast<size_t>(bi) * nbX + j0 / blockW], &marked[static_cast<size_t>(bi) * nbX + j1 / blockW] + 1, 1);
  }
}

// The marked blocks dilated by rx blocks along the rows and ry bands along the columns.
std::vector<unsigned char> dilateBlocks(const std::vector<unsigned char> &marked, int nbX, int rx, int ry)
{
  const int nbY = static_cast<int>(marked.size()) / nbX;
  std::vector<unsigned char> wide(marked.size(), 0), out(marked.size(), 0);
  for (int bi = 0; bi < nbY; ++bi)
    for (int b = 0; b < nbX; ++b)
      if (marked[static_cast<size_t>(bi) * nbX + b])
        std::fill(&wide[static_cast<size_t>(bi) * nbX + std::max(0, b - rx)],
                  &wide[static_cast<size_t>(bi) * nbX + std::min(nbX - 1, b + rx)] + 1, 1);
  for (int bi = 0; bi < nbY; ++bi)
    for (int di = -ry; di <= ry; ++di)
      if (bi + di >= 0 && bi + di < nbY)
        for (int b = 0; b < nbX; ++b)
          out[static_cast<size_t>(bi) * nbX + b] |= wide[static_cast<size_t>(bi + di) * nbX + b];
  return out;
}

// The column spans of each band of the marked blocks.
void blocksToSpans(const std::vector<unsigned char> &marked, int nbX, int W, vsp::laser_detector::RegionSpans &out)
{
  const int blockW = 16, nbY = static_cast<int>(marked.size()) / nbX;
  out.spans.clear();
  out.bandStart.assign(1, 0);
  for (int bi = 0; bi < nbY; ++bi) {
    const unsigned char *row = &marked[static_cast<size_t>(bi) * nbX];
    for (int b = 0; b < nbX; ++b) {
      if (!row[b])
        continue;
      const int start = b;
      while (b + 1 < nbX && row[b + 1])
        ++b;
      out.spans.push_back(vsp::laser_detector::Span(start * blockW, std::min(W - 1, (b + 1) * blockW - 1)));
    }
    out.bandStart.push_back(static_cast<int>(out.spans.size()));
  }
}
} // namespace

void vpLaserConicDetector::rasteriseRegion(int H, int W)
{
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  if (work.regionValid && work.regionGeneration == m_regionGeneration && work.regionHeight == static_cast<unsigned int>(H) &&
      work.regionWidth == static_cast<unsigned int>(W))
    return;
  // The ridge tests of a searched pixel read the score up to the stripe width + 1 pixels away along its row
  // and its column. The searched blocks are thus dilated by that reach rounded up to whole blocks and bands:
  // every score read is of this frame (the score buffer is kept from frame to frame), whatever part of its
  // block a searched pixel lies in.
  const int nbX = (W + 15) / 16, reach = static_cast<int>(m_maxStripeWidth) + 1;
  std::vector<unsigned char> searched;
  markBlocks(m_region, m_regionMargin, m_regionMargin, H, W, nbX, searched);
  blocksToSpans(searched, nbX, W, work.searchRegion);
  blocksToSpans(dilateBlocks(searched, nbX, (reach + 15) / 16,
                             (reach + vsp::laser_detector::RegionSpans::bandHeight - 1) / vsp::laser_detector::RegionSpans::bandHeight),
                nbX, W, work.scoreRegion);
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

std::vector<vpImagePoint> vpLaserConicDetector::detect(const vpImage<vpRGBa> &I)
{
  m_threshold = 0.0;
  m_noise = 0.0;
  m_runs.clear();
  m_height = I.getHeight();
  m_width = I.getWidth();
  m_maskDirty = m_method == DETECTION_RIDGE;
  if (m_method == DETECTION_HSV) {
    const vsp::laser_detector::HsvSettings settings = {m_maxHueLow, m_minHueHigh, m_minSaturation, m_minValue,
                                                    static_cast<int>(m_maxStripeWidth), static_cast<int>(m_step)};
    return vsp::laser_detector::detectHsv(I, settings, m_mask.image);
  }
  const vsp::laser_detector::RidgeSettings settings = {m_minContrast, m_noiseFactor, static_cast<int>(m_maxStripeWidth),
                                                    static_cast<int>(m_saturationLevel), m_minSegmentLength,
                                                    static_cast<int>(m_step), getInstructionSetUsed()};
  vsp::laser_detector::RidgeReport report;
  std::vector<vpImagePoint> points;
  vsp::laser_detector::RidgeWorkspace &work = m_work.get();
  if (m_region.empty() || I.getSize() == 0)
    points = vsp::laser_detector::detectRidge(I, settings, nullptr, nullptr, work, m_runs, report);
  else {
    rasteriseRegion(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()));
    points = vsp::laser_detector::detectRidge(I, settings, &work.scoreRegion, &work.searchRegion, work, m_runs, report);
  }
  m_threshold = report.threshold;
  m_noise = report.noise;
  return points;
}
