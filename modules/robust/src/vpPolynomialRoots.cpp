/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/robust/vpPolynomialRoots.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

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
  int degree = 4;
  while (degree > 0 && std::abs(k[degree]) <= 1e-14 * scale)
    --degree;
  if (degree == 0)
    return 0;
  if (degree == 1) {
    roots[0] = -k[0] / k[1];
    return 1;
  }
  // One dynamic size bounded by 4 (storage on the stack): one instantiation of the solver for every degree.
  using Companion = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
  Companion companion = Companion::Zero(degree, degree);
  for (int i = 0; i < degree; ++i)
    companion(0, i) = -k[degree - 1 - i] / k[degree];
  for (int i = 1; i < degree; ++i)
    companion(i, i - 1) = 1.0;
  const Eigen::EigenSolver<Companion> eig(companion, false);
  if (eig.info() != Eigen::Success)
    return 0;
  for (int i = 0; i < degree; ++i)
    roots[i] = eig.eigenvalues()(i);
  return degree;
}
