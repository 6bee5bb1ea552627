/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Plane-pair solution (Boutteau et al., JMIV 2018, Sec. 4 and appendix A).
#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace vpLaserSolvers
{
namespace
{
/*!
  Abscissa of the double root of det(C + x D). The determinant is a quartic whose roots are 0,
  infinity (det C = det D = 0) and a double root: p(x) = x (a1 + a2 x + a3 x^2). The quadratic
  factor's roots split (or go complex) under noise; their midpoint -a2 / (2 a3) is linear in the
  coefficients, hence stable, unlike the roots themselves (a double root moves with sqrt(noise)).
  The coefficients come from det() at x = +-1, +-2 (central differences of a quartic are exact).
*/
bool doubleRoot(const Eigen::Matrix4d &C, const Eigen::Matrix4d &D, double &x)
{
  const double pp1 = (C + D).determinant(), pm1 = (C - D).determinant();
  const double pp2 = (C + 2.0 * D).determinant(), pm2 = (C - 2.0 * D).determinant();
  const double p0 = C.determinant();
  // p(x) = a0 + a1 x + a2 x^2 + a3 x^3 + a4 x^4 sampled at -2..2.
  const double even1 = 0.5 * (pp1 + pm1) - p0; // a2 + a4
  const double even2 = 0.5 * (pp2 + pm2) - p0; // 4 a2 + 16 a4
  const double odd1 = 0.5 * (pp1 - pm1);       // a1 + a3
  const double odd2 = 0.5 * (pp2 - pm2);       // 2 a1 + 8 a3
  const double a2 = (16.0 * even1 - even2) / 12.0;
  const double a3 = (odd2 - 2.0 * odd1) / 6.0;
  if (!(std::abs(a3) > 0.0) || !std::isfinite(a2))
    return false;
  x = -a2 / (2.0 * a3);
  return std::isfinite(x);
}

//! Scales a plane to a unit normal pointing towards the camera centre (d > 0).
Eigen::Vector4d normalisedGroundPlane(const Eigen::Vector4d &p)
{
  Eigen::Vector4d q = p / p.head<3>().norm();
  if (q(3) < 0.0)
    q = -q;
  return q;
}
} // namespace

bool planePair(const Eigen::Matrix3d &c, const LaserCone &cone, Eigen::Vector4d &plane)
{
  Eigen::Matrix4d C = cameraConeQuadric(c);
  Eigen::Matrix4d D = laserConeQuadric(cone);
  const double nc = C.norm(), nd = D.norm();
  if (!(nc > 0.0) || !(nd > 0.0) || !std::isfinite(nc) || !std::isfinite(nd))
    return false;
  C /= nc;
  D /= nd;

  // Two passes: the second rescales D so that the root is near 1, where the sampled
  // abscissae +-1, +-2 give the best-conditioned coefficients.
  double x = 0.0;
  if (!doubleRoot(C, D, x))
    return false;
  double scale = std::abs(x) > 0.0 ? x : 1.0;
  double y = 0.0;
  if (!doubleRoot(C, scale * D, y))
    return false;
  const Eigen::Matrix4d Q = C + (y * scale) * D;

  // Rank-2 quadric of a plane pair: eigenvalues l1 > 0 > l2 (appendix A.1), Q = U V^T + V U^T with
  // U, V = sqrt(l1) a1 +- sqrt(-l2) a2.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(Q);
  if (eig.info() != Eigen::Success)
    return false;
  const Eigen::Vector4d &l = eig.eigenvalues(); // ascending
  const double lpos = l(3), lneg = l(0);
  if (!(lpos > 0.0) || !(lneg < 0.0))
    return false;
  const Eigen::Vector4d a1 = std::sqrt(lpos) * eig.eigenvectors().col(3);
  const Eigen::Vector4d a2 = std::sqrt(-lneg) * eig.eigenvectors().col(0);
  const Eigen::Vector4d candidates[2] = {a1 + a2, a1 - a2};

  // The ground plane has both optical centres on its side; the other plane separates them.
  const Eigen::Vector4d apex(cone.apex(0), cone.apex(1), cone.apex(2), 1.0);
  int chosen = -1;
  double bestMargin = 0.0;
  for (int k = 0; k < 2; ++k) {
    if (!(candidates[k].head<3>().norm() > 0.0))
      continue;
    const Eigen::Vector4d p = normalisedGroundPlane(candidates[k]);
    const double camSide = p(3), apexSide = p.dot(apex);
    if (!(camSide > 0.0) || !(apexSide > 0.0))
      continue;
    // Under noise both planes may pass the test; the ground plane is the farther one from the
    // centres (the separating plane lies within a baseline of both).
    const double margin = std::min(camSide, apexSide);
    if (chosen < 0 || margin > bestMargin) {
      chosen = k;
      bestMargin = margin;
      plane = p;
    }
  }
  return chosen >= 0;
}
} // namespace vpLaserSolvers
