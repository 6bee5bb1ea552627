/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file stressGravity.cpp
  \brief Stress test of the gravity-aided minimal solvers on random exact configurations.

  For each of N configurations (random rotation, random gravity, points in a 90 deg field of view
  at 0.5-10 m, exact bearings), the solver must return the true pose within 1e-6 (rotation angle in
  rad, translation relative to the mean depth). Outcomes are counted as:
  - correct;
  - degenerate: the configuration is degenerate by construction (object points closer than 1e-6
    times the scene size, collinear, image points within 1e-9 rad) and no pose or any pose is accepted;
  - ambiguous: the returned pose differs from the truth but reprojects every point exactly
    (< 1e-9), i.e. the data admit two exact poses and the solver returned the other one;
  - no answer: the solver returned no pose on a non-degenerate configuration;
  - wrong: a pose was returned that neither matches the truth nor reprojects the points.
  The program exits with 1 on any wrong answer.

  Usage: stress-gravity [--solver p3p|p2p|ls|all] [--n N] [--seed S] [--verbose]
  (default: p3p, N = 1e7, seed 1).
*/
#include <array>
#include <cstdio>
#include <random>
#include <string>

#include <visp3/pose_gravity/vpGravitySolvers.h>

#include "stressCommon.h"
#include "vspBenchUtils.h"

namespace
{
struct Config
{
  Eigen::Matrix3d R;
  Eigen::Vector3d t, gCam, gObj;
  Eigen::Vector3d x[8], X[8];
  double scale = 1.0; // mean depth
};

/*! A random exact configuration of \e n points. Uniform reals from a 64-bit twister, which keeps the
    generator cheaper than the solvers so that 1e7 configurations take seconds. */
void makeConfig(std::mt19937_64 &rng, int n, Config &c)
{
  std::uniform_real_distribution<double> fov(-1.0, 1.0), depth(0.5, 10.0), offset(-2.0, 2.0);
  c.R = vspBench::randomRotation(rng);
  c.t = Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
  c.gObj = vspBench::randomUnitVector(rng);
  c.gCam = c.R * c.gObj;
  double depthSum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = depth(rng);
    const Eigen::Vector3d Xc(fov(rng) * z, fov(rng) * z, z);
    c.x[i] = Xc / z;
    c.X[i] = c.R.transpose() * (Xc - c.t);
    depthSum += z;
  }
  c.scale = depthSum / n;
}

//! Degenerate by construction: coincident or collinear object points, or coincident image points.
bool isDegenerate(const Config &c, int n)
{
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if ((c.X[i] - c.X[j]).norm() < 1e-6 * c.scale) {
        return true;
      }
      if (c.x[i].normalized().cross(c.x[j].normalized()).norm() < 1e-9) {
        return true;
      }
    }
  }
  if (n == 3) {
    const double area = (c.X[1] - c.X[0]).cross(c.X[2] - c.X[0]).norm();
    const double side = std::max((c.X[1] - c.X[0]).squaredNorm(), (c.X[2] - c.X[0]).squaredNorm());
    if (area < 1e-9 * side) {
      return true;
    }
  }
  return false;
}

