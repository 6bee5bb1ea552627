/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpPolynomialRoots.h
  \brief The roots of a polynomial of degree at most 4 (Aberth-Ehrlich iteration): the quartics of the
  gravity-aided least squares (the stationary points of the yaw's cost) and of the laser's PP-3 solver
  share it.
*/
#ifndef VP_POLYNOMIAL_ROOTS_H
#define VP_POLYNOMIAL_ROOTS_H

#include <complex>

#include <visp3/core/vpConfig.h>

/*!
  Roots of k[0] + k[1] u + k[2] u^2 + k[3] u^3 + k[4] u^4.

  The degree is lowered while the leading coefficient is at most 1e-14 times the largest one in absolute
  value (a quartic whose leading term vanishes is solved as the cubic it is). The roots of degree 2 to 4
  come from the Aberth-Ehrlich simultaneous iteration (complex roots included, in no particular order):
  simple roots to about the rounding of their value, a double root to about the square root of the
  rounding, the two copies slightly apart, and a real root may carry a tiny imaginary part. Callers keep
  the ones they need and polish them on their own equation.

  \param k : the five coefficients, constant term first (unused high-order ones set to 0).
  \param roots : receives the roots, roots[0, returned count).
  \return the number of roots written, which is the degree found: 0 for a constant or zero polynomial, or
  when a coefficient is not finite. No allocation.
*/
VISP_EXPORT int vpPolynomialRoots(const double k[5], std::complex<double> roots[4]);

#endif
