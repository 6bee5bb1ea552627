/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section V of D'Alfonso et al.: P3P with known vertical = P2P on one pair + selection by the third
  point. The pair farthest apart in the image is tried first (the paper's remark: best conditioned
  under pixel noise); when its image points coincide (Lemma 1) or it yields no admissible pose the
  other pairs are tried, in decreasing image distance.
*/
#include <limits>

#include "gravityGeometry.h"

namespace vpGravitySolvers
{
namespace
{
// Squared distance between two image points given as bearings.
double imageDistance2(const Eigen::Vector3d &a, const Eigen::Vector3d &b)
{
  const double dx = a.x() / a.z() - b.x() / b.z();
  const double dy = a.y() / a.z() - b.y() / b.z();
  return dx * dx + dy * dy;
}
} // namespace

bool p3p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[3],
         const Eigen::Vector3d X[3], Pose &pose)
{
  // Pairs (i, j) with the third point k, sorted by decreasing image distance (three elements).
  int pairs[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
  double dist[3];
  for (int p = 0; p < 3; ++p)
    dist[p] = imageDistance2(x[pairs[p][0]], x[pairs[p][1]]);
  for (int p = 0; p < 2; ++p)
    for (int q = p + 1; q < 3; ++q)
      if (dist[q] > dist[p]) {
        std::swap(dist[p], dist[q]);
        for (int m = 0; m < 3; ++m)
          std::swap(pairs[p][m], pairs[q][m]);
      }

  for (int p = 0; p < 3; ++p) {
    const int i = pairs[p][0], j = pairs[p][1], k = pairs[p][2];
    const Eigen::Vector3d xPair[2] = {x[i], x[j]};
    const Eigen::Vector3d XPair[2] = {X[i], X[j]};
    std::array<Pose, 2> candidates;
    P2PCase p2pCase = P2PCase::NoSolution;
    const int count = p2p(gCam, gObj, xPair, XPair, candidates, &p2pCase);
    if (p2pCase != P2PCase::TwoSolutions)
      continue; // coincident image points or no admissible yaw: use another pair
    double bestError = std::numeric_limits<double>::infinity();
    int best = -1;
    for (int m = 0; m < count; ++m) {
      const double e = detail::reprojectionError2(candidates[m], x[k], X[k]);
      if (e < bestError) {
        bestError = e;
        best = m;
      }
    }
    if (best >= 0) {
      pose = candidates[best];
      return true;
    }
  }
  return false;
}
} // namespace vpGravitySolvers
