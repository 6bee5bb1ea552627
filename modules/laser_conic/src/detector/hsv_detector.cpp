/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The historical detector of vpLaserConicDetector (DETECTION_HSV): HSV thresholds, brightness-weighted centre
// of each run along the rows and the columns.
#include "laser_detector.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace
{
// True when the 8 bytes at p are all zero: lets the scans jump over empty stretches of the mask.
inline bool zero8(const unsigned char *p)
{
  uint64_t word;
  std::memcpy(&word, p, sizeof(word));
  return word == 0;
}

// Run of mask pixels through (i, j) along one direction ((di, dj) = (1, 0) for a column, (0, 1) for a row):
// its length (counting stops beyond maxLength, all the caller needs) and the largest weight on it.
struct CrossRun
{
  int length;
  int maxWeight;
};
CrossRun runThrough(const unsigned char *mask, const unsigned char *weight, int H, int W, int i, int j, int di, int dj,
                    int maxLength)
{
  CrossRun run = {0, 0};
  if (!mask[i * W + j])
    return run;
  run.length = 1;
  run.maxWeight = weight[i * W + j];
  for (int sign = -1; sign <= 1; sign += 2) {
    for (int k = 1; k <= maxLength; ++k) {
      const int ii = i + sign * k * di, jj = j + sign * k * dj;
      if (ii < 0 || jj < 0 || ii >= H || jj >= W || !mask[ii * W + jj])
        break;
      ++run.length;
      run.maxWeight = std::max<int>(run.maxWeight, weight[ii * W + jj]);
    }
  }
  return run;
}

// Centre of a run that ended, kept if it is a stripe crossing measured by the better-suited scan direction.
// alongRow: the run lies along row `line` (centre is a column) when true, along column `line` otherwise.
void keepRun(const unsigned char *mask, const unsigned char *weight, int H, int W, bool alongRow, int line, int start,
             int end, double sumW, double sumWk, int maxW, int lineLength, int maxWidth,
             std::vector<vpImagePoint> &points)
{
  const int length = end - start;
  if (length > maxWidth || start == 0 || end == lineLength)
    return; // blob, or truncated by the image border
  const double centre = sumWk / sumW;
  const int c = static_cast<int>(centre + 0.5);
  const CrossRun across = alongRow ? runThrough(mask, weight, H, W, line, c, 1, 0, maxWidth)
                                   : runThrough(mask, weight, H, W, c, line, 0, 1, maxWidth);
  // The other scan direction crosses the stripe more steeply here: it measures this part of the curve.
  if (across.length < length)
    return;
  // A run along the dim edge of the stripe (mask flicker at the threshold, noise) is not a crossing: a
  // crossing goes through the bright core, so its peak is about the peak of the run across it.
  if (2 * maxW < across.maxWeight)
    return;
  points.push_back(alongRow ? vpImagePoint(line, centre) : vpImagePoint(centre, line));
}

// Stripe crossings along every step-th row.
void scanRows(const unsigned char *mask, const unsigned char *weight, int H, int W, int step, int maxWidth,
              std::vector<vpImagePoint> &points)
{
  for (int i = 0; i < H; i += step) {
    const unsigned char *m = mask + i * W;
    const unsigned char *w = weight + i * W;
    int j = 0;
    while (j < W) {
      if (j + 8 <= W && zero8(m + j)) {
        j += 8;
        continue;
      }
      if (!m[j]) {
        ++j;
        continue;
      }
      const int start = j;
      double sumW = 0.0, sumWj = 0.0;
      int maxW = 0;
      for (; j < W && m[j]; ++j) {
        sumW += w[j];
        sumWj += static_cast<double>(w[j]) * j;
        maxW = std::max<int>(maxW, w[j]);
      }
      keepRun(mask, weight, H, W, true, i, start, j, sumW, sumWj, maxW, W, maxWidth, points);
    }
  }
}

// Stripe crossings along every step-th column, visited row by row (cache friendly) with one open run per column.
void scanColumns(const unsigned char *mask, const unsigned char *weight, int H, int W, int step, int maxWidth,
                 std::vector<vpImagePoint> &points)
{
  std::vector<int> start(W, -1), maxW(W, 0);
  std::vector<double> sumW(W, 0.0), sumWi(W, 0.0);
  std::vector<unsigned char> open(W + 8, 0); // 1 where a column run is open (padded for zero8)
  for (int i = 0; i <= H; ++i) {
    const unsigned char *m = i < H ? mask + i * W : nullptr;
    const unsigned char *w = weight + i * W;
    for (int j0 = 0; j0 < W; j0 += 8) {
      const int j1 = std::min(W, j0 + 8);
      // Nothing to start, extend or close in these 8 columns.
      if (zero8(&open[j0]) && (m == nullptr || (j1 - j0 == 8 && zero8(m + j0))))
        continue;
      for (int j = j0; j < j1; ++j) {
        if (j % step != 0)
          continue;
        if (m != nullptr && m[j]) {
          if (!open[j]) {
            open[j] = 1;
            start[j] = i;
            sumW[j] = 0.0;
            sumWi[j] = 0.0;
            maxW[j] = 0;
          }
          sumW[j] += w[j];
          sumWi[j] += static_cast<double>(w[j]) * i;
          maxW[j] = std::max<int>(maxW[j], w[j]);
        } else if (open[j]) {
          keepRun(mask, weight, H, W, false, j, start[j], i, sumW[j], sumWi[j], maxW[j], H, maxWidth, points);
          open[j] = 0;
        }
      }
    }
  }
}
} // namespace

