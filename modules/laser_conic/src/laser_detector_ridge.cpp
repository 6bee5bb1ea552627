/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The ridge detector of vpLaserConicDetector (DETECTION_RIDGE): red-dominance score in one pass over the
// RGBA buffer, top-hat candidates along rows and columns against a threshold estimated from the image,
// profile checks and sub-pixel centre around each candidate only, then a continuity filter.
#include "laser_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>

namespace vpLaserDetector
{
namespace
{
// True when the 8 bytes at p are all zero: lets the scans jump over empty stretches.
inline bool zero8(const unsigned char *p)
{
  uint64_t word;
  std::memcpy(&word, p, sizeof(word));
  return word == 0;
}

// Width (grey levels of the red channel) of the ramp below the saturation level over which the score goes
// from the red dominance to 255.
const int kSaturationRamp = 30;

// Score of n pixels: the red dominance R - w max(G, B), clipped to [0, 255], where w = 1 below the ramp
// (R <= saturation - 30), falls linearly to 0 at the saturation level and stays 0 above. A stripe whose red
// channel saturates (and a white saturated core) is thus a plateau of 255 joined continuously to its red
// flanks: no jump at the saturation level for the sensor noise to flicker on. Integer arithmetic without
// branch over the bytes of the RGBA buffer, so that the compiler vectorises it.
void scoreSpan(const unsigned char *rgba, unsigned char *score, int n, int saturation)
{
  for (int j = 0; j < n; ++j) {
    const int r = rgba[4 * j], g = rgba[4 * j + 1], b = rgba[4 * j + 2];
    const int m = g > b ? g : b;
    int t = saturation - r; // ramp weight x 30
    t = t < 0 ? 0 : (t > kSaturationRamp ? kSaturationRamp : t);
    const int s = r - (m * t * 2185 >> 16); // 2185 / 65536 = 1 / 30 (to 1e-4)
    score[j] = static_cast<unsigned char>(s < 0 ? 0 : s);
  }
}

// Robust noise of the unclipped score r - max(g, b): 1.4826 MAD / sqrt(2) of its differences two pixels
// apart (two apart: the optical blur correlates neighbours), over every 4th row of the scored region.
double estimateNoise(const vpImage<vpRGBa> &I, const RowIntervals *region)
{
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  std::vector<uint32_t> histogram(511, 0);
  uint64_t count = 0;
  auto sampleSpan = [&](const unsigned char *row, int j0, int j1) {
    for (int j = j0; j + 2 <= j1; j += 2) {
      const unsigned char *p = row + 4 * j, *q = p + 8;
      const int a = p[0] - std::max(p[1], p[2]), b = q[0] - std::max(q[1], q[2]);
      ++histogram[std::abs(a - b)];
      ++count;
    }
  };
  for (int i = 0; i < H; i += 4) {
    const unsigned char *row = reinterpret_cast<const unsigned char *>(I[static_cast<unsigned int>(i)]);
    if (region == nullptr)
      sampleSpan(row, 0, W - 1);
    else
      for (const std::pair<int, int> &span : (*region)[i])
        sampleSpan(row, span.first, span.second);
  }
  if (count == 0)
    return 0.0;
  // Median of the absolute differences, interpolated inside its bin.
  const double half = 0.5 * count;
  uint64_t below = 0;
  for (size_t k = 0; k < histogram.size(); ++k) {
    if (below + histogram[k] >= half) {
      const double mad = k > 0 ? k - 0.5 + (half - below) / histogram[k] : (half - below) / histogram[k] * 0.5;
      return 1.4826 * mad / std::sqrt(2.0);
    }
    below += histogram[k];
  }
  return 0.0;
}

// A candidate peak: its scan line and its position along it.
struct Candidate
{
  int line, pos;
  bool operator<(const Candidate &o) const { return line < o.line || (line == o.line && pos < o.pos); }
};

// Candidate peaks along the rows within [j0, j1] of row i: local maximum (first pixel of a plateau) that
// exceeds the score d pixels away on both sides (one side at the image border) by threshold.
void rowCandidates(const unsigned char *c, int W, int i, int j0, int j1, int d, int threshold,
                   std::vector<unsigned char> &flags, std::vector<Candidate> &out)
{
  j0 = std::max(j0, 1);
  j1 = std::min(j1, W - 2);
  if (j1 < j0)
    return;
  const unsigned char *row = c + static_cast<size_t>(i) * W;
  unsigned char *f = flags.data();
  const int inner0 = std::max(j0, d), inner1 = std::min(j1, W - 1 - d);
  for (int j = inner0; j <= inner1; ++j) { // vectorised: no branch
    const int v = row[j], bg = std::max<int>(row[j - d], row[j + d]);
    f[j] = static_cast<unsigned char>((v >= bg + threshold) & (v > row[j - 1]) & (v >= row[j + 1]));
  }
  for (int j = j0; j <= j1; ++j) { // near the border, one background side
    if (j >= inner0 && j <= inner1) {
      j = inner1;
      continue;
    }
    const int v = row[j];
    const int bg = std::max<int>(j - d >= 0 ? row[j - d] : 0, j + d < W ? row[j + d] : 0);
    f[j] = static_cast<unsigned char>((v >= bg + threshold) & (v > row[j - 1]) & (v >= row[j + 1]));
  }
  for (int j = j0; j <= j1; ++j) {
    if (j + 8 <= j1 + 1 && zero8(f + j)) {
      j += 7;
      continue;
    }
    if (f[j])
      out.push_back(Candidate{i, j});
  }
}

// Candidate peaks along the columns (every step-th column) at row i within [j0, j1].
void columnCandidates(const unsigned char *c, int W, int H, int i, int j0, int j1, int d, int threshold, int step,
                      std::vector<unsigned char> &flags, std::vector<Candidate> &out)
{
  if (i < 1 || i > H - 2)
    return;
  const unsigned char *row = c + static_cast<size_t>(i) * W;
  const unsigned char *up = row - W, *down = row + W;
  static const unsigned char zeros[1] = {0};
  const unsigned char *far0 = i - d >= 0 ? row - static_cast<size_t>(d) * W : nullptr;
  const unsigned char *far1 = i + d < H ? row + static_cast<size_t>(d) * W : nullptr;
  unsigned char *f = flags.data();
  if (far0 != nullptr && far1 != nullptr) {
    for (int j = j0; j <= j1; ++j) { // vectorised: no branch
      const int v = row[j], bg = std::max<int>(far0[j], far1[j]);
      f[j] = static_cast<unsigned char>((v >= bg + threshold) & (v > up[j]) & (v >= down[j]));
    }
  } else {
    for (int j = j0; j <= j1; ++j) {
      const int v = row[j], bg = std::max<int>(far0 ? far0[j] : zeros[0], far1 ? far1[j] : zeros[0]);
      f[j] = static_cast<unsigned char>((v >= bg + threshold) & (v > up[j]) & (v >= down[j]));
    }
  }
  for (int j = j0; j <= j1; ++j) {
    if (j + 8 <= j1 + 1 && zero8(f + j)) {
      j += 7;
      continue;
    }
    if (f[j] && j % step == 0)
      out.push_back(Candidate{j, i});
  }
}

// A measured stripe crossing.
struct Crossing
{
  vpImagePoint point;
  bool alongRow;
  int line, first, last; // the half-maximum run [first, last] along the scan line
};

// Access to the score and the pixels along one scan line.
struct ScanLine
{
  const unsigned char *score;
  const unsigned char *rgba;
  int W, H;
  bool alongRow;
  int line;
  int length() const { return alongRow ? W : H; }
  size_t index(int pos) const { return alongRow ? static_cast<size_t>(line) * W + pos : static_cast<size_t>(pos) * W + line; }
  int at(int pos) const { return score[index(pos)]; }
  // Unclipped red dominance of the pixel (negative for grey or other colours).
  int dominance(int pos) const
  {
    const unsigned char *p = rgba + 4 * index(pos);
    return p[0] - std::max(p[1], p[2]);
  }
  int red(int pos) const { return rgba[4 * index(pos)]; }
};

// Run of scores above `level` through (i, j) along the direction (di, dj), up to limit pixels per side:
// its length and its largest score.
struct Run
{
  int length, maxScore;
};
Run runThrough(const unsigned char *score, int W, int H, int i, int j, int di, int dj, double level, int limit)
{
  Run run = {1, score[static_cast<size_t>(i) * W + j]};
  for (int sign = -1; sign <= 1; sign += 2)
    for (int k = 1; k <= limit; ++k) {
      const int ii = i + sign * k * di, jj = j + sign * k * dj;
      if (ii < 0 || jj < 0 || ii >= H || jj >= W)
        break;
      const int v = score[static_cast<size_t>(ii) * W + jj];
      if (!(v > level))
        break;
      ++run.length;
      run.maxScore = std::max(run.maxScore, v);
    }
  return run;
}

enum Verdict
{
  ACCEPTED,
  REJECTED, // shape, width or white light: mark the run
  IGNORED   // not measured by this direction (the other direction crosses more steeply)
};

// Checks the profile around the candidate peak p and measures its sub-pixel centre.
Verdict analyse(const ScanLine &s, int p, const RidgeSettings &settings, int threshold, Crossing &out)
{
  const int n = s.length(), d = settings.maxWidth;
  const int peak = s.at(p);
  const int bg = std::max(p - d >= 0 ? s.at(p - d) : 0, p + d < n ? s.at(p + d) : 0);
  const int contrast = peak - bg;
  if (contrast < threshold)
    return IGNORED;
  // Half-maximum run.
  const double half = bg + 0.5 * contrast;
  int a = p, b = p;
  while (a - 1 >= 0 && s.at(a - 1) > half && p - a <= d)
    --a;
  while (b + 1 < n && s.at(b + 1) > half && b - p <= d)
    ++b;
  out.alongRow = s.alongRow;
  out.line = s.line;
  out.first = a;
  out.last = b;
  if (b - a + 1 > settings.maxWidth)
    return REJECTED; // a wide red object, not a stripe
  // White pixels (red channel in the saturation ramp or above, low dominance) must be flanked by red on both
  // sides: a saturated core, not white light.
  int firstWhite = -1, lastWhite = -1;
  for (int k = a; k <= b; ++k)
    if (s.red(k) >= settings.saturation - kSaturationRamp && s.dominance(k) < threshold) {
      if (firstWhite < 0)
        firstWhite = k;
      lastWhite = k;
    }
  if (firstWhite >= 0) {
    bool redLeft = false, redRight = false;
    for (int k = std::max(0, a - 2); k < firstWhite && !redLeft; ++k)
      redLeft = s.dominance(k) >= threshold;
    for (int k = lastWhite + 1; k <= std::min(n - 1, b + 2) && !redRight; ++k)
      redRight = s.dominance(k) >= threshold;
    if (!redLeft || !redRight)
      return REJECTED; // white light, not a laser
  }
  // The other scan direction crosses the stripe more steeply here: it measures this part of the curve.
  const int i = s.alongRow ? s.line : p, j = s.alongRow ? p : s.line;
  const Run across = runThrough(s.score, s.W, s.H, i, j, s.alongRow ? 1 : 0, s.alongRow ? 0 : 1, half, d + 1);
  if (across.length < b - a + 1)
    return IGNORED;
  // A line grazing the edge of a stripe (nearly tangent to it) runs inside the stripe's flank: its contrast
  // along the line is a fraction of the stripe's contrast across it. A sliver, not a crossing.
  const int di = s.alongRow ? d : 0, dj = s.alongRow ? 0 : d;
  const int acrossBg = std::max(i - di >= 0 && j - dj >= 0 ? s.score[static_cast<size_t>(i - di) * s.W + (j - dj)] : 0,
                                i + di < s.H && j + dj < s.W ? s.score[static_cast<size_t>(i + di) * s.W + (j + dj)] : 0);
  if (across.maxScore - bg > 1.5 * contrast || 2 * contrast < across.maxScore - acrossBg)
    return IGNORED;
  // Centroid of the score above a quarter of the contrast, over the connected part around the peak.
  const double level = bg + 0.25 * contrast;
  int lo = a, hi = b;
  while (lo - 1 >= 0 && s.at(lo - 1) > level && p - lo < d - 1)
    --lo;
  while (hi + 1 < n && s.at(hi + 1) > level && hi - p < d - 1)
    ++hi;
  double sumW = 0.0, sumWk = 0.0;
  for (int k = lo; k <= hi; ++k) {
    const double w = s.at(k) - level;
    if (w > 0.0) {
      sumW += w;
      sumWk += w * k;
    }
  }
  const double centre = sumW > 0.0 ? sumWk / sumW : p;
  out.point = s.alongRow ? vpImagePoint(s.line, centre) : vpImagePoint(centre, s.line);
  return ACCEPTED;
}

// Union-find root with path halving.
int root(std::vector<int> &parent, int k)
{
  while (parent[k] != k) {
    parent[k] = parent[parent[k]];
    k = parent[k];
  }
  return k;
}

// Keeps the crossings that belong to chains (neighbours within `link` pixels) at least minLength long.
std::vector<bool> longChains(const std::vector<Crossing> &crossings, double link, double minLength)
{
  const size_t n = crossings.size();
  std::vector<bool> keep(n, true);
  if (minLength <= 0.0 || n == 0)
    return keep;
  // Points sorted by grid cell (cell side = link): neighbours are in the 3 x 3 cells around.
  const int64_t columns = 1 << 20;
  std::vector<std::pair<int64_t, int> > cells(n);
  for (size_t k = 0; k < n; ++k) {
    const int64_t cx = static_cast<int64_t>(std::floor(crossings[k].point.get_u() / link)) + 1;
    const int64_t cy = static_cast<int64_t>(std::floor(crossings[k].point.get_v() / link)) + 1;
    cells[k] = std::make_pair(cy * columns + cx, static_cast<int>(k));
  }
  std::sort(cells.begin(), cells.end());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const double link2 = link * link;
  for (size_t k = 0; k < n; ++k) {
    const int64_t key = cells[k].first;
    const vpImagePoint &p = crossings[cells[k].second].point;
    for (int64_t dy = -1; dy <= 1; ++dy) {
      const int64_t lo = key + dy * columns - 1, hi = key + dy * columns + 1;
      auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(lo, -1));
      for (; it != cells.end() && it->first <= hi; ++it) {
        if (it->second <= cells[k].second)
          continue; // each pair once
        const vpImagePoint &q = crossings[it->second].point;
        const double du = p.get_u() - q.get_u(), dv = p.get_v() - q.get_v();
        if (du * du + dv * dv <= link2) {
          const int ra = root(parent, cells[k].second), rb = root(parent, it->second);
          if (ra != rb)
            parent[ra] = rb;
        }
      }
    }
  }
  // Extent of each chain: bounding-box diagonal.
  std::vector<double> minU(n, 1e30), maxU(n, -1e30), minV(n, 1e30), maxV(n, -1e30);
  for (size_t k = 0; k < n; ++k) {
    const int r = root(parent, static_cast<int>(k));
    const vpImagePoint &p = crossings[k].point;
    minU[r] = std::min(minU[r], p.get_u());
    maxU[r] = std::max(maxU[r], p.get_u());
    minV[r] = std::min(minV[r], p.get_v());
    maxV[r] = std::max(maxV[r], p.get_v());
  }
  for (size_t k = 0; k < n; ++k) {
    const int r = root(parent, static_cast<int>(k));
    keep[k] = std::hypot(maxU[r] - minU[r], maxV[r] - minV[r]) >= minLength;
  }
  return keep;
}

void markRun(vpImage<unsigned char> &mask, const Crossing &c, unsigned char value)
{
  for (int k = c.first; k <= c.last; ++k) {
    unsigned char &m = c.alongRow ? mask[static_cast<unsigned int>(c.line)][static_cast<unsigned int>(k)]
                                  : mask[static_cast<unsigned int>(k)][static_cast<unsigned int>(c.line)];
    m = std::max(m, value);
  }
}
} // namespace

