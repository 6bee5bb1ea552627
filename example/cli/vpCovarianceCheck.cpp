/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
#include "vpCovarianceCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Cholesky>

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
  Eigen::Vector3d e;
  Eigen::Matrix3d P;
  for (unsigned int i = 0; i < 3; ++i) {
    e(i) = error[i];
    for (unsigned int j = 0; j < 3; ++j)
      P(i, j) = covariance[i][j];
  }
  // A Cholesky factor exists only for a positive definite matrix, whatever its units (m^2 beside rad^2): no
  // determinant threshold to choose.
  const Eigen::LLT<Eigen::Matrix3d> cholesky(P);
  if (!e.allFinite() || !P.allFinite() || cholesky.info() != Eigen::Success) {
    ++m_notUsable;
    return;
  }
  m_nees.push_back(e.dot(cholesky.solve(e)));
  for (int k = 0; k < 3; ++k)
    m_within3Sd[k] += std::abs(e(k)) <= 3.0 * std::sqrt(P(k, k)) ? 1 : 0;
}

double vpCovarianceCheck::shareWithin3Sd(unsigned int k) const
{
  if (m_nees.empty() || k > 2)
    return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(m_within3Sd[k]) / static_cast<double>(m_nees.size());
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
     << " over " << count() << " frames (2.37 if honest), " << 100.0 * shareOver95() << " % over 7.81 (5 % if honest); "
     << "errors within 3 standard deviations: altitude " << 100.0 * shareWithin3Sd(0) << " %, roll "
     << 100.0 * shareWithin3Sd(1) << " %, pitch " << 100.0 * shareWithin3Sd(2) << " % (99.7 % if honest)";
  if (m_notUsable > 0)
    os << ", " << m_notUsable << " frames without a usable covariance";
  return os.str();
}
