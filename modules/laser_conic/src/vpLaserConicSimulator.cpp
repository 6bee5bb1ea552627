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
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/laser_conic/vpLaserConicException.h>

#include "laser_lens.h"
#include "laser_pose_check.h"
#include "laser_sim_floor.h"

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
    m_seed(0), m_rng(0), m_texture(), m_texelSize(1.0), m_textureX0(0.0), m_textureY0(0.0), m_boardX(0),
    m_boardY(0), m_boardSquare(0.0), m_rayX(), m_rayY(), m_rayCam(), m_rayValid()
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
  if (!vsp::laser_pose_check::isFinitePose(cMl))
    throw vpLaserConicException(vpLaserConicException::badLaserError,
                                "vpLaserConicSimulator: the laser pose is not a finite rigid transformation");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
}

void vpLaserConicSimulator::setGroundPose(const vpHomogeneousMatrix &cMg)
{
  if (!vsp::laser_pose_check::isFinitePose(cMg))
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
  // The pixel the estimators will read back onto this ray (vpPixelMeterConversion's model, inverted).
  return vsp::laser_lens::pixelOfNormalized(m_cam, P[0] / P[2], P[1] / P[2], u, v);
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

void vpLaserConicSimulator::setGroundTexture(const vpImage<vpRGBa> &texture, double metresPerTexel, double x0,
                                             double y0)
{
  if (!std::isfinite(metresPerTexel) || metresPerTexel <= 0.0 || !std::isfinite(x0) || !std::isfinite(y0))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the texel size must be positive and the origin finite");
  m_texture.image = texture;
  m_texelSize = metresPerTexel;
  m_textureX0 = x0;
  m_textureY0 = y0;
}

void vpLaserConicSimulator::setGroundChessboard(unsigned int squaresX, unsigned int squaresY, double squareSize)
{
  if (squaresX == 0) {
    m_boardX = m_boardY = 0;
    return;
  }
  if (squaresY == 0 || !std::isfinite(squareSize) || squareSize <= 0.0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the chessboard needs squares of positive size");
  m_boardX = squaresX;
  m_boardY = squaresY;
  m_boardSquare = squareSize;
}

vpCameraParameters vpLaserConicSimulator::fitInverseDistortion(const vpCameraParameters &cam, unsigned int width,
                                                               unsigned int height)
{
  if (cam.get_projModel() != vpCameraParameters::perspectiveProjWithDistortion || cam.get_kdu() == 0.0)
    return cam;
  // Pixel-to-metre model r = rd (1 + kdu rd^2) (rd: distorted normalized radius); the metre-to-pixel model
  // of vpMeterPixelConversion is rd = r (1 + kud r^2): least squares on kud over the radii of the image.
  const double kdu = cam.get_kdu();
  const double du = std::max(cam.get_u0(), width - 1.0 - cam.get_u0()) / cam.get_px();
  const double dv = std::max(cam.get_v0(), height - 1.0 - cam.get_v0()) / cam.get_py();
  double rdMax = std::hypot(du, dv);
  if (kdu < 0.0) // r peaks at rd* = 1 / sqrt(-3 kdu)
    rdMax = std::min(rdMax, 0.98 / std::sqrt(-3.0 * kdu));
  double num = 0.0, den = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const double rd = rdMax * k / 200.0, r = rd * (1.0 + kdu * rd * rd);
    const double a = r * r * r, b = rd - r; // rd - r = kud r^3
    num += a * b;
    den += a * a;
  }
  return vpCameraParameters(cam.get_px(), cam.get_py(), cam.get_u0(), cam.get_v0(), num / den, kdu);
}

void vpLaserConicSimulator::updateRayMap()
{
  const size_t n = static_cast<size_t>(m_width) * m_height;
  if (m_rayX.size() == n && m_rayCam == m_cam)
    return;
  m_rayX.resize(n);
  m_rayY.resize(n);
  m_rayValid.assign(n, 1);
  // The pixel-to-metre conversion of the estimators is the rendering model itself: exact by construction.
  for (unsigned int i = 0; i < m_height; ++i)
    for (unsigned int j = 0; j < m_width; ++j) {
      const size_t k = static_cast<size_t>(i) * m_width + j;
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(m_cam, static_cast<double>(j), static_cast<double>(i), x, y);
      m_rayX[k] = static_cast<float>(x);
      m_rayY[k] = static_cast<float>(y);
      m_rayValid[k] = std::isfinite(x) && std::isfinite(y);
    }
  m_rayCam = m_cam;
}

void vpLaserConicSimulator::groundFootprint(double &cx, double &cy, double &half) const
{
  // Back-project the image corners on the ground (camera frame plane n.X + D = 0, D > 0).
  const vpPlane plane = getGroundPlane();
  const double n[3] = {plane.getA(), plane.getB(), plane.getC()}, D = plane.getD();
  const vpHomogeneousMatrix gMc = m_cMg.inverse();
  const unsigned int corners[4][2] = {{0, 0}, {m_width - 1, 0}, {m_width - 1, m_height - 1}, {0, m_height - 1}};
  double minX = std::numeric_limits<double>::infinity(), minY = minX, maxX = -minX, maxY = -minX;
  bool allHit = true;
  for (const auto &corner : corners) {
    const size_t k = static_cast<size_t>(corner[1]) * m_width + corner[0];
    const double ray[3] = {m_rayX[k], m_rayY[k], 1.0};
    const double towards = n[0] * ray[0] + n[1] * ray[1] + n[2] * ray[2];
    if (!m_rayValid[k] || !(towards < 0.0)) {
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

namespace
{
// Bilinear texel of a texture at continuous texel coordinates (x along columns, y along rows), false outside.
bool sampleTexture(const vpImage<vpRGBa> &T, double x, double y, float rgb[3])
{
  const double fx = x - 0.5, fy = y - 0.5; // texel centres at half-integers
  if (!(x >= 0.0 && y >= 0.0 && x < T.getWidth() && y < T.getHeight()))
    return false;
  const int j0 = std::max(0, std::min(static_cast<int>(T.getWidth()) - 1, static_cast<int>(std::floor(fx))));
  const int i0 = std::max(0, std::min(static_cast<int>(T.getHeight()) - 1, static_cast<int>(std::floor(fy))));
  const int j1 = std::min(static_cast<int>(T.getWidth()) - 1, j0 + 1), i1 = std::min(static_cast<int>(T.getHeight()) - 1, i0 + 1);
  const float tx = static_cast<float>(std::min(1.0, std::max(0.0, fx - j0)));
  const float ty = static_cast<float>(std::min(1.0, std::max(0.0, fy - i0)));
  const vpRGBa &a = T[i0][j0], &b = T[i0][j1], &c = T[i1][j0], &d = T[i1][j1];
  rgb[0] = (a.R * (1 - tx) + b.R * tx) * (1 - ty) + (c.R * (1 - tx) + d.R * tx) * ty;
  rgb[1] = (a.G * (1 - tx) + b.G * tx) * (1 - ty) + (c.G * (1 - tx) + d.G * tx) * ty;
  rgb[2] = (a.B * (1 - tx) + b.B * tx) * (1 - ty) + (c.B * (1 - tx) + d.B * tx) * ty;
  return true;
}

// Chessboard of the simulator: -1 outside the paper, else the albedo grey (black squares, white squares/paper).
float chessboardGrey(double X, double Y, unsigned int nx, unsigned int ny, double s)
{
  if (X < -s || Y < -s || X > (nx + 1) * s || Y > (ny + 1) * s)
    return -1.f;
  if (X < 0.0 || Y < 0.0 || X >= nx * s || Y >= ny * s)
    return 215.f; // white paper around the board
  const long kx = static_cast<long>(std::floor(X / s)), ky = static_cast<long>(std::floor(Y / s));
  return ((kx + ky) % 2 == 0) ? 28.f : 215.f;
}

// True when the ground point (X, Y) lies on the distractor.
bool onDistractor(const vpLaserConicSimulator::vpDistractor &d, double X, double Y)
{
  switch (d.shape) {
  case vpLaserConicSimulator::DISTRACTOR_RECTANGLE:
    return std::fabs(X - d.x) <= 0.5 * d.size && std::fabs(Y - d.y) <= 0.5 * d.size;
  case vpLaserConicSimulator::DISTRACTOR_LINE: {
    const double dx = d.x2 - d.x, dy = d.y2 - d.y, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::min(1.0, std::max(0.0, ((X - d.x) * dx + (Y - d.y) * dy) / len2)) : 0.0;
    return std::hypot(X - d.x - t * dx, Y - d.y - t * dy) <= 0.5 * d.size;
  }
  default:
    return std::hypot(X - d.x, Y - d.y) <= 0.5 * d.size;
  }
}
} // namespace

void vpLaserConicSimulator::renderGround(float *rgb, const vpRenderSettings &settings,
                                         const vpImage<vpRGBa> *stretchedTexture)
{
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  const vpHomogeneousMatrix gMc = m_cMg.inverse();
  const double R[3][3] = {{gMc[0][0], gMc[0][1], gMc[0][2]}, {gMc[1][0], gMc[1][1], gMc[1][2]},
                          {gMc[2][0], gMc[2][1], gMc[2][2]}};
  const double C[3] = {gMc[0][3], gMc[1][3], gMc[2][3]}; // camera centre in the ground frame
  const double maxDistance = 50.0 * std::fabs(C[2]);

  // Texture of render(I, texture): stretched over the footprint square (historical behaviour).
  double stretchX0 = 0.0, stretchY0 = 0.0, stretchTexel = 1.0;
  if (stretchedTexture != nullptr) {
    double cx = 0.0, cy = 0.0, half = 0.0;
    groundFootprint(cx, cy, half);
    stretchX0 = cx - half;
    stretchY0 = cy - half;
    stretchTexel = 2.0 * half / std::max(stretchedTexture->getWidth(), stretchedTexture->getHeight());
  }

  const uint32_t sceneSeed = settings.sceneSeed >= 0 ? static_cast<uint32_t>(settings.sceneSeed) : m_seed;
  // Clutter: small red patches at ground positions drawn from the seed only (the same scene every frame).
  std::vector<vpDistractor> objects = settings.distractors;
  for (unsigned int k = 0; k < settings.clutter; ++k) {
    const uint32_t h1 = vsp::laser_sim_floor::hash(static_cast<int>(k), 11, sceneSeed),
                   h2 = vsp::laser_sim_floor::hash(static_cast<int>(k), 12, sceneSeed);
    vpDistractor d;
    d.shape = (h1 & 1) ? DISTRACTOR_DISC : DISTRACTOR_RECTANGLE;
    const double radius = settings.clutterRadius * std::sqrt(vsp::laser_sim_floor::unit(h1));
    const double angle = 2.0 * M_PI * vsp::laser_sim_floor::unit(h2);
    d.x = radius * std::cos(angle);
    d.y = radius * std::sin(angle);
    d.size = 0.01 + 0.03 * vsp::laser_sim_floor::unit(h1 >> 5);
    float c[3];
    vsp::laser_sim_floor::hsvToRgb(vsp::laser_sim_floor::unit(h2 >> 3) < 0.5f ? 355.f : 5.f, 0.75f + 0.25f * vsp::laser_sim_floor::unit(h2 >> 9),
                              0.45f + 0.4f * vsp::laser_sim_floor::unit(h2 >> 13), c);
    d.colour = vpRGBa(static_cast<unsigned char>(c[0]), static_cast<unsigned char>(c[1]),
                      static_cast<unsigned char>(c[2]), 255);
    objects.push_back(d);
  }

  const float ambient = static_cast<float>(settings.ambient), specular = static_cast<float>(settings.specular);
  const double lamp[3] = {settings.lampX, settings.lampY, settings.lampZ};
  // Sub-pixel sample offsets of the anti-aliased chessboard (rotated grid).
  const double sub[4][2] = {{-0.375, -0.125}, {0.125, -0.375}, {0.375, 0.125}, {-0.125, 0.375}};

  for (int i = 0; i < H; ++i) {
    for (int j = 0; j < W; ++j) {
      const size_t k = static_cast<size_t>(i) * W + j;
      float *out = rgb + 3 * k;
      out[0] = out[1] = out[2] = kFarGroundGrey;
      if (!m_rayValid[k])
        continue;
      // Ray of the pixel in the ground frame and its hit on Z = 0.
      const double x = m_rayX[k], y = m_rayY[k];
      const double d[3] = {R[0][0] * x + R[0][1] * y + R[0][2], R[1][0] * x + R[1][1] * y + R[1][2],
                           R[2][0] * x + R[2][1] * y + R[2][2]};
      const double lambda = -C[2] / d[2];
      if (!(lambda > 0.0) || !std::isfinite(lambda))
        continue; // the ray goes to the sky
      const double X = C[0] + lambda * d[0], Y = C[1] + lambda * d[1];
      if (std::hypot(X - C[0], Y - C[1]) > maxDistance)
        continue; // a few pixels per metre: plain far grey

      float albedo[3], gloss = 0.f;
      if (stretchedTexture != nullptr) {
        if (!sampleTexture(*stretchedTexture, (X - stretchX0) / stretchTexel, (Y - stretchY0) / stretchTexel, albedo))
          continue;
        out[0] = albedo[0];
        out[1] = albedo[1];
        out[2] = albedo[2];
        continue; // historical path: the texture as is, no lighting
      }
      vsp::laser_sim_floor::albedo(settings.floor, X, Y, sceneSeed, albedo, gloss);
      if (m_texture.image.getSize() != 0 &&
          sampleTexture(m_texture.image, (X - m_textureX0) / m_texelSize, (Y - m_textureY0) / m_texelSize, albedo))
        gloss = 0.2f;
      if (m_boardX != 0 && chessboardGrey(X, Y, m_boardX, m_boardY, m_boardSquare) >= 0.f) {
        // Average of 4 sub-pixel samples (rays interpolated between the pixel centres).
        float sum = 0.f;
        for (const auto &o : sub) {
          const int j2 = std::min(W - 1, std::max(0, o[0] < 0 ? j - 1 : j + 1));
          const int i2 = std::min(H - 1, std::max(0, o[1] < 0 ? i - 1 : i + 1));
          const size_t kj = static_cast<size_t>(i) * W + j2, ki = static_cast<size_t>(i2) * W + j;
          const double wx = std::fabs(o[0]), wy = std::fabs(o[1]);
          const double xs = x + wx * (m_rayX[kj] - x) + wy * (m_rayX[ki] - x);
          const double ys = y + wx * (m_rayY[kj] - y) + wy * (m_rayY[ki] - y);
          const double ds[3] = {R[0][0] * xs + R[0][1] * ys + R[0][2], R[1][0] * xs + R[1][1] * ys + R[1][2],
                                R[2][0] * xs + R[2][1] * ys + R[2][2]};
          const double ls = -C[2] / ds[2];
          const float g = chessboardGrey(C[0] + ls * ds[0], C[1] + ls * ds[1], m_boardX, m_boardY, m_boardSquare);
          sum += g >= 0.f ? g : 215.f;
        }
        albedo[0] = albedo[1] = albedo[2] = 0.25f * sum;
        gloss = 0.15f;
      }
      for (const vpDistractor &o : objects)
        if (onDistractor(o, X, Y)) {
          albedo[0] = o.colour.R;
          albedo[1] = o.colour.G;
          albedo[2] = o.colour.B;
          gloss = 0.3f;
        }
      float spec = 0.f;
      if (specular > 0.f && gloss > 0.f) {
        // Phong: half vector of the directions to the camera and to the lamp, ground normal +Z.
        double v[3] = {C[0] - X, C[1] - Y, C[2]}, l[3] = {lamp[0] - X, lamp[1] - Y, lamp[2]};
        const double nv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const double nl = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        const double h[3] = {v[0] / nv + l[0] / nl, v[1] / nv + l[1] / nl, std::fabs(v[2]) / nv + l[2] / nl};
        const double cosine = h[2] / std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        spec = specular * gloss * static_cast<float>(std::pow(std::max(0.0, cosine), settings.shininess));
      }
      for (int c = 0; c < 3; ++c)
        out[c] = ambient * albedo[c] + spec;
    }
  }
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

void vpLaserConicSimulator::render(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture, double stripeWidth,
                                   double noise)
{
  vpRenderSettings settings;
  settings.stripeWidth = stripeWidth;
  settings.noise = noise;
  if (texture.getSize() == 0) {
    render(I, settings);
    return;
  }
  // Historical path: the given texture stretched over the footprint (no floor, chessboard or lighting).
  renderImpl(I, settings, &texture);
}

void vpLaserConicSimulator::render(vpImage<vpRGBa> &I, const vpRenderSettings &settings)
{
  renderImpl(I, settings, nullptr);
}

void vpLaserConicSimulator::renderImpl(vpImage<vpRGBa> &I, const vpRenderSettings &s,
                                       const vpImage<vpRGBa> *stretchedTexture)
{
  checkCamera();
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto nonNegative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(s.stripeWidth) || !positive(s.bloomWidth) || !positive(s.shininess))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: the stripe width, bloom width and shininess must be positive");
  if (!nonNegative(s.noise) || !nonNegative(s.ambient) || !nonNegative(s.specular) || !nonNegative(s.laserPower) ||
      !nonNegative(s.whiteCore) || !nonNegative(s.bloom) || !nonNegative(s.blur) || !nonNegative(s.motionBlurLength) ||
      !std::isfinite(s.motionBlurAngle) || !nonNegative(s.clutterRadius) || !std::isfinite(s.lampX) ||
      !std::isfinite(s.lampY) || !std::isfinite(s.lampZ))
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicSimulator: a render setting is negative or not finite (sensor noise, "
                                "ambient, specular, laser power, white core, bloom, blur, clutter radius, lamp)");
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  updateRayMap();

  // 1. Ground, 2. laser, in floating point (linear light before the sensor clips it).
  cv::Mat image(H, W, CV_32FC3);
  float *rgb = image.ptr<float>(0);
  renderGround(rgb, s, stretchedTexture);
  if (s.laserOn)
    renderLaser(rgb, s);

  // 3. Objects in front of the ground hide it and the laser.
  for (const std::vector<vpImagePoint> &polygon : s.occluders) {
    if (polygon.size() < 3)
      continue;
    std::vector<cv::Point> pts;
    pts.reserve(polygon.size());
    for (const vpImagePoint &p : polygon)
      pts.push_back(cv::Point(static_cast<int>(std::lround(p.get_u())), static_cast<int>(std::lround(p.get_v()))));
    const std::vector<std::vector<cv::Point> > polys(1, pts);
    cv::fillPoly(image, polys, cv::Scalar(s.occluderColour.R, s.occluderColour.G, s.occluderColour.B));
  }

  // 4. Optics and motion: blur, linear motion blur.
  if (s.blur > 0.0)
    cv::GaussianBlur(image, image, cv::Size(0, 0), s.blur);
  if (s.motionBlurLength >= 1.0) {
    const int half = static_cast<int>(std::ceil(0.5 * s.motionBlurLength));
    cv::Mat kernel = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    const int samples = 8 * (2 * half + 1);
    for (int k = 0; k < samples; ++k) { // the segment sampled finely, splatted bilinearly
      const double t = (k + 0.5) / samples - 0.5;
      const double u = half + t * s.motionBlurLength * std::cos(s.motionBlurAngle);
      const double v = half + t * s.motionBlurLength * std::sin(s.motionBlurAngle);
      const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
      const float fu = static_cast<float>(u - u0), fv = static_cast<float>(v - v0);
      kernel.at<float>(v0, u0) += (1 - fu) * (1 - fv);
      kernel.at<float>(v0, std::min(2 * half, u0 + 1)) += fu * (1 - fv);
      kernel.at<float>(std::min(2 * half, v0 + 1), u0) += (1 - fu) * fv;
      kernel.at<float>(std::min(2 * half, v0 + 1), std::min(2 * half, u0 + 1)) += fu * fv;
    }
    kernel /= cv::sum(kernel)[0];
    cv::filter2D(image, image, -1, kernel, cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
  }

  // 5. Sensor: noise, rounding and saturation in one pass.
  I.resize(m_height, m_width);
  const std::vector<float> &quantiles = normalQuantiles();
  FastRandom random((static_cast<uint64_t>(m_rng()) << 32) | m_rng());
  const float sensorSigma = static_cast<float>(s.noise);
  for (int i = 0; i < H; ++i) {
    const float *in = image.ptr<float>(i);
    vpRGBa *out = I[static_cast<unsigned int>(i)];
    for (int j = 0; j < W; ++j, in += 3) {
      float c3[3] = {in[0], in[1], in[2]};
      if (sensorSigma > 0.f) {
        const uint64_t bits = random.next(); // 3 x 16 bits: one normal draw per channel
        for (int k = 0; k < 3; ++k)
          c3[k] += sensorSigma * quantiles[(bits >> (16 * k)) & 0xFFFF];
      }
      unsigned char c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = static_cast<unsigned char>(std::min(255.f, std::max(0.f, c3[k])) + 0.5f); // round to nearest
      out[j] = vpRGBa(c[0], c[1], c[2], 255);
    }
  }
}