double poseError(const vpGravitySolvers::Pose &p, const Config &c)
{
  const double rot = vspBench::rotationAngleBetween(p.R, c.R);
  const double tra = (p.t - c.t).norm() / c.scale;
  const double e = std::max(rot, tra);
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

//! Largest reprojection error (normalized units) of the n points, +inf for a point behind the camera.
double reprojection(const vpGravitySolvers::Pose &p, const Config &c, int n)
{
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d Xc = p.R * c.X[i] + p.t;
    if (!(Xc.z() > 0.0)) {
      return std::numeric_limits<double>::infinity();
    }
    worst = std::max(worst, (Xc.head<2>() / Xc.z() - c.x[i].head<2>()).norm());
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

void dump(const char *what, long index, const Config &c, int n, double error)
{
  std::printf("  %s at configuration %ld (error %.3g):\n", what, index, error);
  std::printf("    gCam = [%.17g %.17g %.17g]  gObj = [%.17g %.17g %.17g]\n", c.gCam.x(), c.gCam.y(), c.gCam.z(),
              c.gObj.x(), c.gObj.y(), c.gObj.z());
  for (int i = 0; i < n; ++i) {
    std::printf("    x%d = [%.17g %.17g 1]  X%d = [%.17g %.17g %.17g]\n", i, c.x[i].x(), c.x[i].y(), i, c.X[i].x(),
                c.X[i].y(), c.X[i].z());
  }
}

constexpr double kExactReprojection = 1e-9;

using vspStress::Tally;

void classify(Tally &tally, long index, const Config &c, int n, bool degenerate, bool answered, double best,
              bool exactAlternative, bool verbose)
{
  vspStress::classify(tally, degenerate, answered, best, exactAlternative, verbose,
                      [&](const char *what) { dump(what, index, c, n, best); });
}

/*!
  Runs \e count configurations of \e n points through a solver that returns one pose,
  \e solve(config, pose) -> found. A pose that is not the truth but reprojects every point exactly
  (< 1e-9) is the other solution of ambiguous data.
*/
template <typename Solve> Tally stressOnePose(long count, unsigned long seed, int n, bool verbose, Solve solve)
{
  std::mt19937_64 rng(seed);
  Tally tally;
  Config c;
  for (long k = 0; k < count; ++k) {
    makeConfig(rng, n, c);
    vpGravitySolvers::Pose pose;
    const bool ok = solve(c, pose);
    const double e = ok ? poseError(pose, c) : std::numeric_limits<double>::infinity();
    classify(tally, k, c, n, isDegenerate(c, n), ok, e, ok && reprojection(pose, c, n) <= kExactReprojection, verbose);
  }
  return tally;
}

Tally stressP2P(long count, unsigned long seed, bool verbose)
{
  std::mt19937_64 rng(seed);
  Tally tally;
  Config c;
  for (long k = 0; k < count; ++k) {
    makeConfig(rng, 2, c);
    std::array<vpGravitySolvers::Pose, 2> poses;
    const int m = vpGravitySolvers::p2p(c.gCam, c.gObj, c.x, c.X, poses);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m; ++i) {
      best = std::min(best, poseError(poses[i], c));
    }
    // Two points: every candidate reprojects both points, so "exact but different" is not an
    // acceptable alternative here: the truth must be among the candidates.
    classify(tally, k, c, 2, isDegenerate(c, 2), m > 0, best, false, verbose);
  }
  return tally;
}
} // namespace

int main(int argc, char **argv)
{
  vspStress::Options o;
  int exitStatus = 0;
  if (!vspStress::parseOptions(argc, argv, "--solver", {"p3p", "p2p", "ls", "all"}, "p3p", "1e7", o, exitStatus))
    return exitStatus;
  bool ok = true;
  if (o.solver == "p3p" || o.solver == "all") {
    ok = vspStress::report("P3P", o.count,
                           stressOnePose(o.count, o.seed, 3, o.verbose,
                                         [](const Config &c, vpGravitySolvers::Pose &p) {
                                           return vpGravitySolvers::p3p(c.gCam, c.gObj, c.x, c.X, p);
                                         })) &&
         ok;
  }
  if (o.solver == "p2p" || o.solver == "all") {
    ok = vspStress::report("P2P", o.count, stressP2P(o.count, o.seed, o.verbose)) && ok;
  }
  if (o.solver == "ls" || o.solver == "all") {
    const int n = 6;
    ok = vspStress::report("LEAST_SQUARES", o.count,
                           stressOnePose(o.count, o.seed, n, o.verbose,
                                         [n](const Config &c, vpGravitySolvers::Pose &p) {
                                           return vpGravitySolvers::leastSquares(c.gCam, c.gObj, c.x, c.X, n, p);
                                         })) &&
         ok;
  }
  return ok ? 0 : 1;
}
