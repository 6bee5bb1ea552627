/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section V of D'Alfonso et al.: P3P with known vertical = P2P on one pair + selection by the third
  point.

  Which pair? The paper solves the pair farthest apart in the image. That pair is not always the
  best conditioned one: its yaw equation can have two nearly equal roots (or none within noise),
  and a pair along the vertical carries no yaw information at all, however wide it is. Every pair
  has a free check, the third point, whose reprojection error measures how well that pair's roots
  explain the whole measurement. So the default rule (P3PPairRule::BestThirdPoint) solves the three
  pairs and keeps the pose whose third point reprojects best; a pair whose yaw is only weakly
  observable (observability below kWeakYaw: nearly vertical segment, or rays in a nearly vertical
  plane) competes only when no other pair gives a pose. The paper's rule stays available
  (P3PPairRule::WidestPair): pairs by decreasing image distance, the first with an admissible root.

  The gravity-dependent part of the rotation (vpYawFrame) is built once for all pairs, and the
  third point is compared through cross-multiplied squared errors: no allocation.
*/
#include <limits>
#include <utility>

#include "gravity_geometry.h"
#include "gravity_pair_solver.h"

namespace vpGravitySolvers
{
namespace
{
// Below this observability (see vpPairYaw) a pair's roots follow the noise more than the data: a
// 1e-3 image error turns the yaw by ~1e-3 / observability.
constexpr double kWeakYaw = 0.05;
// Squared third-point error (normalized units) of an exact fit: 1e-12, far below any image noise.
constexpr double kExactFit2 = 1e-24;

/*!
  Writes the root of \e yaw (pair i, j) that reprojects the third point k closest to its image point
  (u, v) in normalized coordinates, with its squared reprojection error in \e error2, and returns
  true; returns false when every root puts a point behind the camera.
*/
bool bestRoot(const detail::vpYawFrame &frame, const detail::vpPairYaw &yaw, const Eigen::Vector3d x[3],
              const Eigen::Vector3d X[3], const Eigen::Vector3d Y[3], int i, int j, int k, double u, double v,
              Pose &pose, double &error2)
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
    valid[m] = (static_cast<int>(yaw.qA(c, s) > 0.0) & static_cast<int>(yaw.qB(c, s) > 0.0) &
                static_cast<int>(P.z() > 0.0)) != 0; // no branch
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
  error2 = num[m] / den[m];
  return true;
}

// Pair p is (p, p + 1) with the third point p + 2 (mod 3).
inline int pairFirst(int p) { return p; }
inline int pairSecond(int p) { return (p + 1) % 3; }
inline int pairThird(int p) { return (p + 2) % 3; }
} // namespace

bool p3p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[3],
         const Eigen::Vector3d X[3], Pose &pose, P3PPairRule rule)
{
  if (!detail::unitGravities(gCam, gObj) || !detail::allFinite(x, 3) || !detail::allFinite(X, 3) || !(x[0].z() > 0.0) ||
      !(x[1].z() > 0.0) || !(x[2].z() > 0.0))
    return false;

  double u[3], v[3];
  for (int i = 0; i < 3; ++i) {
    const double iz = 1.0 / x[i].z();
    u[i] = x[i].x() * iz;
    v[i] = x[i].y() * iz;
  }
  // The upright frames and the object points in them serve every pair.
  const detail::vpYawFrame frame(gCam, gObj);
  const Eigen::Vector3d Y[3] = {frame.upObject(X[0]), frame.upObject(X[1]), frame.upObject(X[2])};
  const Eigen::Vector3d F[3] = {frame.upCamera(x[0]), frame.upCamera(x[1]), frame.upCamera(x[2])};

  // Solves pair p; on success writes its best root into candidate, its third-point error and observability.
  auto solvePair = [&](int p, Pose &candidate, double &error2, double &observability) {
    const int i = pairFirst(p), j = pairSecond(p), k = pairThird(p);
    detail::vpPairYaw yaw;
    P2PCase p2pCase = P2PCase::NoSolution;
    // Coincident image points or no admissible yaw: no pose from this pair.
    if (detail::solvePairYaw(F[i], F[j], Y[i], Y[j], yaw, p2pCase) <= 0)
      return false;
    observability = yaw.observability;
    return bestRoot(frame, yaw, x, X, Y, i, j, k, u[k], v[k], candidate, error2);
  };

  if (rule == P3PPairRule::WidestPair) {
    // The paper's rule: pairs by decreasing image distance (a three-element sorting network).
    double dist[3];
    for (int p = 0; p < 3; ++p) {
      const int q = pairSecond(p);
      dist[p] = (u[p] - u[q]) * (u[p] - u[q]) + (v[p] - v[q]) * (v[p] - v[q]);
    }
    int order[3] = {0, 1, 2};
    for (int a = 0; a < 2; ++a)
      for (int b = a + 1; b < 3; ++b)
        if (dist[order[b]] > dist[order[a]])
          std::swap(order[a], order[b]);
    for (int p : order) {
      double error2 = 0.0, observability = 0.0;
      if (solvePair(p, pose, error2, observability))
        return true;
    }
    return false;
  }

  // BestThirdPoint: the pose of smallest third-point error among the pairs that observe the yaw,
  // the weakly observing ones only as a last resort. A pair that explains the third point to
  // rounding (exact data) cannot be beaten: the other pairs are not solved then.
  const double inf = std::numeric_limits<double>::infinity();
  double bestError[2] = {inf, inf}; // [0]: observable pairs, [1]: weak pairs
  Pose best[2];
  for (int p = 0; p < 3; ++p) {
    Pose candidate;
    double error2 = inf, observability = 0.0;
    if (!solvePair(p, candidate, error2, observability))
      continue;
    const int weak = (observability < kWeakYaw) ? 1 : 0;
    if (error2 < bestError[weak]) {
      bestError[weak] = error2;
      best[weak] = candidate;
    }
    if (weak == 0 && error2 < kExactFit2)
      break;
  }
  for (int w = 0; w < 2; ++w)
    if (bestError[w] < inf) {
      pose = best[w];
      return true;
    }
  return false;
}
} // namespace vpGravitySolvers
