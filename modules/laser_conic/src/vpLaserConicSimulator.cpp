/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/robot/vpImageSimulator.h>

#include "laser_pose_check.h"

namespace
{
// Standard deviation (pixels) of the optical blur applied by render().
const double kBlurSigma = 0.7;
// Added laser light, per unit of the stripe profile, in grey levels (R, G, B): a saturated red.
const float kLaserRgb[3] = {330.f, 26.f, 13.f};
// Grey level of the ground beyond the textured square.
const unsigned char kFarGroundGrey = 20;

// Sensor noise needs millions of Gaussian draws per image: a table of the standard normal quantiles at
// (k + 0.5) / 65536, indexed by 16 random bits, samples it exactly up to a 1/65536 quantisation of the
// probabilities, an order of magnitude faster than transforming uniform draws one by one.
const std::vector<float> &normalQuantiles()
{
  static const std::vector<float> table = [] {
    std::vector<float> q(65536);
    for (size_t k = 0; k < q.size(); ++k) {
      // Inverse of the normal CDF (done once): a few bisection steps to bracket, then Newton steps.
      const double p = (k + 0.5) / q.size();
      double lo = -6.0, hi = 6.0;
      for (int it = 0; it < 8; ++it) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
      }
      double x = 0.5 * (lo + hi);
      for (int it = 0; it < 5; ++it)
        x -= (0.5 * std::erfc(-x / std::sqrt(2.0)) - p) / (std::exp(-0.5 * x * x) / std::sqrt(2.0 * M_PI));
      q[k] = static_cast<float>(x);
    }
    return q;
  }();
  return table;
}

// Small fast generator for the per-pixel noise (xorshift64*), seeded from the simulator's generator.
struct FastRandom
{
  explicit FastRandom(uint64_t seed) : state(seed ? seed : 0x9E3779B97F4A7C15ULL) {}
  uint64_t next()
  {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 0x2545F4914F6CDD1DULL;
  }
  uint64_t state;
};

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

vpLaserConicSimulator::vpLaserConicSimulator()
  : m_cam(), m_width(0), m_height(0), m_openingAngle(34.0 * M_PI / 180.0), m_cMl(), m_cMg(0, 0, 1, 0, 0, 0),
    m_seed(0), m_rng(0), m_texture(), m_textureSeed(0)
{
}

void vpLaserConicSimulator::setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height)
{
  if (!(cam.get_px() > 0) || !(cam.get_py() > 0) || !std::isfinite(cam.get_px()) || !std::isfinite(cam.get_py()) ||
      !std::isfinite(cam.get_u0()) || !std::isfinite(cam.get_v0()))
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicSimulator: focal lengths must be positive and finite");
  if (width == 0 || height == 0)
    throw vpLaserConicException(vpLaserConicException::badCameraError, "vpLaserConicSimulator: empty image size");
  m_cam = cam;
  m_width = width;
  m_height = height;
}

void vpLaserConicSimulator::setLaser(double openingAngle, const vpHomogeneousMatrix &cMl)
{
  if (!std::isfinite(openingAngle) || openingAngle <= 0.0 || openingAngle >= M_PI)
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicSimulator: the laser opening angle must be in (0, pi) radians");
  if (!vpLaserPoseCheck::isFinitePose(cMl))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicSimulator: the laser pose is not a finite rigid transformation");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
}

void vpLaserConicSimulator::setGroundPose(const vpHomogeneousMatrix &cMg)
{
  if (!vpLaserPoseCheck::isFinitePose(cMg))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the ground pose is not a finite rigid transformation");
  // Signed distance of the camera centre to the plane Z = 0 of g.
  const double distance = -(cMg[0][2] * cMg[0][3] + cMg[1][2] * cMg[1][3] + cMg[2][2] * cMg[2][3]);
  if (std::fabs(distance) < 1e-9)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the camera centre lies on the ground plane");
  m_cMg = cMg;
}

void vpLaserConicSimulator::setSeed(unsigned int seed)
{
  m_seed = seed;
  m_rng.seed(seed);
}

vpPlane vpLaserConicSimulator::getGroundPlane() const
{
  // Normal: Z axis of g expressed in the camera frame, flipped so that the camera is on its positive side.
  double n[3] = {m_cMg[0][2], m_cMg[1][2], m_cMg[2][2]};
  double d = -(n[0] * m_cMg[0][3] + n[1] * m_cMg[1][3] + n[2] * m_cMg[2][3]);
  if (d < 0) {
    for (double &c : n)
      c = -c;
    d = -d;
  }
  return vpPlane(n[0], n[1], n[2], d);
}