namespace vsp::laser_detector
{
std::vector<vpImagePoint> detectHsv(const vpImage<vpRGBa> &I, const HsvSettings &settings,
                                    vpImage<unsigned char> &maskImage)
{
  std::vector<vpImagePoint> points;
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  maskImage.resize(I.getHeight(), I.getWidth()); // cleared below
  if (H == 0 || W == 0)
    return points;

  // vpRGBa is laid out as R, G, B, A bytes: wrap it without copy.
  const cv::Mat rgba(H, W, CV_8UC4, const_cast<vpRGBa *>(I.bitmap));
  cv::Mat rgb, hsv;
  cv::cvtColor(rgba, rgb, cv::COLOR_RGBA2RGB);
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);

  // Mask and brightness weight of the trace pixels, in one pass.
  const int maxHueLow = settings.maxHueLow, minHueHigh = settings.minHueHigh, minSaturation = settings.minSaturation,
            minValue = settings.minValue;
  cv::Mat weight = cv::Mat::zeros(H, W, CV_8UC1);
  unsigned char *mask = maskImage.bitmap;
  std::memset(mask, 0, static_cast<size_t>(W) * H);
  for (int i = 0; i < H; ++i) {
    const unsigned char *p = hsv.ptr<unsigned char>(i);
    unsigned char *w = weight.ptr<unsigned char>(i);
    unsigned char *m = mask + i * W;
    for (int j = 0; j < W; ++j, p += 3) {
      // Most pixels are darker than the laser: one well-predicted test rejects them.
      if (p[2] < minValue)
        continue;
      const int h = p[0], s = p[1], v = p[2];
      if ((h <= maxHueLow || h >= minHueHigh) && s >= minSaturation) {
        m[j] = 255;
        // Brightness above the threshold (+1 so that no trace pixel weighs zero).
        w[j] = static_cast<unsigned char>(std::min(255, v - minValue + 1));
      }
    }
  }

  const int step = settings.step, maxWidth = settings.maxWidth;
  scanRows(mask, weight.ptr<unsigned char>(0), H, W, step, maxWidth, points);
  scanColumns(mask, weight.ptr<unsigned char>(0), H, W, step, maxWidth, points);
  return points;
}
} // namespace vsp::laser_detector
