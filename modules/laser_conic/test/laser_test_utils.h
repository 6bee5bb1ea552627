/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_test_utils.h
  \brief Exact simulation of a camera/circular-laser rig for the solver and estimator tests: random
  rigs and ground planes, the laser trace sampled on the cone, projected with vpCameraParameters.
  The ground truth of every test comes from this simulation.
*/
#ifndef VP_LASER_TEST_UTILS_H
#define VP_LASER_TEST_UTILS_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace laser_test
{
//! The repetitions of a statistical test: \e full, or \e reduced when the environment has
//! VSP_REDUCED_TRIALS=1 (the sanitizer stage of scripts/test.sh: the same code paths, fewer times; the
//! full counts run in the Release stage).
inline int trials(int full, int reduced)
{
  const char *env = std::getenv("VSP_REDUCED_TRIALS");
  return env != nullptr && std::string(env) == "1" ? reduced : full;
}

//! The cases of a test: all of \e cases, or their first \e reduced under VSP_REDUCED_TRIALS=1 (trials()).
template <typename T> std::vector<T> trialsOf(const std::vector<T> &cases, size_t reduced)
{
  const size_t count = static_cast<size_t>(trials(static_cast<int>(cases.size()), static_cast<int>(reduced)));
  return std::vector<T>(cases.begin(), cases.begin() + static_cast<std::ptrdiff_t>(std::min(count, cases.size())));
}

//! The typical rig of the paper's experiment: 1600x1200 camera, px = py = 1200, 34 deg laser.
struct Rig
{
  vpCameraParameters cam = vpCameraParameters(1200.0, 1200.0, 800.0, 600.0);
  unsigned int width = 1600, height = 1200;
  double openingAngle = vpMath::rad(34.0); //!< full opening angle
  vpHomogeneousMatrix cMl;
};

//! A rig with its ground plane (n, d): unit normal towards the camera, d = altitude.
struct Scene
{
  Rig rig;
  Eigen::Vector4d plane = Eigen::Vector4d(0.0, 0.0, -1.0, 1.0);
};

//! Ranges of the random scenes.
struct SceneRanges
{
  double minBaseline = 0.05, maxBaseline = 0.30; //!< metres, random direction
  double maxLaserTilt = vpMath::rad(15.0);       //!< laser axis from the optical axis
  double maxGroundTilt = vpMath::rad(60.0);      //!< ground normal from the optical axis
  double minAltitude = 0.5, maxAltitude = 1.5;   //!< metres
};

//! Uniform random unit vector.
inline Eigen::Vector3d randomDirection(std::mt19937 &rng)
{
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Vector3d v(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-6)
    v = Eigen::Vector3d(g(rng), g(rng), g(rng));
  return v.normalized();
}

//! The optical axis +Z tilted by a random angle in [0, maxTilt] about a random axis of the XY plane.
inline Eigen::Matrix3d randomTilt(std::mt19937 &rng, double maxTilt)
{
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double azimuth = 2.0 * M_PI * u01(rng);
  const double tilt = maxTilt * std::sqrt(u01(rng)); // uniform over the spherical cap (small angles)
  const Eigen::Vector3d axis(std::cos(azimuth), std::sin(azimuth), 0.0);
  return Eigen::AngleAxisd(tilt, axis).toRotationMatrix();
}

inline vpHomogeneousMatrix toVisp(const Eigen::Matrix3d &R, const Eigen::Vector3d &t)
{
  vpHomogeneousMatrix M;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      M[i][j] = R(i, j);
    M[i][3] = t(i);
  }
  return M;
}

//! The laser cone of a rig, in the solvers' representation.
inline vpLaserSolvers::LaserCone toCone(const Rig &rig)
{
  vpLaserSolvers::LaserCone cone;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j)
      cone.cRl(i, j) = rig.cMl[i][j];
    cone.apex(i) = rig.cMl[i][3];
  }
  cone.halfAngle = 0.5 * rig.openingAngle;
  return cone;
}

