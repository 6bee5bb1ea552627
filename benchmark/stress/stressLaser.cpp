/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file stressLaser.cpp
  \brief Stress test of the circular-laser solvers (vpLaserSolvers) on random exact configurations.

  Each configuration draws a rig (half opening angle 10-40 deg, apex up to 20 cm from the camera
  centre, cone axis tilted up to 10 deg) and a ground plane (altitude 0.5-5 m, roll and pitch within
  30 deg), then exact trace points in normalized coordinates from an independent ray/plane
  generator (vspLaserScene.h). Per method:
  - GP3: gp3Planes on 3 points; the true plane must be among the candidates;
  - PP3: pp3Conics on 3 points + planePair on each conic; the true plane must be among the results;
  - PP5: fitConic on 5 points + planePair;
  - PLANE_PAIR: fitConic on 50 points + planePair.
  A plane is correct when its normal is within 1e-6 rad and its altitude within 1e-6 (relative), or
  within the error rounding alone may cause on an ill-conditioned minimal sample (roundingTolerance(),
  counted and printed apart).
  Outcomes: correct; degenerate (a refusal, no candidate, on a degenerate configuration: for the
  minimal solvers two sample points closer than 1e-3 rad of cone angle; for PP3 also the camera centre
  inside the cone or two sample points on epipolar lines within 1e-2 rad, where the canonical frame
  of eq. 36 degenerates); no answer (no candidate on a non-degenerate configuration); wrong (candidates,
  none correct, degenerate configuration or not). Exit status 1 on any wrong answer.

  Usage: stress-laser [--method gp3|pp3|pp5|planepair|all] [--n N] [--seed S] [--verbose]
  (default: all, N = 1e6 per method).
*/
#include <cstdio>
#include <random>
#include <string>

#include <Eigen/SVD>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include "stressCommon.h"
#include "vspBenchUtils.h"
#include "vspLaserScene.h"

namespace
{
constexpr int kPlanePairPoints = 50;

struct Config
{
  vspBench::LaserRig rig;
  vpLaserSolvers::LaserCone cone;
  Eigen::Vector4d plane;
  Eigen::Vector2d x[kPlanePairPoints];
  double phi[kPlanePairPoints];
};

//! A random rig and plane and \e n exact trace points; false when the trace misses the camera's front.
bool makeConfig(std::mt19937_64 &rng, int n, Config &c)
{
  std::uniform_real_distribution<double> half(10.0, 40.0), offset(-0.2, 0.2), tilt(-10.0, 10.0), altitude(0.5, 5.0),
      attitude(-30.0, 30.0), angle(-M_PI, M_PI);
  const double deg = M_PI / 180.0;
  c.rig.halfAngle = half(rng) * deg;
  c.rig.apex = Eigen::Vector3d(offset(rng), offset(rng), offset(rng) * 0.25);
  c.rig.cRl = (Eigen::AngleAxisd(tilt(rng) * deg, Eigen::Vector3d::UnitX()) *
               Eigen::AngleAxisd(tilt(rng) * deg, Eigen::Vector3d::UnitY()) *
               Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()))
                  .toRotationMatrix();
  c.cone.cRl = c.rig.cRl;
  c.cone.apex = c.rig.apex;
  c.cone.halfAngle = c.rig.halfAngle;
  c.plane = vspBench::groundPlane(altitude(rng), attitude(rng) * deg, attitude(rng) * deg);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d Xc;
    int attempts = 0;
    do {
      c.phi[i] = angle(rng);
    } while (!vspBench::traceAt(c.rig, c.plane, c.phi[i], Xc) && ++attempts < 100);
    if (attempts >= 100) {
      return false;
    }
    c.x[i] = vspBench::normalizedOf(Xc);
  }
  return true;
}

//! Two sample points closer than 1e-3 rad on the cone: the minimal problem is degenerate.
bool closeSamples(const Config &c, int n)
{
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double d = std::remainder(c.phi[i] - c.phi[j], 2.0 * M_PI);
      if (std::abs(d) < 1e-3) {
        return true;
      }
    }
  }
  return false;
}

double planeError(const Eigen::Vector4d &estimate, const Eigen::Vector4d &truth)
{
  double angle = 0.0, offset = 0.0;
  vspBench::planeErrors(estimate, truth, angle, offset);
  const double e = std::max(angle, offset / truth(3));
  return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
}

using vspStress::Tally;

//! Answers counted correct because their error, above 1e-6, is within roundingTolerance().
long illConditionedCorrect = 0;
//! Largest error and rounding bound among them.
double illConditionedError = 0.0, illConditionedBound = 0.0;

