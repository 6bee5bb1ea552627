/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The roots by the Aberth-Ehrlich iteration: Newton's step of each root, corrected by the repulsion of the
// others, so that the estimates converge to distinct roots (cubically for simple roots, linearly for a
// multiple one) from any start off the real axis. Eigen's general eigenvalue solver on the companion
// matrix gives the same roots but took 20 to 35 seconds to compile (and clang-tidy as long to read).
#include <visp3/robust/vpPolynomialRoots.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
//! Iterations of the simultaneous update at most: a quartic's simple roots take 5 to 15, a double root
//! converges linearly to about the square root of the rounding in about 60.
constexpr int kMaxIterations = 200;

//! p(z) / p'(z) of the monic polynomial a[0] + a[1] z + ... + z^n (a[n] = 1), by Horner's scheme. \e atRounding:
//! |p(z)| is within the rounding error of its evaluation (z is a root to working precision).
std::complex<double> newtonRatio(const double *a, int n, std::complex<double> z, bool &flat, bool &atRounding)
{
  std::complex<double> p(1.0, 0.0), d(0.0, 0.0);
  double bound = 1.0; // sum of |a_i| |z|^i, by the same scheme
  const double r = std::abs(z);
  for (int i = n - 1; i >= 0; --i) {
    d = d * z + p;
    p = p * z + a[i];
    bound = bound * r + std::abs(a[i]);
  }
  atRounding = std::abs(p) <= 8.0 * n * std::numeric_limits<double>::epsilon() * bound;
  flat = std::abs(d) == 0.0 && std::abs(p) > 0.0;
  return std::abs(d) == 0.0 ? std::complex<double>(0.0, 0.0) : p / d;
}

//! Radius of the starting circle: the largest |a_{n-j}|^(1/j), a bound of the roots' moduli within a factor 2.
double startRadius(const double *a, int n)
{
  double r = 0.0;
  for (int j = 1; j <= n; ++j)
    r = std::max(r, std::pow(std::abs(a[n - j]), 1.0 / j));
  return r > 0.0 ? r : 1.0;
}
} // namespace

int vpPolynomialRoots(const double k[5], std::complex<double> roots[4])
{
  double scale = 0.0;
  for (int i = 0; i < 5; ++i) {
    if (!std::isfinite(k[i]))
      return 0;
    scale = std::max(scale, std::abs(k[i]));
  }
  if (!(scale > 0.0))
    return 0;
  int n = 4;
  while (n > 0 && std::abs(k[n]) <= 1e-14 * scale)
    --n;
  if (n == 0)
    return 0;
  double a[5];
  for (int i = 0; i <= n; ++i)
    a[i] = k[i] / k[n];
  // Starts on a circle, turned off the real axis (a real polynomial's iteration started on the axis would
  // stay on it and never reach a complex pair).
  const double r = startRadius(a, n);
  if (!std::isfinite(r))
    return 0; // the leading coefficient underflows against the others
  for (int j = 0; j < n; ++j) {
    const double angle = 2.0 * 3.14159265358979323846 * j / n + 0.4;
    roots[j] = std::complex<double>(r * std::cos(angle), r * std::sin(angle));
  }
  // A root whose value is within the rounding of its evaluation is final: further steps only move it in
  // the rounding noise (and a criterion on the step's size alone would never be met there).
  bool done[4] = {false, false, false, false};
  for (int it = 0; it < kMaxIterations; ++it) {
    bool converged = true;
    for (int j = 0; j < n; ++j) {
      if (done[j])
        continue;
      bool flat = false, atRounding = false;
      const std::complex<double> ratio = newtonRatio(a, n, roots[j], flat, atRounding);
      if (atRounding) {
        done[j] = true;
        continue;
      }
      converged = false;
      if (flat) { // a stationary point that is no root (p' = 0): moved off it, off the real axis
        roots[j] += std::complex<double>(1e-3, 1e-3) * (1.0 + std::abs(roots[j]));
        continue;
      }
      std::complex<double> repulsion(0.0, 0.0);
      for (int m = 0; m < n; ++m)
        if (m != j && roots[m] != roots[j])
          repulsion += 1.0 / (roots[j] - roots[m]);
      const std::complex<double> step = ratio / (1.0 - ratio * repulsion);
      if (std::isfinite(step.real()) && std::isfinite(step.imag()))
        roots[j] -= step;
    }
    if (converged)
      break;
  }
  return n;
}
