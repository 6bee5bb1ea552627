/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  The laser light of vpLaserConicSimulator::render(): the exact (distorted) image of the trace rasterised as a
  distance map, the stripe's fall-off along the ring, and the stripe, white core and bloom drawn from them
  (scaled by the surface's reflectance when asked); traceTruth(), the ground truth of that stripe.
*/
#include <visp3/laser_conic/vpLaserConicException.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace
{
// Added laser light, per unit of the stripe profile, in grey levels (R, G, B): a saturated red.
const float kLaserRgb[3] = {330.f, 26.f, 13.f};
// Full width at half maximum of a Gaussian over its standard deviation.
const double kFwhmPerSigma = 2.0 * std::sqrt(2.0 * std::log(2.0));
// Cone rays sampled to find the brightest and the dimmest visible part of the ring.
const unsigned int kFalloffSamples = 2048;

// Squared distance from (px, py) to the segment [a, b]; \e t receives the parameter of the nearest point.
inline float squaredDistanceToSegment(float px, float py, float ax, float ay, float bx, float by, float &t)
{
  const float dx = bx - ax, dy = by - ay;
  const float len2 = dx * dx + dy * dy;
  t = len2 > 0.f ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.f;
  t = std::min(1.f, std::max(0.f, t));
  const float ex = ax + t * dx - px, ey = ay + t * dy - py;
  return ex * ex + ey * ey;
}

// Peak of a Gaussian line profile of standard deviation \e sigma after a Gaussian blur \e blur (both pixels).
inline double blurredPeak(double sigma, double blur) { return sigma / std::sqrt(sigma * sigma + blur * blur); }

// True when the image point (u, v) is hidden by one of the occluders (as render() fills them).
bool occluded(const std::vector<std::vector<vpImagePoint> > &occluders, double u, double v)
{
  for (const std::vector<vpImagePoint> &polygon : occluders) {
    if (polygon.size() < 3)
      continue;
    std::vector<cv::Point2f> contour;
    contour.reserve(polygon.size());
    for (const vpImagePoint &p : polygon)
      contour.push_back(
          cv::Point2f(static_cast<float>(std::lround(p.get_u())), static_cast<float>(std::lround(p.get_v()))));
    if (cv::pointPolygonTest(contour, cv::Point2f(static_cast<float>(u), static_cast<float>(v)), false) >= 0)
      return true;
  }
  return false;
}

// Throws \e message when a sample's \e field (a measurement that starts as NaN) was not measured.
void requireMeasured(const std::vector<vpLaserConicSimulator::vpTraceTruth> &truth,
                     double vpLaserConicSimulator::vpTraceTruth::*field, const char *message)
{
  for (const vpLaserConicSimulator::vpTraceTruth &t : truth)
    if (std::isnan(t.*field))
      throw vpLaserConicException(vpLaserConicException::badValueError, message);
}

// Brightness R + G + B of I at p, bilinear between the four pixels around it (the border pixels repeated).
double bilinearBrightness(const vpImage<vpRGBa> &I, const vpImagePoint &p)
{
  const int W = static_cast<int>(I.getWidth()), H = static_cast<int>(I.getHeight());
  const double u = std::min(std::max(p.get_u(), 0.0), W - 1.0), v = std::min(std::max(p.get_v(), 0.0), H - 1.0);
  const int j = std::max(0, std::min(static_cast<int>(u), W - 2)),
            i = std::max(0, std::min(static_cast<int>(v), H - 2));
  const double a = u - j, b = v - i;
  const auto at = [&I, W, H](int x, int y) {
    const vpRGBa &q = I[static_cast<unsigned int>(std::min(y, H - 1))][static_cast<unsigned int>(std::min(x, W - 1))];
    return static_cast<double>(q.R) + q.G + q.B;
  };
  return (1 - a) * (1 - b) * at(j, i) + a * (1 - b) * at(j + 1, i) + (1 - a) * b * at(j, i + 1) +
         a * b * at(j + 1, i + 1);
}

// True when the settings shape the stripe's brightness along the ring.
inline bool hasFalloff(const vpLaserConicSimulator::vpRenderSettings &s)
{
  return s.distanceFalloff > 0.0 || s.lambertIncidence;
}
} // namespace

double vpLaserConicSimulator::rawFalloff(const vpRenderSettings &settings, double gamma) const
{
  double P[3];
  if (!groundPoint(gamma, P))
    return 0.0;
  const double ray[3] = {P[0] - m_cMl[0][3], P[1] - m_cMl[1][3], P[2] - m_cMl[2][3]};
  const double d = std::sqrt(ray[0] * ray[0] + ray[1] * ray[1] + ray[2] * ray[2]);
  double value = settings.distanceFalloff > 0.0 ? std::pow(d, -settings.distanceFalloff) : 1.0;
  if (settings.lambertIncidence) // cosine of the ray with the ground normal (the Z axis of g)
    value *= std::fabs(ray[0] * m_cMg[0][2] + ray[1] * m_cMg[1][2] + ray[2] * m_cMg[2][2]) / d;
  return value;
}

vpLaserConicSimulator::vpFalloffModel vpLaserConicSimulator::falloffModel(const vpRenderSettings &settings) const
{
  vpFalloffModel model;
  if (!hasFalloff(settings))
    return model;
  // The visible ring: cone rays whose ground point is seen inside the image.
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (unsigned int k = 0; k < kFalloffSamples; ++k) {
    const double gamma = 2.0 * M_PI * k / kFalloffSamples;
    double P[3], u = 0.0, v = 0.0;
    if (!groundPoint(gamma, P) || !project(P, u, v) || u < 0.0 || v < 0.0 || u > m_width - 1.0 || v > m_height - 1.0)
      continue;
    const double value = rawFalloff(settings, gamma);
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  if (!(hi > 0.0))
    return model; // nothing visible: nothing to normalise
  model.maxRaw = hi;
  if (settings.stripeFarFraction > 0.0 && lo < hi && lo > 0.0)
    model.exponent = std::log(settings.stripeFarFraction) / std::log(lo / hi);
  return model;
}

double vpLaserConicSimulator::stripeFalloff(const vpRenderSettings &settings, const vpFalloffModel &model,
                                            double gamma) const
{
  if (!hasFalloff(settings))
    return 1.0;
  const double raw = rawFalloff(settings, gamma);
  return raw > 0.0 ? std::pow(raw / model.maxRaw, model.exponent) : 1.0;
}

void vpLaserConicSimulator::traceDistanceMap(float radius, std::vector<float> &dist2, const vpRenderSettings *settings,
                                             std::vector<float> *falloff) const
{
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  dist2.assign(static_cast<size_t>(W) * H, std::numeric_limits<float>::infinity());
  const bool withFalloff = settings != nullptr && falloff != nullptr;
  const vpFalloffModel model = withFalloff ? falloffModel(*settings) : vpFalloffModel();
  if (withFalloff)
    falloff->assign(dist2.size(), 1.f);

  // Image point of the cone ray gamma, if that ray lights a ground point in front of the camera.
  struct Sample
  {
    double gamma, u, v;
    bool ok;
    float falloff;
  };
  auto sample = [&](double gamma) {
    Sample s = {gamma, 0.0, 0.0, false, 1.f};
    double P[3];
    s.ok = groundPoint(gamma, P) && project(P, s.u, s.v);
    if (s.ok && withFalloff)
      s.falloff = static_cast<float>(stripeFalloff(*settings, model, gamma));
    return s;
  };
  // Lowers dist2 around the chord [a, b] (and gives the pixels it lowers the chord's fall-off there).
  auto rasterise = [&](const Sample &a, const Sample &b) {
    const float ax = static_cast<float>(a.u), ay = static_cast<float>(a.v);
    const float bx = static_cast<float>(b.u), by = static_cast<float>(b.v);
    const int j0 = std::max(0, static_cast<int>(std::floor(std::min(ax, bx) - radius)));
    const int j1 = std::min(W - 1, static_cast<int>(std::ceil(std::max(ax, bx) + radius)));
    const int i0 = std::max(0, static_cast<int>(std::floor(std::min(ay, by) - radius)));
    const int i1 = std::min(H - 1, static_cast<int>(std::ceil(std::max(ay, by) + radius)));
    for (int i = i0; i <= i1; ++i) {
      const size_t row = static_cast<size_t>(i) * W;
      for (int j = j0; j <= j1; ++j) {
        float t = 0.f;
        const float d2 = squaredDistanceToSegment(static_cast<float>(j), static_cast<float>(i), ax, ay, bx, by, t);
        if (d2 < dist2[row + j]) {
          dist2[row + j] = d2;
          if (withFalloff)
            (*falloff)[row + j] = a.falloff + t * (b.falloff - a.falloff);
        }
      }
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
    const Sample next = k == coarse ? Sample{2.0 * M_PI, first.u, first.v, first.ok, first.falloff}
                                    : sample(2.0 * M_PI * k / coarse);
    draw(previous, next, 24);
    previous = next;
  }
}

void vpLaserConicSimulator::renderLaser(float *rgb, const vpRenderSettings &settings, const float *reflectance) const
{
  // Distance of the pixels near the trace to the exact (distorted) image curve; Gaussian profiles of that
  // distance (stripe and bloom) added as red light, with white light where the red exceeds the sensor range.
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  const double sigma = settings.stripeWidth / kFwhmPerSigma, bloomSigma = settings.bloomWidth / kFwhmPerSigma;
  const bool bloom = settings.bloom > 0.0;
  const float radius = static_cast<float>(3.5 * std::max(sigma, bloom ? bloomSigma : 0.0) + 1.0);
  std::vector<float> dist2, falloff;
  const bool withFalloff = hasFalloff(settings);
  traceDistanceMap(radius, dist2, &settings, withFalloff ? &falloff : nullptr);
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
    if (withFalloff)
      red *= falloff[k];
    if (reflectance != nullptr) // the light the surface sends back at the laser's wavelength
      red *= reflectance[k];
    const float white = core * std::max(0.f, red - 255.f);
    float *out = rgb + 3 * k;
    out[0] += red + white;
    out[1] += leakG * red + white;
    out[2] += leakB * red + white;
  }
}

std::vector<vpLaserConicSimulator::vpTraceTruth> vpLaserConicSimulator::traceTruth(unsigned int n,
                                                                                   const vpRenderSettings &settings)
{
  checkCamera();
  checkSettings(settings);
  const vpFalloffModel model = falloffModel(settings);
  const vpHomogeneousMatrix gMc = m_cMg.inverse();
  // Peak of the stripe and of its bloom across a straight curve after the optical blur, per unit of laserPower,
  // as red dominance (the laser also leaks into the green channel).
  const double sigma = settings.stripeWidth / kFwhmPerSigma, bloomSigma = settings.bloomWidth / kFwhmPerSigma;
  const double unitPeak =
      (blurredPeak(sigma, settings.blur) + settings.bloom * blurredPeak(bloomSigma, settings.blur)) *
      (1.0 - static_cast<double>(kLaserRgb[1]) / kLaserRgb[0]);
  std::vector<vpTraceTruth> truth;
  truth.reserve(n);
  for (unsigned int k = 0; k < n; ++k) {
    vpTraceTruth t;
    t.gamma = 2.0 * M_PI * k / n;
    double P[3], u = 0.0, v = 0.0;
    if (!groundPoint(t.gamma, P) || !project(P, u, v) || u < 0.0 || v < 0.0 || u > m_width - 1.0 || v > m_height - 1.0)
      continue;
    t.point.set_uv(u, v);
    t.falloff = stripeFalloff(settings, model, t.gamma);
    if (settings.reflectanceScaled) {
      const double X = gMc[0][0] * P[0] + gMc[0][1] * P[1] + gMc[0][2] * P[2] + gMc[0][3];
      const double Y = gMc[1][0] * P[0] + gMc[1][1] * P[1] + gMc[1][2] * P[2] + gMc[1][3];
      t.reflectance = groundReflectance(settings, X, Y);
    }
    const bool lit = settings.laserOn && !occluded(settings.occluders, u, v);
    t.peakDominance = lit ? settings.laserPower * t.falloff * t.reflectance * unitPeak : 0.0;
    t.peakOverNoise = settings.noise > 0.0 ? t.peakDominance / settings.noise
                                           : (t.peakDominance > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    truth.push_back(t);
  }
  return truth;
}

double vpLaserConicSimulator::coverageOf(const std::vector<vpTraceTruth> &truth,
                                         const std::vector<vpImagePoint> &points, double radius,
                                         const std::function<bool(const vpTraceTruth &)> &counts)
{
  // The points by cell of side 2 radius (at least 1 px): a query reads its 3 x 3 cells.
  const double cellSize = std::max(1.0, 2.0 * radius);
  auto cellOf = [cellSize](double x) { return static_cast<long long>(std::floor(x / cellSize)); };
  std::map<std::pair<long long, long long>, std::vector<vpImagePoint> > cells;
  for (const vpImagePoint &p : points)
    cells[std::make_pair(cellOf(p.get_u()), cellOf(p.get_v()))].push_back(p);
  auto covered = [&](const vpImagePoint &q) {
    const long long cu = cellOf(q.get_u()), cv = cellOf(q.get_v());
    for (long long dv = -1; dv <= 1; ++dv)
      for (long long du = -1; du <= 1; ++du) {
        const auto it = cells.find(std::make_pair(cu + du, cv + dv));
        if (it != cells.end())
          for (const vpImagePoint &p : it->second)
            if (vpImagePoint::distance(p, q) <= radius)
              return true;
      }
    return false;
  };
  double visible = 0.0, found = 0.0;
  const size_t n = truth.size();
  for (size_t k = 0; k < n; ++k) {
    if (!counts(truth[k]))
      continue;
    double length = 0.0;
    for (size_t m : {(k + n - 1) % n, (k + 1) % n}) {
      const double d = vpImagePoint::distance(truth[k].point, truth[m].point);
      length += d < 4.0 ? 0.5 * d : 0.0;
    }
    visible += length;
    found += covered(truth[k].point) ? length : 0.0;
  }
  return visible > 0.0 ? found / visible : 0.0;
}

double vpLaserConicSimulator::stripeCoverage(const std::vector<vpTraceTruth> &truth,
                                             const std::vector<vpImagePoint> &points, double minOverNoise,
                                             double radius)
{
  return coverageOf(truth, points, radius,
                    [minOverNoise](const vpTraceTruth &t) { return t.peakOverNoise >= minOverNoise; });
}

double vpLaserConicSimulator::ridgeCoverage(const std::vector<vpTraceTruth> &truth,
                                            const std::vector<vpImagePoint> &points, double minOverNoise, double radius)
{
  requireMeasured(truth, &vpTraceTruth::prominenceOverNoise,
                  "ridgeCoverage(): the prominence of the truth was not measured "
                  "(call measureProminence() with the settings of traceTruth())");
  return coverageOf(truth, points, radius, [minOverNoise](const vpTraceTruth &t) {
    return t.peakOverNoise >= minOverNoise && t.prominenceOverNoise >= minOverNoise;
  });
}

void vpLaserConicSimulator::measureCompression(std::vector<vpTraceTruth> &truth, const vpRenderSettings &settings) const
{
  checkCamera();
  checkSettings(settings);
  if (settings.jpegQuality <= 0) {
    for (vpTraceTruth &t : truth)
      t.keptOverNoise = t.peakOverNoise;
    return;
  }
  // The stripe's brightness at each sample: the image with the laser less the one without, compressed or not,
  // each drawn by a copy of this simulator (the same noise, the same floor).
  const auto added = [this, &truth](const vpRenderSettings &with) {
    vpRenderSettings without = with;
    without.laserOn = false;
    vpImage<vpRGBa> on, off;
    vpLaserConicSimulator(*this).render(on, with);
    vpLaserConicSimulator(*this).render(off, without);
    std::vector<double> stripe(truth.size(), 0.0);
    for (size_t k = 0; k < truth.size(); ++k)
      stripe[k] = bilinearBrightness(on, truth[k].point) - bilinearBrightness(off, truth[k].point);
    return stripe;
  };
  vpRenderSettings raw = settings;
  raw.jpegQuality = 0;
  const std::vector<double> kept = added(settings), drawn = added(raw);
  const double reach = 4.5; // pixels along the ring on each side: a nine-line profile's stretch
  const size_t n = truth.size();
  for (size_t k = 0; k < n; ++k) {
    double sumKept = kept[k], sumDrawn = drawn[k];
    for (const bool forwards : {false, true})
      for (size_t step = 1; step < n; ++step) {
        const size_t m = forwards ? (k + step) % n : (k + n - step) % n; // round the ring
        if (vpImagePoint::distance(truth[m].point, truth[k].point) > reach)
          break;
        sumKept += kept[m];
        sumDrawn += drawn[m];
      }
    const double share = sumDrawn > 0.0 ? std::min(1.0, std::max(0.0, sumKept / sumDrawn)) : 0.0;
    truth[k].keptOverNoise = truth[k].peakOverNoise * share;
  }
}

double vpLaserConicSimulator::keptCoverage(const std::vector<vpTraceTruth> &truth,
                                           const std::vector<vpImagePoint> &points, double minOverNoise, double radius)
{
  requireMeasured(truth, &vpTraceTruth::keptOverNoise,
                  "keptCoverage(): what the compression keeps of the stripe was not measured "
                  "(call measureCompression() with the settings of traceTruth())");
  return coverageOf(truth, points, radius,
                    [minOverNoise](const vpTraceTruth &t) { return t.keptOverNoise >= minOverNoise; });
}

bool vpLaserConicSimulator::curveNormal(double gamma, double n[2]) const
{
  // The chord between two rays 1e-4 rad apart on either side (under a hundredth of a pixel on the rings drawn).
  const double h = 1e-4;
  double P[3], Q[3], u0 = 0.0, v0 = 0.0, u1 = 0.0, v1 = 0.0;
  if (!groundPoint(gamma - h, P) || !groundPoint(gamma + h, Q) || !project(P, u0, v0) || !project(Q, u1, v1))
    return false;
  const double length = std::hypot(u1 - u0, v1 - v0);
  if (!(length > 0.0))
    return false;
  n[0] = -(v1 - v0) / length;
  n[1] = (u1 - u0) / length;
  return true;
}

void vpLaserConicSimulator::measureProminence(std::vector<vpTraceTruth> &truth, const vpRenderSettings &settings) const
{
  checkCamera();
  checkSettings(settings);
  vpRenderSettings clean = settings;
  clean.noise = 0.0;
  clean.jpegQuality = 0;
  vpImage<vpRGBa> I;
  vpLaserConicSimulator(*this).render(I, clean);
  // Red dominance of the pixel nearest to (u, v), the image's border repeated. (Pixels, not an interpolation,
  // which reads a stripe's peak lower wherever the normal passes between pixel centres.)
  auto dominance = [&I](double u, double v) {
    const long j = std::min(std::max(std::lround(u), 0L), static_cast<long>(I.getWidth()) - 1),
               i = std::min(std::max(std::lround(v), 0L), static_cast<long>(I.getHeight()) - 1);
    const vpRGBa &p = I[static_cast<unsigned int>(i)][static_cast<unsigned int>(j)];
    return static_cast<double>(p.R) - std::max(p.G, p.B);
  };
  // The stripe's extent after the optical blur: its top is the brightest pixel within half its width at half
  // maximum of the centre point (at least 0.75 px, so that some pixel centre is in reach), the scene beside it
  // read where the stripe's own light is 0.2 % of its peak.
  const double sigma = std::hypot(settings.stripeWidth / kFwhmPerSigma, settings.blur);
  const double top = std::max(0.75, 0.5 * kFwhmPerSigma * sigma), side = 3.5 * sigma;
  for (vpTraceTruth &t : truth) {
    double n[2] = {0.0, 0.0};
    if (t.peakDominance > 0.0 && curveNormal(t.gamma, n)) {
      const double u = t.point.get_u(), v = t.point.get_v();
      double peak = -std::numeric_limits<double>::infinity();
      for (double di = std::ceil(v - top); di <= v + top; ++di)
        for (double dj = std::ceil(u - top); dj <= u + top; ++dj)
          if (std::hypot(dj - u, di - v) <= top)
            peak = std::max(peak, dominance(dj, di));
      t.prominence =
          peak - std::max(dominance(u - side * n[0], v - side * n[1]), dominance(u + side * n[0], v + side * n[1]));
    } else
      t.prominence = 0.0;
    t.prominenceOverNoise = settings.noise > 0.0 ? t.prominence / settings.noise
                                                 : (t.prominence > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  }
}
