/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  vpLaserConicSimulator: the rig's geometry (settings, cone rays on the ground, projection), trace points with
  noise and outliers, and the render() pipeline. The ground is drawn in laser_sim_ground.cpp, the laser light in
  laser_sim_stripe.cpp, the optics and the sensor in laser_sim_sensor.cpp.
*/
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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
#include "laser_sim_sensor.h"
#include "laser_value_check.h"

using vsp::laser_value_check::require;
using vsp::laser_value_check::requireNonNegative;

vpLaserConicSimulator::vpLaserConicSimulator()
  : m_cam(), m_width(0), m_height(0), m_openingAngle(34.0 * M_PI / 180.0), m_cMl(), m_cMg(0, 0, 1, 0, 0, 0), m_seed(0),
    m_rng(0), m_texture(), m_texelSize(1.0), m_textureX0(0.0), m_textureY0(0.0), m_boardX(0), m_boardY(0),
    m_boardSquare(0.0), m_rayX(), m_rayY(), m_rayCam(), m_rayValid()
{
}

void vpLaserConicSimulator::setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height)
{
  vsp::laser_value_check::requireUsableCamera(cam, "vpLaserConicSimulator");
  require(width > 0 && height > 0, "vpLaserConicSimulator: empty image size", vpLaserConicException::badCameraError);
  m_cam = cam;
  m_width = width;
  m_height = height;
}

void vpLaserConicSimulator::setLaser(double openingAngle, const vpHomogeneousMatrix &cMl)
{
  vsp::laser_value_check::requireOpeningAngle(openingAngle, "vpLaserConicSimulator");
  vsp::laser_value_check::requireLaserPose(cMl, "vpLaserConicSimulator");
  m_openingAngle = openingAngle;
  m_cMl = cMl;
}

void vpLaserConicSimulator::setGroundPose(const vpHomogeneousMatrix &cMg)
{
  require(vsp::laser_pose_check::isFinitePose(cMg),
          "vpLaserConicSimulator: the ground pose is not a finite rigid transformation");
  // Signed distance of the camera centre to the plane Z = 0 of g.
  const double distance = -(cMg[0][2] * cMg[0][3] + cMg[1][2] * cMg[1][3] + cMg[2][2] * cMg[2][3]);
  require(std::fabs(distance) >= 1e-9, "vpLaserConicSimulator: the camera centre lies on the ground plane");
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
  require(m_width > 0 && m_height > 0, "vpLaserConicSimulator: call setCamera() before simulating images",
          vpLaserConicException::badCameraError);
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
  requireNonNegative(roughness, "vpLaserConicSimulator: the ground roughness must be finite and >= 0");
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
  requireNonNegative(sigma, "vpLaserConicSimulator: the noise standard deviation must be finite and >= 0");
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
  require(ratio >= 0.0 && ratio <= 1.0, "vpLaserConicSimulator: the outlier ratio must be in [0, 1]");
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
  require(std::isfinite(metresPerTexel) && metresPerTexel > 0.0 && std::isfinite(x0) && std::isfinite(y0),
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
  require(squaresY > 0 && std::isfinite(squareSize) && squareSize > 0.0,
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

void vpLaserConicSimulator::render(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture, double stripeWidth, double noise)
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

void vpLaserConicSimulator::checkSettings(const vpRenderSettings &s)
{
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto nonNegative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require(positive(s.stripeWidth) && positive(s.bloomWidth) && positive(s.shininess),
          "vpLaserConicSimulator: the stripe width, bloom width and shininess must be positive");
  require(nonNegative(s.noise) && nonNegative(s.ambient) && nonNegative(s.specular) && nonNegative(s.laserPower) &&
              nonNegative(s.whiteCore) && nonNegative(s.bloom) && nonNegative(s.blur) &&
              nonNegative(s.motionBlurLength) && std::isfinite(s.motionBlurAngle) && nonNegative(s.clutterRadius) &&
              std::isfinite(s.lampX) && std::isfinite(s.lampY) && std::isfinite(s.lampZ),
          "vpLaserConicSimulator: a render setting is negative or not finite (sensor noise, ambient, specular, laser "
          "power, white core, bloom, blur, clutter radius, lamp)");
  require(nonNegative(s.distanceFalloff) && nonNegative(s.stripeFarFraction) && s.stripeFarFraction < 1.0,
          "vpLaserConicSimulator: the distance fall-off must be finite and >= 0, the stripe's far fraction in [0, 1)");
  require(s.jpegQuality >= 0 && s.jpegQuality <= 100,
          "vpLaserConicSimulator: the JPEG quality must be in [1, 100] (0: no compression)");
}

namespace
{
// Objects in front of the ground (image polygons) hide it and the laser.
void drawOccluders(cv::Mat &image, const std::vector<std::vector<vpImagePoint> > &occluders, const vpRGBa &colour)
{
  for (const std::vector<vpImagePoint> &polygon : occluders) {
    if (polygon.size() < 3)
      continue;
    std::vector<cv::Point> pts;
    pts.reserve(polygon.size());
    for (const vpImagePoint &p : polygon)
      pts.push_back(cv::Point(static_cast<int>(std::lround(p.get_u())), static_cast<int>(std::lround(p.get_v()))));
    const std::vector<std::vector<cv::Point> > polys(1, pts);
    cv::fillPoly(image, polys, cv::Scalar(colour.R, colour.G, colour.B));
  }
}
} // namespace

void vpLaserConicSimulator::renderImpl(vpImage<vpRGBa> &I, const vpRenderSettings &s,
                                       const vpImage<vpRGBa> *stretchedTexture)
{
  checkCamera();
  checkSettings(s);
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  updateRayMap();

  // 1. Ground, 2. laser, in floating point (linear light before the sensor clips it).
  cv::Mat image(H, W, CV_32FC3);
  float *rgb = image.ptr<float>(0);
  std::vector<float> reflectance(s.reflectanceScaled ? static_cast<size_t>(W) * H : 0);
  renderGround(rgb, s, stretchedTexture, s.reflectanceScaled ? reflectance.data() : nullptr);
  if (s.laserOn)
    renderLaser(rgb, s, s.reflectanceScaled ? reflectance.data() : nullptr);
  // 3. Objects in front of the ground, 4. optics and motion, 5. sensor noise, rounding and saturation.
  drawOccluders(image, s.occluders, s.occluderColour);
  vsp::laser_sim_sensor::applyOptics(image, s.blur, s.motionBlurLength, s.motionBlurAngle);
  vsp::laser_sim_sensor::expose(image, s.noise, (static_cast<uint64_t>(m_rng()) << 32) | m_rng(), I);
  // 6. What the camera streams.
  if (s.jpegQuality > 0)
    vsp::laser_sim_sensor::compressJpeg(I, s.jpegQuality);
}
