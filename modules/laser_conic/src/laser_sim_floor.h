/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_sim_floor.h
  \brief Procedural floors of vpLaserConicSimulator, as functions of the ground coordinates (metres), so that
  a floor stays attached to the ground from one frame to the next. Internal header.
*/
#ifndef VP_LASER_SIM_FLOOR_H
#define VP_LASER_SIM_FLOOR_H

#include <cstdint>

namespace vsp::laser_sim_floor
{
//! Integer hash of a lattice cell and a seed, well mixed (one multiply-xorshift chain).
inline uint32_t hash(int32_t a, int32_t b, uint32_t seed)
{
  uint64_t h = (static_cast<uint64_t>(static_cast<uint32_t>(a)) * 0x9E3779B97F4A7C15ULL) ^
               (static_cast<uint64_t>(static_cast<uint32_t>(b)) * 0xC2B2AE3D27D4EB4FULL) ^
               (static_cast<uint64_t>(seed) * 0x165667B19E3779F9ULL);
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ULL;
  h ^= h >> 29;
  return static_cast<uint32_t>(h >> 16);
}

//! Uniform value in [0, 1) from a hash.
inline float unit(uint32_t h) { return static_cast<float>(h & 0xFFFFFF) * (1.0f / 16777216.0f); }

/*!
  Albedo (R, G, B in grey levels under ambient 1) and glossiness in [0, 1] (weight of the specular reflection)
  of the floor \e type (vpLaserConicSimulator::vpFloorType) at ground point (X, Y).
*/
void albedo(int type, double X, double Y, uint32_t seed, float rgb[3], float &gloss);

//! R, G, B (0-255) of a colour given by hue (degrees), saturation and value (0-1).
void hsvToRgb(float hue, float saturation, float value, float rgb[3]);
} // namespace vsp::laser_sim_floor

#endif
