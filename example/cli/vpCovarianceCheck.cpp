/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
#include "vpCovarianceCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace
{
//! The 95 % point of the chi-square law of 3 degrees of freedom.
const double kChiSquare3At95 = 7.815;
} // namespace

void vpCovarianceCheck::add(const vpColVector &error, const vpMatrix &covariance)
{
  if (error.size() != 3 || covariance.getRows() != 3 || covariance.getCols() != 3) {
    ++m_notUsable;
    return;
  }
  // Scaled to unit diagonal before the solve: altitude (m^2) and angles (rad^2) differ by orders of magnitude,
  // and a determinant of 1e-28 is refused by vpMatrix's inverse.
  double scale[3];
  for (unsigned int i = 0; i < 3; ++i) {
    const double d = covariance[i][i];
    if (!(d > 0.0) || !std::isfinite(d) || !std::isfinite(error[i])) {
      ++m_notUsable;
      return;
    }
    scale[i] = 1.0 / std::sqrt(d);
  }
  vpMatrix P(3, 3);
  vpColVector e(3);
  for (unsigned int i = 0; i < 3; ++i) {
    e[i] = error[i] * scale[i];
    for (unsigned int j = 0; j < 3; ++j)
      P[i][j] = covariance[i][j] * scale[i] * scale[j];
  }
  if (!(P.det() > 1e-12)) { // not positive definite (a correlation of one)
    ++m_notUsable;
    return;
  }
  const double nees = e.t() * P.inverseByLU() * e;
  if (std::isfinite(nees))
    m_nees.push_back(nees);
  else
    ++m_notUsable;
}

double vpCovarianceCheck::median() const
{
  if (m_nees.empty())
    return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted = m_nees;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  return sorted[sorted.size() / 2];
}

double vpCovarianceCheck::shareOver95() const
{
  if (m_nees.empty())
    return std::numeric_limits<double>::quiet_NaN();
  const auto over = std::count_if(m_nees.begin(), m_nees.end(), [](double v) { return v > kChiSquare3At95; });
  return static_cast<double>(over) / static_cast<double>(m_nees.size());
}

std::string vpCovarianceCheck::summary(double inflation) const
{
  std::ostringstream os;
  os << "covariance of (altitude, roll, pitch) at variance scale " << inflation << ": NEES median " << median()
     << " over " << count() << " frames (2.37 if honest), " << 100.0 * shareOver95() << " % over 7.81 (5 % if honest)";
  if (m_notUsable > 0)
    os << ", " << m_notUsable << " frames without a usable covariance";
  return os.str();
}