/*!
  Exact 3D trace: the generator of azimuth gamma, cRl (sin th cos g, sin th sin g, cos th) from the
  apex (nappe = +1, the lit one; -1 for the mirrored nappe), met by the plane. \return false when the
  generator misses the plane or the point is not in front of the camera.
*/
inline bool tracePoint(const Scene &s, double gamma, int nappe, Eigen::Vector3d &X)
{
  const vpLaserSolvers::LaserCone cone = toCone(s.rig);
  const double th = cone.halfAngle;
  const Eigen::Vector3d dir =
      double(nappe) *
      (cone.cRl * Eigen::Vector3d(std::sin(th) * std::cos(gamma), std::sin(th) * std::sin(gamma), std::cos(th)));
  const Eigen::Vector3d n = s.plane.head<3>();
  const double nd = n.dot(dir);
  if (!(nd < 0.0))
    return false;
  const double along = -(n.dot(cone.apex) + s.plane(3)) / nd;
  if (!(along > 0.0))
    return false;
  X = cone.apex + along * dir;
  return X(2) > 1e-3;
}

/*!
  Pixel of the normalized point (x, y) that vpPixelMeterConversion maps back onto (x, y) exactly (to
  rounding): the camera's own projection without distortion, and with distortion the inverse of its
  pixel-to-metre model (coefficient kdu), found by Newton's method on the distorted radius. This is not
  vpMeterPixelConversion (coefficient kud), whose one-coefficient model is only an approximate inverse
  of the kdu one: with it no estimator could recover the plane exactly.
*/
inline vpImagePoint exactPixel(const vpCameraParameters &cam, double x, double y)
{
  if (cam.get_projModel() != vpCameraParameters::perspectiveProjWithDistortion || cam.get_kdu() == 0.0) {
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(cam, x, y, ip);
    return ip;
  }
  // Undistorted radius r = rd (1 + kdu rd^2) in normalized units, with the anisotropy of px, py folded
  // in: (x, y) = (xd, yd) (1 + kdu (xd^2 + yd^2)) with xd = (u - u0) / px, yd = (v - v0) / py.
  const double r = std::hypot(x, y);
  double rd = r;
  for (int it = 0; it < 50 && r > 0.0; ++it) {
    const double f = rd * (1.0 + cam.get_kdu() * rd * rd) - r;
    const double df = 1.0 + 3.0 * cam.get_kdu() * rd * rd;
    const double step = f / df;
    rd -= step;
    if (std::abs(step) < 1e-17 * (1.0 + rd))
      break;
  }
  const double scale = r > 0.0 ? rd / r : 1.0;
  return vpImagePoint(cam.get_v0() + cam.get_py() * y * scale, cam.get_u0() + cam.get_px() * x * scale);
}

/*!
  \e n image points (pixels) of the trace, azimuths evenly spread from a random phase.
  \return false when one generator misses the plane, falls behind the camera or (when
  \e insideImage) leaves the image.
*/
inline bool traceImagePoints(const Scene &s, unsigned int n, std::mt19937 &rng, std::vector<vpImagePoint> &points,
                             bool insideImage = true, int nappe = 1)
{
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double phase = 2.0 * M_PI * u01(rng);
  points.clear();
  for (unsigned int k = 0; k < n; ++k) {
    Eigen::Vector3d X;
    if (!tracePoint(s, phase + 2.0 * M_PI * k / n, nappe, X))
      return false;
    const vpImagePoint ip = exactPixel(s.rig.cam, X(0) / X(2), X(1) / X(2));
    if (insideImage &&
        (ip.get_u() < 0.0 || ip.get_v() < 0.0 || ip.get_u() > s.rig.width - 1.0 || ip.get_v() > s.rig.height - 1.0))
      return false;
    points.push_back(ip);
  }
  return true;
}

//! A random scene (rig + ground) whose whole trace of \e n points is visible.
inline Scene randomScene(std::mt19937 &rng, const SceneRanges &r, unsigned int n, std::vector<vpImagePoint> &points,
                         bool insideImage = true)
{
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (;;) {
    Scene s;
    const Eigen::Vector3d apex = (r.minBaseline + (r.maxBaseline - r.minBaseline) * u01(rng)) * randomDirection(rng);
    const Eigen::Matrix3d cRl =
        randomTilt(rng, r.maxLaserTilt) * Eigen::AngleAxisd(2.0 * M_PI * u01(rng), Eigen::Vector3d::UnitZ());
    s.rig.cMl = toVisp(cRl, apex);
    const Eigen::Vector3d down = randomTilt(rng, r.maxGroundTilt) * Eigen::Vector3d::UnitZ();
    const double altitude = r.minAltitude + (r.maxAltitude - r.minAltitude) * u01(rng);
    s.plane << -down, altitude;
    // The apex must be on the camera side, well above the ground.
    if (s.plane.head<3>().dot(apex) + s.plane(3) < 0.2)
      continue;
    if (traceImagePoints(s, n, rng, points, insideImage))
      return s;
  }
}

