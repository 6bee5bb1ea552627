/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  The laser light of vpLaserConicSimulator::render(): the exact (distorted) image of the trace rasterised as a
  distance map, and the stripe, white core and bloom drawn from it.
*/
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace
{
// Added laser light, per unit of the stripe profile, in grey levels (R, G, B): a saturated red.
const float kLaserRgb[3] = {330.f, 26.f, 13.f};

// Squared distance from (px, py) to the segment [a, b].
inline float squaredDistanceToSegment(float px, float py, float ax, float ay, float bx, float by)
{
  const float dx = bx - ax, dy = by - ay;
  const float len2 = dx * dx + dy * dy;
  float t = len2 > 0.f ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.f;
  t = std::min(1.f, std::max(0.f, t));
  const float ex = ax + t * dx - px, ey = ay + t * dy - py;
  return ex * ex + ey * ey;
}
} // namespace

void vpLaserConicSimulator::traceDistanceMap(float radius, std::vector<float> &dist2) const
{
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  dist2.assign(static_cast<size_t>(W) * H, std::numeric_limits<float>::infinity());

  // Image point of the cone ray gamma, if that ray lights a ground point in front of the camera.
  struct Sample
  {
    double gamma, u, v;
    bool ok;
  };
  auto sample = [this](double gamma) {
    Sample s = {gamma, 0.0, 0.0, false};
    double P[3];
    s.ok = groundPoint(gamma, P) && project(P, s.u, s.v);
    return s;
  };
  // Lowers dist2 around the chord [a, b].
  auto rasterise = [&](const Sample &a, const Sample &b) {
    const float ax = static_cast<float>(a.u), ay = static_cast<float>(a.v);
    const float bx = static_cast<float>(b.u), by = static_cast<float>(b.v);
    const int j0 = std::max(0, static_cast<int>(std::floor(std::min(ax, bx) - radius)));
    const int j1 = std::min(W - 1, static_cast<int>(std::ceil(std::max(ax, bx) + radius)));
    const int i0 = std::max(0, static_cast<int>(std::floor(std::min(ay, by) - radius)));
    const int i1 = std::min(H - 1, static_cast<int>(std::ceil(std::max(ay, by) + radius)));
    for (int i = i0; i <= i1; ++i) {
      float *row = &dist2[static_cast<size_t>(i) * W];
      for (int j = j0; j <= j1; ++j)
        row[j] = std::min(row[j], squaredDistanceToSegment(static_cast<float>(j), static_cast<float>(i), ax, ay, bx, by));
    }
  };
  // Both ends on the same outer side of the image (with the stripe radius): the chord cannot touch it.
  auto outside = [&](const Sample &a, const Sample &b) {
    return (a.u < -radius && b.u < -radius) || (a.v < -radius && b.v < -radius) ||
           (a.u > W - 1 + radius && b.u > W - 1 + radius) || (a.v > H - 1 + radius && b.v > H - 1 + radius);
  };
  // Splits [a, b] in gamma until each chord is shorter than a pixel, so that the polyline stays within
  // 1e-3 pixel of the curve (curvature radius above ~100 pixels); depth-limited near the horizon, where
  // the curve runs to infinity.
  std::function<void(const Sample &, const Sample &, int)> draw = [&](const Sample &a, const Sample &b, int depth) {
    if (a.ok && b.ok) {
      if (outside(a, b))
        return;
      if (std::hypot(b.u - a.u, b.v - a.v) <= 1.0) {
        rasterise(a, b);
        return;
      }
    }
    if (depth == 0 || (!a.ok && !b.ok))
      return;
    const Sample mid = sample(0.5 * (a.gamma + b.gamma));
    draw(a, mid, depth - 1);
    draw(mid, b, depth - 1);
  };
  const unsigned int coarse = 256;
  Sample previous = sample(0.0);
  const Sample first = previous;
  for (unsigned int k = 1; k <= coarse; ++k) {
    const Sample next = k == coarse ? Sample{2.0 * M_PI, first.u, first.v, first.ok} : sample(2.0 * M_PI * k / coarse);
    draw(previous, next, 24);
    previous = next;
  }
}

void vpLaserConicSimulator::renderLaser(float *rgb, const vpRenderSettings &settings) const
{
  // Distance of the pixels near the trace to the exact (distorted) image curve; Gaussian profiles of that
  // distance (stripe and bloom) added as red light, with white light where the red exceeds the sensor range.
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  const double fwhm = 2.0 * std::sqrt(2.0 * std::log(2.0));
  const double sigma = settings.stripeWidth / fwhm, bloomSigma = settings.bloomWidth / fwhm;
  const bool bloom = settings.bloom > 0.0;
  const float radius = static_cast<float>(3.5 * std::max(sigma, bloom ? bloomSigma : 0.0) + 1.0);
  std::vector<float> dist2;
  traceDistanceMap(radius, dist2);
  const float inv2s2 = static_cast<float>(1.0 / (2.0 * sigma * sigma));
  const float inv2b2 = static_cast<float>(1.0 / (2.0 * bloomSigma * bloomSigma));
  const float r2 = radius * radius, power = static_cast<float>(settings.laserPower);
  const float bloomPower = static_cast<float>(settings.bloom * settings.laserPower);
  const float core = static_cast<float>(settings.whiteCore);
  const float leakG = kLaserRgb[1] / kLaserRgb[0], leakB = kLaserRgb[2] / kLaserRgb[0];
  for (int k = 0; k < W * H; ++k) {
    if (!(dist2[k] < r2))
      continue;
    float red = power * std::exp(-dist2[k] * inv2s2);
    if (bloom)
      red += bloomPower * std::exp(-dist2[k] * inv2b2);
    const float white = core * std::max(0.f, red - 255.f);
    float *out = rgb + 3 * k;
    out[0] += red + white;
    out[1] += leakG * red + white;
    out[2] += leakB * red + white;
  }
}
