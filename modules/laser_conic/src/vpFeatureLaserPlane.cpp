/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpFeatureLaserPlane.h>

#include <cmath>
#include <cstdio>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpMath.h>
#include <visp3/laser_conic/vpLaserConicException.h>

#include "laser_value_check.h"

using vsp::laser_value_check::require;

vpFeatureLaserPlane::vpFeatureLaserPlane() : m_gz(1.0) { init(); }

void vpFeatureLaserPlane::init()
{
  dim_s = 3;
  nbParameters = 3;
  s.resize(dim_s);
  if (flags == nullptr)
    flags = new bool[nbParameters];
  set(1.0, 0.0, 0.0, 1.0);
}

void vpFeatureLaserPlane::set(double h, double gx, double gy, double gz)
{
  s[0] = h;
  s[1] = gx;
  s[2] = gy;
  m_gz = gz;
  for (unsigned int i = 0; i < nbParameters; ++i)
    flags[i] = true;
}

void vpFeatureLaserPlane::buildFrom(double altitude, double roll, double pitch)
{
  require(std::isfinite(altitude) && altitude > 0.0, "vpFeatureLaserPlane::buildFrom: altitude must be finite and > 0");
  require(vsp::laser_value_check::isGroundAttitude(roll, pitch),
          "vpFeatureLaserPlane::buildFrom: roll and pitch must be radians within (-pi/2, pi/2), a ground in front of "
          "the camera (degrees given?)");
  const double cp = std::cos(pitch);
  set(altitude, std::sin(pitch), -std::sin(roll) * cp, std::cos(roll) * cp);
}

void vpFeatureLaserPlane::buildFrom(const vpPlane &cPlane)
{
  const double a = cPlane.getA(), b = cPlane.getB(), c = cPlane.getC(), d = cPlane.getD();
  const double norm = std::sqrt(a * a + b * b + c * c);
  require(norm > 0.0 && std::isfinite(norm) && std::isfinite(d) && d != 0.0,
          "vpFeatureLaserPlane::buildFrom: the plane needs a non-zero normal and the camera off it");
  // Plane a x + b y + c z + d = 0: the camera centre is on the side of sign(d); the downward normal
  // points from the camera to the plane.
  const double sign = d > 0.0 ? -1.0 : 1.0;
  set(std::abs(d) / norm, sign * a / norm, sign * b / norm, sign * c / norm);
}

vpMatrix vpFeatureLaserPlane::interaction(unsigned int select)
{
  const double gx = s[1], gy = s[2], gz = m_gz;
  const double rows[3][6] = {{-gx, -gy, -gz, 0.0, 0.0, 0.0},
                             {0.0, 0.0, 0.0, 0.0, -gz, gy},
                             {0.0, 0.0, 0.0, gz, 0.0, -gx}};
  vpMatrix L(0, 6);
  for (unsigned int i = 0; i < 3; ++i) {
    if (!(select & FEATURE_LINE[i]))
      continue;
    vpMatrix row(1, 6);
    for (unsigned int j = 0; j < 6; ++j)
      row[0][j] = rows[i][j];
    L.stack(row);
  }
  return L;
}

vpColVector vpFeatureLaserPlane::error(const vpBasicFeature &s_star, unsigned int select)
{
  vpColVector e(0);
  for (unsigned int i = 0; i < 3; ++i)
    if (select & FEATURE_LINE[i]) {
      vpColVector ei(1);
      ei[0] = s[i] - s_star[i];
      e.stack(ei);
    }
  return e;
}

void vpFeatureLaserPlane::print(unsigned int select) const
{
  std::printf("vpFeatureLaserPlane:");
  const char *names[3] = {"h", "gx", "gy"};
  for (unsigned int i = 0; i < 3; ++i)
    if (select & FEATURE_LINE[i])
      std::printf(" %s=%g", names[i], s[i]);
  std::printf(" (gz=%g)\n", m_gz);
}

vpFeatureLaserPlane *vpFeatureLaserPlane::duplicate() const { return new vpFeatureLaserPlane(*this); }

namespace
{
template <typename Image> void caption(const vpFeatureLaserPlane &f, const Image &I, const vpColor &color)
{
  char text[96];
  const double roll = std::atan2(-f.get_gy(), f.get_gz()), pitch = std::asin(std::max(-1.0, std::min(1.0, f.get_gx())));
  std::snprintf(text, sizeof(text), "h %.3f m  roll %.1f deg  pitch %.1f deg", f.get_h(), vpMath::deg(roll),
                vpMath::deg(pitch));
  vpDisplay::displayText(I, 20, 10, text, color);
}
} // namespace

void vpFeatureLaserPlane::display(const vpCameraParameters &, const vpImage<unsigned char> &I, const vpColor &color,
                                  unsigned int) const
{
  caption(*this, I, color);
}

void vpFeatureLaserPlane::display(const vpCameraParameters &, const vpImage<vpRGBa> &I, const vpColor &color,
                                  unsigned int) const
{
  caption(*this, I, color);
}
