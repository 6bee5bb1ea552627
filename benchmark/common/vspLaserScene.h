/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file vspLaserScene.h
  \brief Independent ground truth for the laser benchmarks and stress tests: a camera/circular-laser
  rig over a ground plane, and the exact image of the laser trace computed by ray/plane intersection
  (no code of the laser_conic module is used, so that its results can be checked against it).
*/
#ifndef VSP_LASER_SCENE_H
#define VSP_LASER_SCENE_H

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vspBench
{
//! Pinhole camera (pixels) and laser cone (camera frame).
struct LaserRig
{
  double px = 800.0, py = 800.0, u0 = 800.0, v0 = 600.0; //!< intrinsics
  int width = 1600, height = 1200;                       //!< image size
  Eigen::Matrix3d cRl = Eigen::Matrix3d::Identity();     //!< laser orientation, cone axis = third column
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();        //!< laser centre in the camera frame
  double halfAngle = 0.0;                                //!< half opening angle (rad)
};

//! The rig of the benchmarks: 34 deg full opening angle, laser 10 cm right of the camera, tilted 3 deg.
inline LaserRig defaultRig()
{
  LaserRig rig;
  rig.cRl = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  rig.apex = Eigen::Vector3d(0.10, 0.02, 0.0);
  rig.halfAngle = 17.0 * M_PI / 180.0;
  return rig;
}

/*!
  Ground plane (n, d) in the camera frame, unit normal towards the camera, d = altitude, for the
  attitude convention of the module: the downward direction is g = Rx(roll) Ry(pitch) e_z, n = -g.
*/
inline Eigen::Vector4d groundPlane(double altitude, double roll, double pitch)
{
  const Eigen::Vector3d g = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
                            (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitZ());
  return Eigen::Vector4d(-g.x(), -g.y(), -g.z(), altitude);
}

/*!
  Trace point of the generator at cone angle \e phi: the ray of the cone meets the plane in front of
  the laser and the point is in front of the camera. \return false otherwise.
*/
inline bool traceAt(const LaserRig &rig, const Eigen::Vector4d &plane, double phi, Eigen::Vector3d &Xc)
{
  const Eigen::Vector3d dirLaser(std::sin(rig.halfAngle) * std::cos(phi), std::sin(rig.halfAngle) * std::sin(phi),
                                 std::cos(rig.halfAngle));
  const Eigen::Vector3d dir = rig.cRl * dirLaser;
  const Eigen::Vector3d n = plane.head<3>();
  const double denom = n.dot(dir);
  if (std::abs(denom) < 1e-12) {
    return false;
  }
  const double s = -(n.dot(rig.apex) + plane(3)) / denom;
  if (s <= 0.0) {
    return false;
  }
  Xc = rig.apex + s * dir;
  return Xc.z() > 1e-6;
}

//! Normalized image coordinates of a camera-frame point.
inline Eigen::Vector2d normalizedOf(const Eigen::Vector3d &Xc)
{
  return Eigen::Vector2d(Xc.x() / Xc.z(), Xc.y() / Xc.z());
}

//! Pixel coordinates (u, v) of normalized coordinates.
inline Eigen::Vector2d pixelOf(const LaserRig &rig, const Eigen::Vector2d &xn)
{
  return Eigen::Vector2d(rig.px * xn.x() + rig.u0, rig.py * xn.y() + rig.v0);
}

/*!
  A frame of \e n trace points in pixels at uniformly random cone angles, inside the image, with
  Gaussian noise \e sigma (pixels) and a fraction \e outlierRatio replaced by uniform points of the
  image. Returns fewer points only if the trace barely enters the image.
*/
template <typename Rng>
std::vector<Eigen::Vector2d> traceFrame(const LaserRig &rig, const Eigen::Vector4d &plane, int n, double sigma,
                                        double outlierRatio, Rng &rng)
{
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), coin(0.0, 1.0), uu(0.0, rig.width - 1.0),
      vv(0.0, rig.height - 1.0);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  std::vector<Eigen::Vector2d> points;
  points.reserve(n);
  for (int attempt = 0; static_cast<int>(points.size()) < n && attempt < 100 * n; ++attempt) {
    Eigen::Vector3d Xc;
    if (!traceAt(rig, plane, angle(rng), Xc)) {
      continue;
    }
    Eigen::Vector2d uv = pixelOf(rig, normalizedOf(Xc));
    if (uv.x() < 0.0 || uv.y() < 0.0 || uv.x() > rig.width - 1.0 || uv.y() > rig.height - 1.0) {
      continue;
    }
    if (sigma > 0.0) {
      uv += Eigen::Vector2d(noise(rng), noise(rng));
    }
    points.push_back(uv);
  }
  const int outliers = static_cast<int>(std::lround(outlierRatio * points.size()));
  for (int i = 0; i < outliers; ++i) {
    points[i] = Eigen::Vector2d(uu(rng), vv(rng));
  }
  std::shuffle(points.begin(), points.end(), rng);
  return points;
}

//! Angle (rad) between the normals of two planes and the difference of their offsets (both normalised).
inline void planeErrors(const Eigen::Vector4d &estimate, const Eigen::Vector4d &truth, double &normalAngle,
                        double &offsetError)
{
  const double ne = estimate.head<3>().norm(), nt = truth.head<3>().norm();
  const Eigen::Vector3d a = estimate.head<3>() / ne, b = truth.head<3>() / nt;
  normalAngle = std::atan2(a.cross(b).norm(), a.dot(b));
  offsetError = std::abs(estimate(3) / ne - truth(3) / nt);
}
} // namespace vspBench

#endif
