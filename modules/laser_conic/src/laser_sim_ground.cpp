/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  The ground of vpLaserConicSimulator::render(): what each pixel's ray hits on the plane Z = 0 of the ground
  frame (procedural floor, texture, chessboard, distractors and clutter) and how the ambient light and the
  lamp light it.
*/
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "laser_sim_floor.h"

namespace
{
// Grey level of the ground beyond the textured square.
const unsigned char kFarGroundGrey = 20;
// Bilinear texel of a texture at continuous texel coordinates (x along columns, y along rows), false outside.
bool sampleTexture(const vpImage<vpRGBa> &T, double x, double y, float rgb[3])
{
  const double fx = x - 0.5, fy = y - 0.5; // texel centres at half-integers
  if (!(x >= 0.0 && y >= 0.0 && x < T.getWidth() && y < T.getHeight()))
    return false;
  const int j0 = std::max(0, std::min(static_cast<int>(T.getWidth()) - 1, static_cast<int>(std::floor(fx))));
  const int i0 = std::max(0, std::min(static_cast<int>(T.getHeight()) - 1, static_cast<int>(std::floor(fy))));
  const int j1 = std::min(static_cast<int>(T.getWidth()) - 1, j0 + 1),
            i1 = std::min(static_cast<int>(T.getHeight()) - 1, i0 + 1);
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

// True when the ground point (X, Y) lies on the distractor. Called for every object at every pixel: squared
// distances, no std::hypot (its overflow guard costs more than the rest of the test).
bool onDistractor(const vpLaserConicSimulator::vpDistractor &d, double X, double Y)
{
  const double halfSize = 0.5 * d.size; // half side of a square, radius of a disc, half width of a line
  switch (d.shape) {
  case vpLaserConicSimulator::DISTRACTOR_RECTANGLE:
    return std::fabs(X - d.x) <= halfSize && std::fabs(Y - d.y) <= halfSize;
  case vpLaserConicSimulator::DISTRACTOR_LINE: {
    const double dx = d.x2 - d.x, dy = d.y2 - d.y, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::min(1.0, std::max(0.0, ((X - d.x) * dx + (Y - d.y) * dy) / len2)) : 0.0;
    const double ex = X - d.x - t * dx, ey = Y - d.y - t * dy;
    return ex * ex + ey * ey <= halfSize * halfSize;
  }
  default:
    return (X - d.x) * (X - d.x) + (Y - d.y) * (Y - d.y) <= halfSize * halfSize;
  }
}

// The distractors of the settings followed by the clutter: small red patches at ground positions drawn from
// the scene seed only (the same scene every frame).
std::vector<vpLaserConicSimulator::vpDistractor> sceneObjects(const vpLaserConicSimulator::vpRenderSettings &settings,
                                                              uint32_t sceneSeed)
{
  std::vector<vpLaserConicSimulator::vpDistractor> objects = settings.distractors;
  for (unsigned int k = 0; k < settings.clutter; ++k) {
    const uint32_t h1 = vsp::laser_sim_floor::hash(static_cast<int>(k), 11, sceneSeed),
                   h2 = vsp::laser_sim_floor::hash(static_cast<int>(k), 12, sceneSeed);
    vpLaserConicSimulator::vpDistractor d;
    d.shape = (h1 & 1) ? vpLaserConicSimulator::DISTRACTOR_DISC : vpLaserConicSimulator::DISTRACTOR_RECTANGLE;
    const double radius = settings.clutterRadius * std::sqrt(vsp::laser_sim_floor::unit(h1));
    const double angle = 2.0 * M_PI * vsp::laser_sim_floor::unit(h2);
    d.x = radius * std::cos(angle);
    d.y = radius * std::sin(angle);
    d.size = 0.01 + 0.03 * vsp::laser_sim_floor::unit(h1 >> 5);
    float c[3];
    vsp::laser_sim_floor::hsvToRgb(vsp::laser_sim_floor::unit(h2 >> 3) < 0.5f ? 355.f : 5.f,
                                   0.75f + 0.25f * vsp::laser_sim_floor::unit(h2 >> 9),
                                   0.45f + 0.4f * vsp::laser_sim_floor::unit(h2 >> 13), c);
    d.colour = vpRGBa(static_cast<unsigned char>(c[0]), static_cast<unsigned char>(c[1]),
                      static_cast<unsigned char>(c[2]), 255);
    objects.push_back(d);
  }
  return objects;
}

// Reflectance of a surface at the laser's wavelength: its red albedo (grey levels under ambient 1) over white.
inline float redReflectance(float redAlbedo) { return std::min(1.f, std::max(0.f, redAlbedo / 255.f)); }

// Phong reflection of the lamp at ground point (X, Y) seen from the camera centre C (ground frame): half vector
// of the directions to the camera and to the lamp, ground normal +Z.
float lampSpecular(const double C[3], const double lamp[3], double X, double Y, float specular, float gloss,
                   double shininess)
{
  double v[3] = {C[0] - X, C[1] - Y, C[2]}, l[3] = {lamp[0] - X, lamp[1] - Y, lamp[2]};
  const double nv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double nl = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
  const double h[3] = {v[0] / nv + l[0] / nl, v[1] / nv + l[1] / nl, std::fabs(v[2]) / nv + l[2] / nl};
  const double cosine = h[2] / std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  return specular * gloss * static_cast<float>(std::pow(std::max(0.0, cosine), shininess));
}
} // namespace

float vpLaserConicSimulator::chessboardAlbedo(int i, int j, const double R[3][3], const double C[3]) const
{
  // Average of 4 sub-pixel samples (rays interpolated between the pixel centres), on a rotated grid.
  const double sub[4][2] = {{-0.375, -0.125}, {0.125, -0.375}, {0.375, 0.125}, {-0.125, 0.375}};
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  const size_t k = static_cast<size_t>(i) * W + j;
  const double x = m_rayX[k], y = m_rayY[k];
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
  return 0.25f * sum;
}

void vpLaserConicSimulator::surfaceAlbedo(const vpRenderSettings &settings, uint32_t sceneSeed,
                                          const std::vector<vpDistractor> &objects, double X, double Y, int i, int j,
                                          const double R[3][3], const double C[3], float albedo[3], float &gloss) const
{
  vsp::laser_sim_floor::albedo(settings.floor, X, Y, sceneSeed, albedo, gloss);
  if (m_texture.image.getSize() != 0 &&
      sampleTexture(m_texture.image, (X - m_textureX0) / m_texelSize, (Y - m_textureY0) / m_texelSize, albedo))
    gloss = 0.2f;
  if (m_boardX != 0 && chessboardGrey(X, Y, m_boardX, m_boardY, m_boardSquare) >= 0.f) {
    albedo[0] = albedo[1] = albedo[2] = i >= 0 ? chessboardAlbedo(i, j, R, C)
                                               : chessboardGrey(X, Y, m_boardX, m_boardY, m_boardSquare);
    gloss = 0.15f;
  }
  for (const vpDistractor &o : objects)
    if (onDistractor(o, X, Y)) {
      albedo[0] = o.colour.R;
      albedo[1] = o.colour.G;
      albedo[2] = o.colour.B;
      gloss = 0.3f;
    }
}

float vpLaserConicSimulator::groundReflectance(const vpRenderSettings &settings, double X, double Y) const
{
  const uint32_t sceneSeed = settings.sceneSeed >= 0 ? static_cast<uint32_t>(settings.sceneSeed) : m_seed;
  float albedo[3], gloss = 0.f;
  surfaceAlbedo(settings, sceneSeed, sceneObjects(settings, sceneSeed), X, Y, -1, -1, nullptr, nullptr, albedo, gloss);
  return redReflectance(albedo[0]);
}

void vpLaserConicSimulator::renderGround(float *rgb, const vpRenderSettings &settings,
                                         const vpImage<vpRGBa> *stretchedTexture, float *reflectance)
{
  const int W = static_cast<int>(m_width), H = static_cast<int>(m_height);
  const vpHomogeneousMatrix gMc = m_cMg.inverse();
  const double R[3][3] = {{gMc[0][0], gMc[0][1], gMc[0][2]},
                          {gMc[1][0], gMc[1][1], gMc[1][2]},
                          {gMc[2][0], gMc[2][1], gMc[2][2]}};
  const double C[3] = {gMc[0][3], gMc[1][3], gMc[2][3]}; // camera centre in the ground frame
  const double maxDistance = 50.0 * std::fabs(C[2]);
  const double maxDistance2 = maxDistance * maxDistance;

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
  const std::vector<vpDistractor> objects = sceneObjects(settings, sceneSeed);
  const float ambient = static_cast<float>(settings.ambient), specular = static_cast<float>(settings.specular);
  const double lamp[3] = {settings.lampX, settings.lampY, settings.lampZ};

  for (int i = 0; i < H; ++i) {
    for (int j = 0; j < W; ++j) {
      const size_t k = static_cast<size_t>(i) * W + j;
      float *out = rgb + 3 * k;
      out[0] = out[1] = out[2] = kFarGroundGrey;
      if (reflectance != nullptr)
        reflectance[k] = redReflectance(kFarGroundGrey);
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
      if ((X - C[0]) * (X - C[0]) + (Y - C[1]) * (Y - C[1]) > maxDistance2)
        continue; // a few pixels per metre: plain far grey

      float albedo[3], gloss = 0.f;
      if (stretchedTexture != nullptr) {
        if (!sampleTexture(*stretchedTexture, (X - stretchX0) / stretchTexel, (Y - stretchY0) / stretchTexel, albedo))
          continue;
        out[0] = albedo[0];
        out[1] = albedo[1];
        out[2] = albedo[2];
        if (reflectance != nullptr)
          reflectance[k] = redReflectance(albedo[0]);
        continue; // historical path: the texture as is, no lighting
      }
      surfaceAlbedo(settings, sceneSeed, objects, X, Y, i, j, R, C, albedo, gloss);
      const float spec =
          specular > 0.f && gloss > 0.f ? lampSpecular(C, lamp, X, Y, specular, gloss, settings.shininess) : 0.f;
      for (int c = 0; c < 3; ++c)
        out[c] = ambient * albedo[c] + spec;
      if (reflectance != nullptr)
        reflectance[k] = redReflectance(albedo[0]);
    }
  }
}
