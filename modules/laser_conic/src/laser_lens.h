/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_lens.h
  \brief Private: the pixel of a normalized point under ViSP's pixel-to-metre lens model.

  The module converts detected pixels with vpPixelMeterConversion, whose distortion model is
  x = (u - u0) (1 + kdu r_d^2) / px (r_d: the distorted normalized radius). vpMeterPixelConversion uses
  another coefficient (kud) that only approximates its inverse, by pixels at the border of a wide lens;
  what renders or draws a point where the estimators will read it must invert the kdu model exactly.
*/
#ifndef VP_LASER_LENS_H
#define VP_LASER_LENS_H

#include <cmath>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpMeterPixelConversion.h>

namespace vsp::laser_lens
{
/*!
  The pixel (u, v) that vpPixelMeterConversion maps onto the normalized point (x, y): with distortion,
  r = r_d (1 + kdu r_d^2) solved for r_d by Newton from r_d = r; without, vpMeterPixelConversion.
  \return false when no pixel maps onto (x, y) (kdu < 0 beyond the widest imaged ray) or the result is
  not finite.
*/
inline bool pixelOfNormalized(const vpCameraParameters &cam, double x, double y, double &u, double &v)
{
  if (cam.get_projModel() != vpCameraParameters::perspectiveProjWithDistortion || cam.get_kdu() == 0.0) {
    vpMeterPixelConversion::convertPoint(cam, x, y, u, v);
    return std::isfinite(u) && std::isfinite(v);
  }
  const double kdu = cam.get_kdu(), r = std::hypot(x, y);
  double rd = r;
  for (int it = 0; it < 60 && r > 0.0; ++it) {
    const double slope = 1.0 + 3.0 * kdu * rd * rd;
    if (!(slope > 0.0))
      return false; // kdu < 0: beyond the radius of the widest imaged ray
    const double step = (rd * (1.0 + kdu * rd * rd) - r) / slope;
    rd -= step;
    if (std::fabs(step) < 1e-16 * (1.0 + rd))
      break;
  }
  if (!(std::fabs(rd * (1.0 + kdu * rd * rd) - r) <= 1e-12 * (1.0 + r)))
    return false; // no distorted radius maps onto r
  const double scale = r > 0.0 ? rd / r : 1.0;
  u = cam.get_u0() + cam.get_px() * x * scale;
  v = cam.get_v0() + cam.get_py() * y * scale;
  return std::isfinite(u) && std::isfinite(v);
}
} // namespace vsp::laser_lens

#endif