void dump(const char *what, long index, const Config &c, int n, double error)
{
  std::printf("  %s at configuration %ld (best error %.3g):\n", what, index, error);
  std::printf("    halfAngle = %.17g  apex = [%.17g %.17g %.17g]\n", c.cone.halfAngle, c.cone.apex.x(), c.cone.apex.y(),
              c.cone.apex.z());
  std::printf("    cRl = [%.17g %.17g %.17g; %.17g %.17g %.17g; %.17g %.17g %.17g]\n", c.cone.cRl(0, 0),
              c.cone.cRl(0, 1), c.cone.cRl(0, 2), c.cone.cRl(1, 0), c.cone.cRl(1, 1), c.cone.cRl(1, 2),
              c.cone.cRl(2, 0), c.cone.cRl(2, 1), c.cone.cRl(2, 2));
  std::printf("    plane = [%.17g %.17g %.17g %.17g]\n", c.plane(0), c.plane(1), c.plane(2), c.plane(3));
  for (int i = 0; i < std::min(n, 5); ++i) {
    std::printf("    x%d = [%.17g %.17g]\n", i, c.x[i].x(), c.x[i].y());
  }
}

/*!
  Forward error that rounding alone may cause on the minimal configuration: the data are exact only to
  rounding, and a backward-stable solver returns a plane whose trace passes within ~1e-14 (normalized
  units, a few tens of ulps of the coordinates and of the cone) of the sample points; the plane is then
  known to that backward error divided by the smallest singular value of the Jacobian of the points'
  Sampson distances with respect to the plane (two rotations of the normal, relative altitude). On
  well-conditioned samples this is far below 1e-6; on a short arc seen from far (three points within
  a few hundredths of a radian of one another at 4-5 m) it is not, and an error up to it is not a
  solver defect.
*/
double roundingTolerance(const Config &c, int n)
{
  constexpr double kBackwardError = 1e-14;
  if (n > 5)
    return vspStress::kTolerance; // the overdetermined fit is well conditioned
  const Eigen::Vector3d normal = c.plane.head<3>();
  Eigen::Vector3d t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  auto perturbed = [&](const Eigen::Vector3d &delta) {
    Eigen::Vector4d p;
    p << (normal + delta(0) * t1 + delta(1) * t2).normalized(), c.plane(3) * (1.0 + delta(2));
    return p;
  };
  Eigen::MatrixXd J(n, 3);
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    step(j) = h;
    const Eigen::Matrix3d plus = vpLaserSolvers::conicFromPlane(perturbed(step), c.cone);
    const Eigen::Matrix3d minus = vpLaserSolvers::conicFromPlane(perturbed(-step), c.cone);
    for (int i = 0; i < n; ++i) {
      // Signed Sampson distance: algebraic value over the gradient norm.
      auto signedDistance = [&](const Eigen::Matrix3d &conic) {
        const Eigen::Vector3d x(c.x[i](0), c.x[i](1), 1.0);
        const Eigen::Vector3d g = conic * x;
        return x.dot(g) / (2.0 * g.head<2>().norm());
      };
      J(i, j) = (signedDistance(plus) - signedDistance(minus)) / (2.0 * h);
    }
  }
  const double smallest = Eigen::JacobiSVD<Eigen::MatrixXd>(J).singularValues()(2);
  const double bound = smallest > 0.0 ? kBackwardError / smallest : std::numeric_limits<double>::infinity();
  return std::max(vspStress::kTolerance, bound);
}

/*!
  A plane is the truth or wrong: the trace of another plane differs from the data. A degenerate
  configuration excuses a refusal only: an answer given on it must be correct like any other, since a
  caller cannot tell it apart from an answer on a well-posed sample.
*/
void classify(Tally &t, long index, const Config &c, int n, bool degenerate, int candidates, double best, bool verbose)
{
  const bool answered = candidates > 0;
  const double bound = answered && best > vspStress::kTolerance ? roundingTolerance(c, n) : 0.0;
  if (bound > 0.0 && best <= bound) {
    ++t.correct; // correct to the conditioning of the configuration
    ++illConditionedCorrect;
    if (best > illConditionedError) {
      illConditionedError = best;
      illConditionedBound = bound;
    }
    return;
  }
  vspStress::classify(t, degenerate && !answered, answered, best, false, verbose,
                      [&](const char *what) { dump(what, index, c, n, best); });
}

