/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_sim_test_utils.h
  \brief The rig rendered by the simulator and detector tests (1600x1200 camera, 34 deg laser 10 cm
  beside it) and the exact image conic of its trace, computed from the implicit cone/plane equations
  rather than from the simulator's ray casting, so that it is an independent ground truth.
*/
#ifndef VP_LASER_SIM_TEST_UTILS_H
#define VP_LASER_SIM_TEST_UTILS_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Dense>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPlane.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "laser_test_utils.h"

namespace laser_sim_test
{
const unsigned int kWidth = 1600, kHeight = 1200;
const double kOpening = vpMath::rad(34.0); //!< full opening angle of the laser cone

inline vpCameraParameters camera() { return vpCameraParameters(1500.0, 1500.0, 800.0, 600.0); }

//! A camera with a wide lens (about 80 x 60 deg over 1600 x 1200) and a barrel distortion (kdu = 0.15: the
//! undistorted radius grows), its kud fitted: the image of a trace on a plane is then not a conic.
inline vpCameraParameters wideCamera()
{
  return vpLaserConicSimulator::fitInverseDistortion(vpCameraParameters(1000.0, 1000.0, 805.0, 596.0, 0.0, 0.15),
                                                     kWidth, kHeight);
}

//! Laser 10 cm beside the camera, axis tilted by a few degrees (a typical rig).
inline vpHomogeneousMatrix laserPose()
{
  return vpHomogeneousMatrix(0.10, 0.02, 0.0, vpMath::rad(3.0), vpMath::rad(-5.0), vpMath::rad(10.0));
}

//! Ground 1 m in front, tilted by (10, -8) degrees.
inline vpHomogeneousMatrix groundPose()
{
  return vpHomogeneousMatrix(0.05, -0.03, 1.0, vpMath::rad(10), vpMath::rad(-8), 0.3);
}

//! A simulator of the test rig looking at the ground \e cMg, noise drawn from \e seed.
inline vpLaserConicSimulator makeSimulator(const vpHomogeneousMatrix &cMg = groundPose(), unsigned int seed = 7)
{
  vpLaserConicSimulator sim;
  sim.setCamera(camera(), kWidth, kHeight);
  sim.setLaser(kOpening, laserPose());
  sim.setGroundPose(cMg);
  sim.setSeed(seed);
  return sim;
}

/*!
  Image conic (pixels) of the intersection of the laser cone with the plane, from the implicit equations:
  cone (X - t)^T M (X - t) = 0 with M = R diag(1, 1, -tan^2 h) R^T, plane n.X + D = 0, X = lambda K^-1 p.
*/
inline Eigen::Matrix3d pixelConic(const vpCameraParameters &cam, double opening, const vpHomogeneousMatrix &cMl,
                                  const vpPlane &plane)
{
  laser_test::Rig rig;
  rig.cMl = cMl;
  rig.openingAngle = opening;
  const vpLaserSolvers::LaserCone cone = laser_test::toCone(rig); // only unpacks cMl: R, t, half angle
  const Eigen::Matrix3d &R = cone.cRl;
  const Eigen::Vector3d &t = cone.apex;
  const double tan2 = std::pow(std::tan(cone.halfAngle), 2);
  const Eigen::Matrix3d M = R * Eigen::Vector3d(1, 1, -tan2).asDiagonal() * R.transpose();
  const Eigen::Vector3d n(plane.getA(), plane.getB(), plane.getC());
  const double D = plane.getD();
  const Eigen::Matrix3d C =
      M + (M * t * n.transpose() + n * t.transpose() * M) / D + (t.dot(M * t) / (D * D)) * n * n.transpose();
  Eigen::Matrix3d Kinv;
  Kinv << 1.0 / cam.get_px(), 0, -cam.get_u0() / cam.get_px(), 0, 1.0 / cam.get_py(), -cam.get_v0() / cam.get_py(), 0,
      0, 1;
  return Kinv.transpose() * C * Kinv;
}

//! The image conic of the test rig's trace on \e plane.
inline Eigen::Matrix3d pixelConic(const vpPlane &plane) { return pixelConic(camera(), kOpening, laserPose(), plane); }

//! First-order (Sampson) distance in pixels of an image point to a conic; exact to first order near the curve.
inline double sampsonDistance(const Eigen::Matrix3d &C, const vpImagePoint &p)
{
  const Eigen::Vector3d x(p.get_u(), p.get_v(), 1.0);
  const Eigen::Vector3d Cx = C * x;
  return std::fabs(x.dot(Cx)) / (2.0 * Cx.head<2>().norm());
}
/*!
  The exact centre line of a rendered trace as a dense polyline (the simulator's own distorted projection of
  the cone rays, sampled about every 0.1 px), and the distance of image points to it: the ground truth of
  the detector tests with and without lens distortion (where the image of the trace is not a conic).
*/
class TraceLine
{
public:
  //! Samples \e n cone rays of \e sim (consecutive samples closer than 2 px are joined by a segment).
  TraceLine(vpLaserConicSimulator &sim, unsigned int n = 40000) : m_points(sim.tracePoints(n))
  {
    for (size_t k = 0; k < m_points.size(); ++k)
      m_cells[key(m_points[k])].push_back(static_cast<int>(k));
  }
  //! The samples.
  const std::vector<vpImagePoint> &samples() const { return m_points; }
  //! Distance (pixels) of \e p to the polyline; +inf beyond 4 px.
  double distance(const vpImagePoint &p) const
  {
    double best = std::numeric_limits<double>::infinity();
    const int64_t cx = cell(p.get_u()), cy = cell(p.get_v());
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dx = -1; dx <= 1; ++dx) {
        const auto it = m_cells.find((cy + dy) * kColumns + cx + dx);
        if (it == m_cells.end())
          continue;
        for (int k : it->second) {
          best = std::min(best, vpImagePoint::distance(p, m_points[k]));
          for (int n : {k - 1, k + 1})
            if (n >= 0 && n < static_cast<int>(m_points.size()) &&
                vpImagePoint::distance(m_points[k], m_points[n]) < 2.0)
              best = std::min(best, segmentDistance(p, m_points[k], m_points[n]));
        }
      }
    return best;
  }

private:
  static constexpr int64_t kColumns = 1 << 20;
  static int64_t cell(double x) { return static_cast<int64_t>(std::floor(x / 4.0)) + 8; }
  static int64_t key(const vpImagePoint &p) { return cell(p.get_v()) * kColumns + cell(p.get_u()); }
  static double segmentDistance(const vpImagePoint &p, const vpImagePoint &a, const vpImagePoint &b)
  {
    const double dx = b.get_u() - a.get_u(), dy = b.get_v() - a.get_v(), len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((p.get_u() - a.get_u()) * dx + (p.get_v() - a.get_v()) * dy) / len2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    return std::hypot(a.get_u() + t * dx - p.get_u(), a.get_v() + t * dy - p.get_v());
  }
  std::vector<vpImagePoint> m_points;
  std::unordered_map<int64_t, std::vector<int> > m_cells;
};