std::vector<vpImagePoint> detectRidge(const vpImage<vpRGBa> &I, const RidgeSettings &settings,
                                      const RowIntervals *scoreRegion, const RowIntervals *searchRegion,
                                      std::vector<unsigned char> &score, vpImage<unsigned char> &mask,
                                      RidgeReport &report)
{
  std::vector<vpImagePoint> points;
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  mask.resize(I.getHeight(), I.getWidth(), 0);
  if (H == 0 || W == 0)
    return points;
  std::memset(mask.bitmap, 0, static_cast<size_t>(W) * H);
  const unsigned char *rgba = reinterpret_cast<const unsigned char *>(I.bitmap);

  // 1. Score (only over the region when one is given: nothing outside it is read).
  score.resize(static_cast<size_t>(W) * H);
  for (int i = 0; i < H; ++i) {
    const size_t offset = static_cast<size_t>(i) * W;
    if (scoreRegion == nullptr)
      scoreSpan(rgba + 4 * offset, &score[offset], W, settings.saturation);
    else
      for (const std::pair<int, int> &span : (*scoreRegion)[i])
        scoreSpan(rgba + 4 * (offset + span.first), &score[offset + span.first], span.second - span.first + 1,
                  settings.saturation);
  }

  // 2. Threshold from the image's own noise.
  report.noise = estimateNoise(I, scoreRegion);
  report.threshold = std::max(settings.minContrast, settings.noiseFactor * report.noise);
  const int threshold = static_cast<int>(std::ceil(report.threshold));

  // 3. Candidates along the rows and the columns.
  const int d = settings.maxWidth, step = settings.step;
  std::vector<unsigned char> flags(W + 8, 0);
  std::vector<Candidate> rowPeaks, columnPeaks;
  for (int i = 0; i < H; ++i) {
    if (searchRegion == nullptr) {
      if (i % step == 0)
        rowCandidates(score.data(), W, i, 0, W - 1, d, threshold, flags, rowPeaks);
      columnCandidates(score.data(), W, H, i, 0, W - 1, d, threshold, step, flags, columnPeaks);
    } else
      for (const std::pair<int, int> &span : (*searchRegion)[i]) {
        if (i % step == 0)
          rowCandidates(score.data(), W, i, span.first, span.second, d, threshold, flags, rowPeaks);
        columnCandidates(score.data(), W, H, i, span.first, span.second, d, threshold, step, flags, columnPeaks);
      }
  }
  std::sort(columnPeaks.begin(), columnPeaks.end()); // by column, then row

  // 4. Profiles around the candidates (one crossing per run: later peaks inside a measured run are skipped).
  std::vector<Crossing> crossings, rejected;
  for (int pass = 0; pass < 2; ++pass) {
    const bool alongRow = pass == 0;
    const std::vector<Candidate> &peaks = alongRow ? rowPeaks : columnPeaks;
    int lastLine = -1, lastEnd = -1;
    for (const Candidate &c : peaks) {
      if (c.line == lastLine && c.pos <= lastEnd)
        continue;
      const ScanLine s = {score.data(), rgba, W, H, alongRow, c.line};
      Crossing crossing;
      const Verdict verdict = analyse(s, c.pos, settings, threshold, crossing);
      if (verdict == IGNORED)
        continue;
      lastLine = c.line;
      lastEnd = crossing.last;
      (verdict == ACCEPTED ? crossings : rejected).push_back(crossing);
    }
  }

  // 5. Continuity: drop the short chains.
  const std::vector<bool> keep = longChains(crossings, 2.0 * step + 0.5, settings.minSegment);
  points.reserve(crossings.size());
  for (const Crossing &c : rejected)
    markRun(mask, c, 100);
  for (size_t k = 0; k < crossings.size(); ++k) {
    markRun(mask, crossings[k], keep[k] ? 255 : 100);
    if (keep[k])
      points.push_back(crossings[k].point);
  }
  return points;
}
} // namespace vpLaserDetector