//! Runs \e count configurations of \e n points through \e solve(config, best) -> number of candidates.
template <typename Solve>
Tally stress(long count, unsigned long seed, int n, bool verbose, Solve solve,
             bool (*degenerate)(const Config &, int) = closeSamples)
{
  std::mt19937_64 rng(seed);
  Tally t;
  Config c;
  illConditionedCorrect = 0;
  illConditionedError = illConditionedBound = 0.0;
  for (long k = 0; k < count; ++k) {
    if (!makeConfig(rng, n, c)) {
      ++t.skipped;
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    const int candidates = solve(c, best);
    classify(t, k, c, n, degenerate(c, n), candidates, best, verbose);
  }
  if (illConditionedCorrect > 0)
    std::printf("  %ld of the correct answers are off by more than 1e-6, within the rounding bound of their "
                "ill-conditioned configuration (largest %.2e, its bound %.2e)\n",
                illConditionedCorrect, illConditionedError, illConditionedBound);
  return t;
}

int solveGp3(const Config &c, double &best)
{
  Eigen::Vector4d planes[8];
  const int m = vpLaserSolvers::gp3Planes(c.x, c.cone, planes);
  for (int i = 0; i < m; ++i) {
    best = std::min(best, planeError(planes[i], c.plane));
  }
  return m;
}

//! An overdetermined fit on many exact points has no degenerate sample.
bool neverDegenerate(const Config &, int) { return false; }

/*!
  Two sample points on nearly the same epipolar line (within \e angle rad seen from the epipole): the
  canonical frame of PP-3 (eq. 36) maps the epipole and two points onto a line there, so the
  parametrisation of the PP-3 conics degenerates, whatever the ordering of the points.
*/
bool epipoleAligned(const Config &c, int n, double angle)
{
  const Eigen::Vector3d e = c.cone.apex;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const Eigen::Vector3d xi(c.x[i](0), c.x[i](1), 1.0), xj(c.x[j](0), c.x[j](1), 1.0);
      const Eigen::Vector3d li = e.cross(xi).normalized(), lj = e.cross(xj).normalized();
      if (li.cross(lj).norm() < angle)
        return true;
    }
  return false;
}

bool pp3Degenerate(const Config &c, int n)
{
  vpLaserSolvers::EpipolarTangents tangents;
  return closeSamples(c, n) || !vpLaserSolvers::epipolarTangents(c.cone, tangents) || epipoleAligned(c, n, 1e-2);
}

int solvePp3(const Config &c, double &best)
{
  vpLaserSolvers::EpipolarTangents tangents;
  if (!vpLaserSolvers::epipolarTangents(c.cone, tangents)) {
    return 0;
  }
  Eigen::Matrix3d conics[4];
  const int m = vpLaserSolvers::pp3Conics(c.x, tangents, conics);
  int planes = 0;
  for (int i = 0; i < m; ++i) {
    Eigen::Vector4d plane;
    if (vpLaserSolvers::planePair(conics[i], c.cone, plane)) {
      ++planes;
      best = std::min(best, planeError(plane, c.plane));
    }
  }
  return planes;
}

int solveConicThenPlanePair(const Config &c, int n, double &best)
{
  Eigen::Matrix3d conic;
  Eigen::Vector4d plane;
  if (!vpLaserSolvers::fitConic(c.x, n, conic) || !vpLaserSolvers::planePair(conic, c.cone, plane)) {
    return 0;
  }
  best = planeError(plane, c.plane);
  return 1;
}

} // namespace

int main(int argc, char **argv)
{
  vspStress::Options o;
  int exitStatus = 0;
  if (!vspStress::parseOptions(argc, argv, "--method", {"gp3", "pp3", "pp5", "planepair", "all"}, "all", "1e6", o,
                               exitStatus))
    return exitStatus;
  const bool all = o.solver == "all";
  bool ok = true;
  if (all || o.solver == "gp3") {
    ok = vspStress::report("GP3", o.count, stress(o.count, o.seed, 3, o.verbose, solveGp3)) && ok;
  }
  if (all || o.solver == "pp3") {
    ok = vspStress::report("PP3", o.count, stress(o.count, o.seed, 3, o.verbose, solvePp3, pp3Degenerate)) && ok;
  }
  if (all || o.solver == "pp5") {
    const auto pp5 = [](const Config &c, double &b) { return solveConicThenPlanePair(c, 5, b); };
    ok = vspStress::report("PP5", o.count, stress(o.count, o.seed, 5, o.verbose, pp5)) && ok;
  }
  if (all || o.solver == "planepair") {
    const auto planePair = [](const Config &c, double &b) { return solveConicThenPlanePair(c, kPlanePairPoints, b); };
    ok = vspStress::report("PLANE_PAIR", o.count,
                           stress(o.count, o.seed, kPlanePairPoints, o.verbose, planePair, neverDegenerate)) &&
         ok;
  }
  return ok ? 0 : 1;
}