//! True when the camera centre lies inside the double laser cone (no real epipolar tangent: PP-3 inapplicable).
inline bool cameraInsideCone(const vpLaserSolvers::LaserCone &cone)
{
  const Eigen::Vector3d toCamera = -cone.apex;
  const double cosine = std::abs(toCamera.normalized().dot(cone.cRl.col(2)));
  return cosine >= std::cos(cone.halfAngle);
}

//! Normalized image coordinates of pixel points (vpPixelMeterConversion, distortion included).
inline std::vector<Eigen::Vector2d> normalized(const vpCameraParameters &cam, const std::vector<vpImagePoint> &points)
{
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const vpImagePoint &p : points) {
    double x = 0.0, y = 0.0;
    vpPixelMeterConversion::convertPoint(cam, p, x, y);
    out.emplace_back(x, y);
  }
  return out;
}

//! Gaussian pixel noise of standard deviation sigma on each coordinate.
inline std::vector<vpImagePoint> addNoise(const std::vector<vpImagePoint> &points, double sigma, std::mt19937 &rng)
{
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<vpImagePoint> out;
  out.reserve(points.size());
  for (const vpImagePoint &p : points)
    out.emplace_back(p.get_i() + g(rng), p.get_j() + g(rng));
  return out;
}

/*!
  Replaces the fraction \e ratio of the points by points uniform in the image that are farther than
  \e margin pixels from the image of the trace (Sampson distance to the true conic, accurate near the
  curve) and from every trace point, so that they are true outliers; \e isOutlier receives the flags.
*/
inline std::vector<vpImagePoint> addOutliers(const std::vector<vpImagePoint> &points, double ratio, const Scene &s,
                                             std::mt19937 &rng, std::vector<bool> &isOutlier, double margin = 10.0)
{
  const Rig &rig = s.rig;
  const Eigen::Matrix3d trueConic = vpLaserSolvers::conicFromPlane(s.plane, toCone(rig));
  const double focal = 0.5 * (rig.cam.get_px() + rig.cam.get_py());
  std::uniform_real_distribution<double> u(0.0, rig.width - 1.0), v(0.0, rig.height - 1.0);
  std::vector<vpImagePoint> out = points;
  std::vector<size_t> order(points.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  isOutlier.assign(points.size(), false);
  const size_t nout = static_cast<size_t>(std::lround(ratio * points.size()));
  for (size_t k = 0; k < nout; ++k) {
    vpImagePoint candidate;
    bool far = false;
    while (!far) {
      candidate.set_uv(u(rng), v(rng));
      const Eigen::Vector2d x((candidate.get_u() - rig.cam.get_u0()) / rig.cam.get_px(),
                              (candidate.get_v() - rig.cam.get_v0()) / rig.cam.get_py());
      far = focal * vpLaserSolvers::sampsonDistance(trueConic, x) > margin;
      for (const vpImagePoint &p : points)
        far = far && vpImagePoint::distance(p, candidate) > margin;
    }
    out[order[k]] = candidate;
    isOutlier[order[k]] = true;
  }
  return out;
}

//! Angle (rad) between the normals of two planes.
inline double normalError(const Eigen::Vector4d &a, const Eigen::Vector4d &b)
{
  const Eigen::Vector3d na = a.head<3>().normalized(), nb = b.head<3>().normalized();
  return std::atan2(na.cross(nb).norm(), na.dot(nb));
}

//! Difference of the camera altitudes over two planes (metres).
inline double altitudeError(const Eigen::Vector4d &a, const Eigen::Vector4d &b)
{
  return std::abs(a(3) / a.head<3>().norm() - b(3) / b.head<3>().norm());
}

//! Distance between two conics as unit-norm matrices, sign-independent.
inline double conicDistance(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b)
{
  const Eigen::Matrix3d na = a / a.norm(), nb = b / b.norm();
  return std::min((na - nb).norm(), (na + nb).norm());
}

//! Median of a copy of the values.
inline double median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

inline double maximum(const std::vector<double> &v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }
} // namespace laser_test

#endif
