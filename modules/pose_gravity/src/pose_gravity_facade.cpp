/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Helpers shared by the vpPoseGravity facade files (see pose_gravity_facade.h).
*/
#include "pose_gravity_facade.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace vsp::pose_gravity_facade
{
void storePose(const vpGravitySolvers::Pose &pose, vpHomogeneousMatrix &cMo)
{
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 3; ++c)
      cMo[r][c] = pose.R(static_cast<int>(r), static_cast<int>(c));
    cMo[r][3] = pose.t(static_cast<int>(r));
    cMo[3][r] = 0.0;
  }
  cMo[3][3] = 1.0;
}

vpGravitySolvers::Pose toPose(const vpHomogeneousMatrix &cMo)
{
  vpGravitySolvers::Pose pose;
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 3; ++c)
      pose.R(static_cast<int>(r), static_cast<int>(c)) = cMo[r][c];
    pose.t(static_cast<int>(r)) = cMo[r][3];
  }
  return pose;
}

namespace
{
void collect(const std::vector<vpPoint> &points, const std::vector<unsigned int> *index, size_t n,
             std::vector<Eigen::Vector3d> &x, std::vector<Eigen::Vector3d> &X)
{
  x.resize(n);
  X.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const vpPoint &P = points[index ? (*index)[k] : k];
    x[k] = Eigen::Vector3d(P.get_x(), P.get_y(), 1.0);
    X[k] = Eigen::Vector3d(P.get_oX(), P.get_oY(), P.get_oZ());
  }
}
} // namespace

void collectPoints(const std::vector<vpPoint> &points, const std::vector<unsigned int> *index,
                   std::vector<Eigen::Vector3d> &x, std::vector<Eigen::Vector3d> &X)
{
  collect(points, index, index ? index->size() : points.size(), x, X);
}

void collectFirst(const std::vector<vpPoint> &points, size_t count, std::vector<Eigen::Vector3d> &x,
                  std::vector<Eigen::Vector3d> &X)
{
  collect(points, nullptr, std::min(count, points.size()), x, X);
}

double objectScale(const std::vector<vpPoint> &points, unsigned int count)
{
  double scale = 0.0;
  for (unsigned int i = 0; i < count && i < points.size(); ++i)
    scale = std::max({scale, std::abs(points[i].get_oX()), std::abs(points[i].get_oY()), std::abs(points[i].get_oZ())});
  return scale;
}

void findDuplicates(const std::vector<double> &v, int dim, double tolerance, std::vector<int> &firstEqual)
{
  const size_t n = v.size() / static_cast<size_t>(dim);
  firstEqual.assign(n, -1);
  if (n < 2)
    return;
  if (n <= 128) {
    // Few points: the direct comparison of every pair is faster than sorting (and allocates nothing).
    for (size_t i = 1; i < n; ++i)
      for (size_t j = 0; j < i && firstEqual[i] < 0; ++j) {
        bool within = true;
        for (int d = 0; d < dim; ++d)
          within = within && std::abs(v[i * dim + d] - v[j * dim + d]) <= tolerance;
        if (within)
          firstEqual[i] = static_cast<int>(j);
      }
    return;
  }
  if (!(tolerance > 0.0)) {
    // Exact equality: the lexicographic order puts equal rows next to each other.
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    auto less = [&](size_t a, size_t b) {
      for (int d = 0; d < dim; ++d)
        if (v[a * dim + d] != v[b * dim + d])
          return v[a * dim + d] < v[b * dim + d];
      return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (size_t k = 1; k < n; ++k) {
      const size_t a = order[k - 1], b = order[k];
      bool same = true;
      for (int d = 0; d < dim; ++d)
        same = same && v[a * dim + d] == v[b * dim + d];
      if (same)
        firstEqual[b] = (firstEqual[a] >= 0) ? firstEqual[a] : static_cast<int>(a);
    }
    return;
  }
  // Cells of side tolerance: two rows within tolerance lie in the same or in adjacent cells.
  typedef std::array<std::int64_t, 3> Key;
  std::vector<Key> keys(n);
  for (size_t i = 0; i < n; ++i) {
    keys[i] = Key{{0, 0, 0}};
    for (int d = 0; d < dim; ++d) {
      const double c = std::floor(v[i * dim + d] / tolerance);
      keys[i][d] = static_cast<std::int64_t>(std::max(-9e18, std::min(9e18, c)));
    }
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  const int offsets = (dim == 1) ? 3 : (dim == 2) ? 9 : 27;
  for (size_t i = 0; i < n; ++i) {
    int best = -1;
    for (int o = 0; o < offsets; ++o) {
      Key target = keys[i];
      int code = o;
      for (int d = 0; d < dim; ++d, code /= 3)
        target[d] += code % 3 - 1;
      // The rows of the target cell, by increasing index: only earlier rows can be the first equal one.
      auto begin =
          std::lower_bound(order.begin(), order.end(), target, [&](size_t a, const Key &k) { return keys[a] < k; });
      for (auto it = begin; it != order.end() && keys[*it] == target && *it < i; ++it) {
        bool within = true;
        for (int d = 0; d < dim; ++d)
          within = within && std::abs(v[*it * dim + d] - v[i * dim + d]) <= tolerance;
        if (within) {
          best = (best < 0) ? static_cast<int>(*it) : std::min(best, static_cast<int>(*it));
          break;
        }
      }
    }
    firstEqual[i] = best;
  }
}

bool exchangeChangesTheProblem(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, double gCamStdDev,
                               double gObjStdDev)
{
  // At 0.16 degree of tilt noise on each IMU (0.002 per component), not stated, the two vectors of an upright
  // camera facing an upright target differ by 0.23 degree RMS, 0.6 degree once in a thousand; three points
  // fitted the exchange better by chance in 1.5 % of such scenes (PoseGravityMistakes.ASharedVerticalIsNever
  // CalledMistaken).
  constexpr double kOneDegree = M_PI / 180.0;
  return (gCam - gObj).norm() > std::max(kOneDegree, 3.0 * std::hypot(gCamStdDev, gObjStdDev));
}
} // namespace vsp::pose_gravity_facade