//! Writes \e I as <dir>/<name>.png when the environment variable VSP_LASER_DUMP_DIR names a folder (to look at).
inline void dumpIfRequested(const std::string &name, const vpImage<vpRGBa> &I)
{
  const char *dir = std::getenv("VSP_LASER_DUMP_DIR");
  if (dir != nullptr && *dir != '\0')
    vpImageIo::write(I, std::string(dir) + "/" + name + ".png");
}

//! Red dominance R - max(G, B) of I at (u, v), bilinear between the four pixels around it; NaN outside.
inline double redDominanceAt(const vpImage<vpRGBa> &I, double u, double v)
{
  const int iu = static_cast<int>(std::floor(u)), iv = static_cast<int>(std::floor(v));
  if (iu < 0 || iv < 0 || iu + 1 >= static_cast<int>(I.getWidth()) || iv + 1 >= static_cast<int>(I.getHeight()))
    return std::numeric_limits<double>::quiet_NaN();
  const auto at = [&I](int x, int y) {
    const vpRGBa &p = I[static_cast<unsigned int>(y)][static_cast<unsigned int>(x)];
    return static_cast<double>(static_cast<int>(p.R) - std::max(static_cast<int>(p.G), static_cast<int>(p.B)));
  };
  const double a = u - iu, b = v - iv;
  return (1 - a) * (1 - b) * at(iu, iv) + a * (1 - b) * at(iu + 1, iv) + (1 - a) * b * at(iu, iv + 1) +
         a * b * at(iu + 1, iv + 1);
}
} // namespace laser_sim_test

#endif
