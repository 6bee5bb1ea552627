/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpPolynomialRoots.h: the roots of polynomials built from known roots, the degree lowered when
// the leading coefficients vanish, and the refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <limits>
#include <random>
#include <vector>

#include <visp3/robust/vpPolynomialRoots.h>

namespace
{
// Coefficients (constant first) of lead * prod (u - r_i), padded with zeros to five.
std::vector<double> fromRoots(const std::vector<std::complex<double> > &r, double lead)
{
  std::vector<std::complex<double> > c{lead};
  for (const auto &root : r) {
    std::vector<std::complex<double> > next(c.size() + 1, 0.0);
    for (size_t i = 0; i < c.size(); ++i) {
      next[i + 1] += c[i];
      next[i] -= root * c[i];
    }
    c = next;
  }
  std::vector<double> k(5, 0.0);
  for (size_t i = 0; i < c.size(); ++i)
    k[i] = c[i].real();
  return k;
}

// Every expected root has a computed one within tol (relative to 1 + |root|), and the counts agree.
void expectRoots(const std::vector<double> &k, const std::vector<std::complex<double> > &expected, double tol)
{
  std::complex<double> roots[4];
  const int n = vpPolynomialRoots(k.data(), roots);
  ASSERT_EQ(n, static_cast<int>(expected.size()));
  for (const auto &e : expected) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
      best = std::min(best, std::abs(roots[i] - e));
    EXPECT_LE(best, tol * (1.0 + std::abs(e))) << "root " << e;
  }
}
} // namespace

// Simple roots of random quartics, cubics and quadratics (real and complex pairs, leading coefficients
// from 1e-3 to 1e3): well separated simple roots of moderate size are found to about 1e-14; 1e-9 leaves
// room for the conditioning of the random draws.
TEST(RobustPolynomialRoots, RandomPolynomialsOfKnownRoots)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-3.0, 3.0), logLead(-3.0, 3.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int degree = 2 + trial % 3;
    std::vector<std::complex<double> > r;
    while (static_cast<int>(r.size()) < degree) {
      if (degree - static_cast<int>(r.size()) >= 2 && trial % 2 == 0) {
        const std::complex<double> z(value(rng), 0.2 + std::abs(value(rng)));
        r.push_back(z);
        r.push_back(std::conj(z));
      } else {
        r.emplace_back(value(rng), 0.0);
      }
    }
    // Roots closer than 0.05 are ill-conditioned (a double root loses half the digits): drawn again.
    bool separated = true;
    for (size_t i = 0; i < r.size(); ++i)
      for (size_t j = i + 1; j < r.size(); ++j)
        separated = separated && std::abs(r[i] - r[j]) > 0.05;
    if (!separated)
      continue;
    expectRoots(fromRoots(r, std::pow(10.0, logLead(rng))), r, 1e-9);
  }
}

// A leading coefficient at 1e-16 of the others is dropped: the quartic is solved as its cubic.
TEST(RobustPolynomialRoots, NegligibleLeadingCoefficientLowersTheDegree)
{
  std::vector<double> k = fromRoots({1.0, -2.0, 0.5}, 2.0);
  k[4] = 1e-16;
  expectRoots(k, {1.0, -2.0, 0.5}, 1e-12);
  expectRoots({3.0, -1.5, 0.0, 0.0, 0.0}, {2.0}, 1e-15); // linear: -k0 / k1
}

// Roots of very different sizes (the start circle is set by the largest) and a root at zero.
TEST(RobustPolynomialRoots, RootsOfDifferentScalesAndZero)
{
  expectRoots(fromRoots({1e-4, -1.0, 1e3, 30.0}, 1.0), {1e-4, -1.0, 1e3, 30.0}, 1e-10);
  expectRoots(fromRoots({0.0, 2.0, std::complex<double>(-1.0, 3.0), std::complex<double>(-1.0, -3.0)}, -0.5),
              {0.0, 2.0, std::complex<double>(-1.0, 3.0), std::complex<double>(-1.0, -3.0)}, 1e-12);
}

// A double root splits into two roots about sqrt(eps) apart: each within 1e-7 of it.
TEST(RobustPolynomialRoots, DoubleRoot)
{
  expectRoots(fromRoots({0.7, 0.7, -1.0, 2.0}, 1.0), {0.7, 0.7, -1.0, 2.0}, 1e-7);
}

TEST(RobustPolynomialRoots, RefusesConstantZeroAndNonFinitePolynomials)
{
  std::complex<double> roots[4];
  const double zero[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, constant[5] = {2.0, 0.0, 0.0, 0.0, 0.0};
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double withNan[5] = {1.0, nan, 0.0, 0.0, 1.0}, withInf[5] = {1.0, 2.0, inf, 0.0, 1.0};
  EXPECT_EQ(vpPolynomialRoots(zero, roots), 0);
  EXPECT_EQ(vpPolynomialRoots(constant, roots), 0);
  EXPECT_EQ(vpPolynomialRoots(withNan, roots), 0);
  EXPECT_EQ(vpPolynomialRoots(withInf, roots), 0);
}
