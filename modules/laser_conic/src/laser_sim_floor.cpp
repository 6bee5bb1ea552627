/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "laser_sim_floor.h"

#include <algorithm>
#include <cmath>

#include <visp3/laser_conic/vpLaserConicSimulator.h>

namespace vsp::laser_sim_floor
{
namespace
{
inline int cell(double x, double size) { return static_cast<int>(std::floor(x / size)); }

// Smooth value noise in [0, 1): bilinear interpolation of random values on a lattice of spacing `size`.
float valueNoise(double X, double Y, double size, uint32_t seed)
{
  const double fx = X / size, fy = Y / size;
  const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
  const float tx = static_cast<float>(fx - ix), ty = static_cast<float>(fy - iy);
  const float a = unit(hash(ix, iy, seed)), b = unit(hash(ix + 1, iy, seed)), c = unit(hash(ix, iy + 1, seed)),
              d = unit(hash(ix + 1, iy + 1, seed));
  const float sx = tx * tx * (3.f - 2.f * tx), sy = ty * ty * (3.f - 2.f * ty); // smoothstep: no lattice seams
  return (a * (1.f - sx) + b * sx) * (1.f - sy) + (c * (1.f - sx) + d * sx) * sy;
}

// Grain of 2 mm texels in [-1, 1).
inline float grain(double X, double Y, uint32_t seed)
{
  return 2.f * unit(hash(cell(X, 0.002), cell(Y, 0.002), seed ^ 0xA5A5u)) - 1.f;
}

void darkTiles(double X, double Y, uint32_t seed, float rgb[3], float &gloss)
{
  const float base = 25.f + 46.f * unit(hash(cell(X, 0.03), cell(Y, 0.03), seed));
  const float g = std::floor(base) + std::round(8.f * grain(X, Y, seed));
  rgb[0] = g;
  rgb[1] = g;
  rgb[2] = g + 3.f;
  gloss = 0.3f;
}

void brightGrey(double X, double Y, uint32_t seed, float rgb[3], float &gloss)
{
  // Concrete: large soft stains and a finer mottling over a mid grey, a fine grain on top.
  const float v =
      45.f + 40.f * valueNoise(X, Y, 0.25, seed) + 20.f * valueNoise(X, Y, 0.04, seed + 1) + 6.f * grain(X, Y, seed);
  rgb[0] = v + 2.f;
  rgb[1] = v;
  rgb[2] = v - 2.f;
  gloss = 0.2f;
}

void mosaic(double X, double Y, uint32_t seed, float rgb[3], float &gloss)
{
  // Voronoi patches around jittered points of a 9 cm lattice; grout where two patches meet.
  const double size = 0.09;
  const int cx = cell(X, size), cy = cell(Y, size);
  // Squared distances while ranking the nine points (the floor's hot loop: one square root per pixel
  // instead of nine calls to std::hypot, which guards against overflow these distances cannot reach).
  double best = 1e30, second = 1e30;
  uint32_t bestHash = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const uint32_t h = hash(cx + dx, cy + dy, seed);
      const double px = (cx + dx + 0.15 + 0.7 * unit(h)) * size, py = (cy + dy + 0.15 + 0.7 * unit(h >> 7)) * size;
      const double d2 = (X - px) * (X - px) + (Y - py) * (Y - py);
      if (d2 < best) {
        second = best;
        best = d2;
        bestHash = h;
      } else if (d2 < second)
        second = d2;
    }
  if (std::sqrt(second) - std::sqrt(best) < 0.003) { // grout line, 3 mm wide
    rgb[0] = rgb[1] = rgb[2] = 45.f;
    gloss = 0.1f;
    return;
  }
  // Warm palette: hues from red-brown to ochre (some brick reds close to the laser's hue).
  const float r1 = unit(hash(static_cast<int>(bestHash), 1, seed)),
              r2 = unit(hash(static_cast<int>(bestHash), 2, seed)),
              r3 = unit(hash(static_cast<int>(bestHash), 3, seed));
  const float hue = r1 < 0.15f ? 350.f + 10.f * r1 / 0.15f : 45.f * (r1 - 0.15f) / 0.85f;
  hsvToRgb(hue, 0.3f + 0.5f * r2, (70.f + 140.f * r3) / 255.f, rgb);
  const float gr = 5.f * grain(X, Y, seed);
  for (int k = 0; k < 3; ++k)
    rgb[k] += gr;
  gloss = 0.6f;
}

void whiteTiles(double X, double Y, uint32_t seed, float rgb[3], float &gloss)
{
  const double size = 0.15, grout = 0.004;
  const double fx = X / size - std::floor(X / size), fy = Y / size - std::floor(Y / size);
  if (fx * size < grout || fy * size < grout) {
    rgb[0] = rgb[1] = rgb[2] = 125.f;
    gloss = 0.1f;
    return;
  }
  const float v = 200.f + 30.f * unit(hash(cell(X, size), cell(Y, size), seed)) + 4.f * grain(X, Y, seed);
  rgb[0] = v;
  rgb[1] = v;
  rgb[2] = v + 2.f;
  gloss = 1.0f;
}
} // namespace

void hsvToRgb(float hue, float saturation, float value, float rgb[3])
{
  const float h = std::fmod(std::fmod(hue, 360.f) + 360.f, 360.f) / 60.f;
  const int sector = static_cast<int>(h);
  const float f = h - sector, v = 255.f * value;
  const float p = v * (1.f - saturation), q = v * (1.f - saturation * f), t = v * (1.f - saturation * (1.f - f));
  const float table[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  for (int k = 0; k < 3; ++k)
    rgb[k] = table[std::min(sector, 5)][k];
}

void albedo(int type, double X, double Y, uint32_t seed, float rgb[3], float &gloss)
{
  switch (type) {
  case vpLaserConicSimulator::FLOOR_BRIGHT_GREY:
    brightGrey(X, Y, seed, rgb, gloss);
    break;
  case vpLaserConicSimulator::FLOOR_MOSAIC:
    mosaic(X, Y, seed, rgb, gloss);
    break;
  case vpLaserConicSimulator::FLOOR_WHITE_TILES:
    whiteTiles(X, Y, seed, rgb, gloss);
    break;
  default:
    darkTiles(X, Y, seed, rgb, gloss);
  }
}
} // namespace vsp::laser_sim_floor
