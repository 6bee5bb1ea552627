/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section V of D'Alfonso et al.: P3P with known vertical = P2P on one pair + selection by the third
  point. The pair farthest apart in the image is tried first (the paper's remark: best conditioned
  under pixel noise); when its image points coincide (Lemma 1) or it yields no admissible pose the
  other pairs are tried, in decreasing image distance.

  The gravity-dependent part of the rotation (vpYawFrame) is built once for all pairs, and the
  third point is compared through cross-multiplied squared errors: no division, no allocation.
*/
#include <utility>

#include "gravityPairSolver.h"

namespace vpGravitySolvers
{
namespace
{
/*!
  Writes the root of \e yaw (pair i, j) that reprojects the third point k closest to its image point
  (u, v) in normalized coordinates and returns true, or returns false when every root puts a point
  behind the camera.
*/
bool bestRoot(const detail::vpYawFrame &frame, const detail::vpPairYaw &yaw, const Eigen::Vector3d x[3],
              const Eigen::Vector3d X[3], const Eigen::Vector3d Y[3], int i, int j, int k, double u, double v,
              Pose &pose)
{
  // P = cRo X_k + t = cRo (X_k - S / 2) + h (qA x_i + qB x_j) with S = X_i + X_j: P = cos Pc + sin Ps + P1.
  const Eigen::Vector3d e = Y[k] - 0.5 * (Y[i] + Y[j]);
  const Eigen::Vector3d Pc = frame.toCamera(e.x(), e.y(), 0.0) + yaw.h * (yaw.qA.k[0] * x[i] + yaw.qB.k[0] * x[j]);
  const Eigen::Vector3d Ps = frame.toCamera(-e.y(), e.x(), 0.0) + yaw.h * (yaw.qA.k[1] * x[i] + yaw.qB.k[1] * x[j]);
  const Eigen::Vector3d P1 = e.z() * frame.gc + yaw.h * (yaw.qA.k[2] * x[i] + yaw.qB.k[2] * x[j]);
  // Squared reprojection error num / den of each root (den = P_z^2), compared cross-multiplied;
  // the double root is stored twice, so both entries are always meaningful.
  bool valid[2];
  double num[2], den[2];
  for (int m = 0; m < 2; ++m) {
    const double c = yaw.cs[m][0], s = yaw.cs[m][1];
    const Eigen::Vector3d P = c * Pc + s * Ps + P1;
    valid[m] = (yaw.qA(c, s) > 0.0) & (yaw.qB(c, s) > 0.0) & (P.z() > 0.0);
    const double ex = P.x() - u * P.z(), ey = P.y() - v * P.z();
    num[m] = ex * ex + ey * ey;
    den[m] = P.z() * P.z();
  }
  if (!(valid[0] | valid[1]))
    return false;
  const int m = (valid[1] & (!valid[0] | (num[1] * den[0] < num[0] * den[1]))) ? 1 : 0;
  const double c = yaw.cs[m][0], s = yaw.cs[m][1];
  frame.rotation(c, s, pose.R);
  pose.t = yaw.translation(c, s, x[i], x[j], pose.R * (X[i] + X[j]));
  return true;
}
} // namespace

bool p3p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[3],
         const Eigen::Vector3d X[3], Pose &pose)
{
  const Eigen::Vector3d g[2] = {gCam, gObj};
  if (!detail::allFinite(g, 2) || !detail::allFinite(x, 3) || !detail::allFinite(X, 3) || !(x[0].z() > 0.0) ||
      !(x[1].z() > 0.0) || !(x[2].z() > 0.0))
    return false;

  // Normalized image points; pair p is (p, p + 1) with the third point p + 2 (mod 3), and the pairs
  // are sorted by decreasing image distance (a three-element sorting network on indices).
  double u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    const double iz = 1.0 / x[i].z();
    u[i] = x[i].x() * iz;
    v[i] = x[i].y() * iz;
  }
  double dist[3];
  for (int p = 0; p < 3; ++p) {
    const int q = (p + 1) % 3;
    dist[p] = (u[p] - u[q]) * (u[p] - u[q]) + (v[p] - v[q]) * (v[p] - v[q]);
  }
  int order[3] = {0, 1, 2};
  for (int a = 0; a < 2; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (dist[order[b]] > dist[order[a]])
        std::swap(order[a], order[b]);

  // The upright frames and the object points in them serve every pair (the bearings of the third
  // point are not needed in the upright frame).
  const detail::vpYawFrame frame(gCam, gObj);
  const Eigen::Vector3d Y[3] = {frame.upObject(X[0]), frame.upObject(X[1]), frame.upObject(X[2])};
  for (int p : order) {
    const int i = p, j = (p + 1) % 3, k = (p + 2) % 3;
    detail::vpPairYaw yaw;
    P2PCase p2pCase = P2PCase::NoSolution;
    // Coincident image points or no admissible yaw: use another pair.
    if (detail::solvePairYaw(frame.upCamera(x[i]), frame.upCamera(x[j]), Y[i], Y[j], yaw, p2pCase) > 0 &&
        bestRoot(frame, yaw, x, X, Y, i, j, k, u[k], v[k], pose))
      return true;
  }
  return false;
}
} // namespace vpGravitySolvers