void vpLaserConicSimulator::checkCamera() const
{
  if (m_width == 0 || m_height == 0)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicSimulator: call setCamera() before simulating images");
}

bool vpLaserConicSimulator::groundPoint(double gamma, double P[3]) const
{
  const double s = std::sin(0.5 * m_openingAngle), c = std::cos(0.5 * m_openingAngle);
  const double dl[3] = {s * std::cos(gamma), s * std::sin(gamma), c};
  double d[3], apex[3], n[3], g0[3];
  for (unsigned int i = 0; i < 3; ++i) {
    d[i] = m_cMl[i][0] * dl[0] + m_cMl[i][1] * dl[1] + m_cMl[i][2] * dl[2];
    apex[i] = m_cMl[i][3];
    n[i] = m_cMg[i][2];
    g0[i] = m_cMg[i][3];
  }
  const double denom = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
  const double num = n[0] * (g0[0] - apex[0]) + n[1] * (g0[1] - apex[1]) + n[2] * (g0[2] - apex[2]);
  if (std::fabs(denom) < 1e-12)
    return false; // ray parallel to the ground
  const double lambda = num / denom;
  if (!(lambda > 0.0) || !std::isfinite(lambda))
    return false; // the ground is behind the apex along this ray: the backward nappe is not lit
  for (unsigned int i = 0; i < 3; ++i)
    P[i] = apex[i] + lambda * d[i];
  return true;
}

bool vpLaserConicSimulator::project(const double P[3], double &u, double &v) const
{
  if (!(P[2] > 1e-9))
    return false;
  vpMeterPixelConversion::convertPoint(m_cam, P[0] / P[2], P[1] / P[2], u, v);
  return std::isfinite(u) && std::isfinite(v);
}

std::vector<vpImagePoint> vpLaserConicSimulator::tracePoints(unsigned int n, double roughness)
{
  checkCamera();
  if (!std::isfinite(roughness) || roughness < 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the ground roughness must be finite and >= 0");
  std::normal_distribution<double> offset(0.0, 1.0);
  const double normal[3] = {m_cMg[0][2], m_cMg[1][2], m_cMg[2][2]};
  std::vector<vpImagePoint> points;
  points.reserve(n);
  for (unsigned int k = 0; k < n; ++k) {
    const double gamma = 2.0 * M_PI * k / n;
    double P[3];
    if (!groundPoint(gamma, P))
      continue;
    if (roughness > 0.0) {
      const double h = roughness * offset(m_rng);
      for (unsigned int i = 0; i < 3; ++i)
        P[i] += h * normal[i];
    }
    double u, v;
    if (!project(P, u, v))
      continue;
    if (u < 0.0 || v < 0.0 || u > m_width - 1.0 || v > m_height - 1.0)
      continue;
    points.push_back(vpImagePoint(v, u));
  }
  return points;
}

std::vector<vpImagePoint> vpLaserConicSimulator::addNoise(const std::vector<vpImagePoint> &points, double sigma)
{
  if (!std::isfinite(sigma) || sigma < 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the noise standard deviation must be finite and >= 0");
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<vpImagePoint> noisy(points);
  for (vpImagePoint &p : noisy) {
    const double du = sigma * gauss(m_rng);
    const double dv = sigma * gauss(m_rng);
    p.set_uv(p.get_u() + du, p.get_v() + dv);
  }
  return noisy;
}

std::vector<vpImagePoint> vpLaserConicSimulator::addOutliers(const std::vector<vpImagePoint> &points, double ratio,
                                                             std::vector<bool> *isOutlier)
{
  checkCamera();
  if (!std::isfinite(ratio) || ratio < 0.0 || ratio > 1.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the outlier ratio must be in [0, 1]");
  const size_t n = points.size();
  const size_t nbOutliers = static_cast<size_t>(std::llround(ratio * static_cast<double>(n)));

  // Which points become outliers: the first nbOutliers of a random permutation.
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), m_rng);
  std::vector<vpImagePoint> mixed(points);
  std::vector<bool> flags(n, false);
  std::uniform_real_distribution<double> uDist(0.0, m_width - 1.0), vDist(0.0, m_height - 1.0);
  for (size_t k = 0; k < nbOutliers; ++k) {
    const double u = uDist(m_rng);
    const double v = vDist(m_rng);
    mixed[order[k]].set_uv(u, v);
    flags[order[k]] = true;
  }

  // Shuffle so that outliers are not grouped, keeping each flag with its point.
  std::shuffle(order.begin(), order.end(), m_rng);
  std::vector<vpImagePoint> result(n);
  std::vector<bool> resultFlags(n);
  for (size_t k = 0; k < n; ++k) {
    result[k] = mixed[order[k]];
    resultFlags[k] = flags[order[k]];
  }
  if (isOutlier)
    *isOutlier = resultFlags;
  return result;
}

const vpImage<vpRGBa> &vpLaserConicSimulator::proceduralTexture()
{
  // The floor depends on the seed only (not on the draws made before), so that every frame of a sequence
  // rendered with one seed sees the same floor; it is cached for speed.
  if (m_texture.getSize() != 0 && m_textureSeed == m_seed)
    return m_texture;
  // Dark tiles of random grey with a fine grain: a dull floor on which the red laser stays visible.
  const unsigned int size = 1024, tile = 16;
  FastRandom random(0x5DEECE66DULL * (m_seed + 1));
  m_texture.resize(size, size);
  std::vector<int> tiles((size / tile) * (size / tile));
  for (int &t : tiles)
    t = 25 + static_cast<int>(random.next() % 46); // 25..70
  for (unsigned int i = 0; i < size; ++i) {
    for (unsigned int j = 0; j < size; ++j) {
      const int grain = static_cast<int>(random.next() % 17) - 8; // -8..8
      const int base = tiles[(i / tile) * (size / tile) + j / tile];
      const unsigned char g = static_cast<unsigned char>(std::min(255, std::max(0, base + grain)));
      m_texture[i][j] = vpRGBa(g, g, static_cast<unsigned char>(std::min(255, g + 3)), 255);
    }
  }
  m_textureSeed = m_seed;
  return m_texture;
}

void vpLaserConicSimulator::groundFootprint(double &cx, double &cy, double &half) const
{
  // Back-project the image corners on the ground (camera frame plane n.X + D = 0, D > 0).
  const vpPlane plane = getGroundPlane();
  const double n[3] = {plane.getA(), plane.getB(), plane.getC()}, D = plane.getD();
  const vpHomogeneousMatrix gMc = m_cMg.inverse();
  const double pixels[4][2] = {{0.0, 0.0}, {m_width - 1.0, 0.0}, {m_width - 1.0, m_height - 1.0}, {0.0, m_height - 1.0}};
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  bool allHit = true;
  for (const auto &pixel : pixels) {
    const double ray[3] = {(pixel[0] - m_cam.get_u0()) / m_cam.get_px(), (pixel[1] - m_cam.get_v0()) / m_cam.get_py(), 1.0};
    const double towards = n[0] * ray[0] + n[1] * ray[1] + n[2] * ray[2];
    if (!(towards < 0.0)) {
      allHit = false; // this corner sees the sky: the horizon is in the image
      break;
    }
    const double lambda = -D / towards;
    double P[3];
    for (unsigned int i = 0; i < 3; ++i)
      P[i] = gMc[i][0] * ray[0] * lambda + gMc[i][1] * ray[1] * lambda + gMc[i][2] * lambda + gMc[i][3];
    minX = std::min(minX, P[0]);
    maxX = std::max(maxX, P[0]);
    minY = std::min(minY, P[1]);
    maxY = std::max(maxY, P[1]);
  }
  const double maxHalf = 50.0 * D; // beyond, the ground is a few pixels wide per metre: plain far grey
  if (allHit) {
    cx = 0.5 * (minX + maxX);
    cy = 0.5 * (minY + maxY);
    half = std::min(maxHalf, 0.55 * std::max(maxX - minX, maxY - minY)); // 10 % margin
  } else {
    cx = gMc[0][3];
    cy = gMc[1][3];
    half = maxHalf;
  }
}

void vpLaserConicSimulator::renderGround(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture)
{
  const vpImage<vpRGBa> &tex = texture.getSize() == 0 ? proceduralTexture() : texture;
  double cx = 0.0, cy = 0.0, half = 0.0;
  groundFootprint(cx, cy, half);
  vpColVector X[4];
  const double corners[4][2] = {{cx - half, cy - half}, {cx + half, cy - half}, {cx + half, cy + half},
                                {cx - half, cy + half}};
  for (unsigned int k = 0; k < 4; ++k) {
    X[k].resize(3);
    X[k][0] = corners[k][0];
    X[k][1] = corners[k][1];
    X[k][2] = 0.0;
  }
  // vpImageSimulator draws one side of its rectangle only: order the corners so that this side faces the camera.
  vpColVector p[3];
  for (unsigned int k = 0; k < 3; ++k) {
    vpColVector Xh(4, 1.0);
    for (unsigned int i = 0; i < 3; ++i)
      Xh[i] = X[k][i];
    p[k] = (m_cMg * Xh).extract(0, 3);
  }
  const vpColVector faceNormal = vpColVector::crossProd(p[1] - p[0], p[2] - p[1]);
  if (vpColVector::dotProd(p[0], faceNormal) <= 0.0)
    std::swap(X[1], X[3]);

  vpImageSimulator ground(vpImageSimulator::COLORED);
  ground.init(tex, X);
  // Nearest texel: the optical blur smooths the texture anyway, at half the cost of bilinear interpolation.
  ground.setInterpolationType(vpImageSimulator::SIMPLE);
  ground.setCleanPreviousImage(true, vpColor(kFarGroundGrey, kFarGroundGrey, kFarGroundGrey));
  ground.setCameraPosition(m_cMg);
  I.resize(m_height, m_width);
  ground.getImage(I, m_cam);
}

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

void vpLaserConicSimulator::render(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture, double stripeWidth,
                                   double noise)
{
  checkCamera();
  if (!std::isfinite(stripeWidth) || stripeWidth <= 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the stripe width must be positive");
  if (!std::isfinite(noise) || noise < 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the sensor noise must be finite and >= 0");
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);

  // 1. Ground through vpImageSimulator.
  renderGround(I, texture);

  // 2. Laser: distance of the pixels near the trace to the exact image curve, Gaussian profile of that
  // distance (full width at half maximum stripeWidth), added as red light to the ground, in floating point.
  const double sigma = stripeWidth / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  const float radius = static_cast<float>(3.5 * sigma + 1.0);
  std::vector<float> dist2;
  traceDistanceMap(radius, dist2);
  cv::Mat image(H, W, CV_32FC3);
  const float inv2s2 = static_cast<float>(1.0 / (2.0 * sigma * sigma));
  const float r2 = radius * radius;
  for (int i = 0; i < H; ++i) {
    float *out = image.ptr<float>(i);
    const vpRGBa *in = I[static_cast<unsigned int>(i)];
    const float *d2 = &dist2[static_cast<size_t>(i) * W];
    for (int j = 0; j < W; ++j) {
      const float profile = d2[j] < r2 ? std::exp(-d2[j] * inv2s2) : 0.f;
      out[3 * j] = in[j].R + kLaserRgb[0] * profile;
      out[3 * j + 1] = in[j].G + kLaserRgb[1] * profile;
      out[3 * j + 2] = in[j].B + kLaserRgb[2] * profile;
    }
  }

  // 3. Optics: blur.
  cv::GaussianBlur(image, image, cv::Size(0, 0), kBlurSigma);

  // 4. Sensor: noise, rounding and saturation in one pass.
  const std::vector<float> &quantiles = normalQuantiles();
  FastRandom random((static_cast<uint64_t>(m_rng()) << 32) | m_rng());
  const float sensorSigma = static_cast<float>(noise);
  for (int i = 0; i < H; ++i) {
    const float *in = image.ptr<float>(i);
    vpRGBa *out = I[static_cast<unsigned int>(i)];
    for (int j = 0; j < W; ++j, in += 3) {
      float rgb[3] = {in[0], in[1], in[2]};
      if (sensorSigma > 0.f) {
        const uint64_t bits = random.next(); // 3 x 16 bits: one normal draw per channel
        for (int k = 0; k < 3; ++k)
          rgb[k] += sensorSigma * quantiles[(bits >> (16 * k)) & 0xFFFF];
      }
      unsigned char c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = static_cast<unsigned char>(std::min(255.f, std::max(0.f, rgb[k])) + 0.5f); // round to nearest
      out[j] = vpRGBa(c[0], c[1], c[2], 255);
    }
  }
}
