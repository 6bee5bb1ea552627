/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file vpCovarianceCheck.h
  \brief Whether the per-frame covariance of (altitude, roll, pitch) is honest on a sequence with ground truth:
  the normalised estimation error squared (NEES) of each frame, summarised by vsp-laser-altimeter --truth.
*/
#ifndef VP_COVARIANCE_CHECK_H
#define VP_COVARIANCE_CHECK_H

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>

/*!
  NEES e^T P^-1 e of 3-vectors of errors e with their covariances P. With an honest covariance and Gaussian
  errors the NEES follows a chi-square law of 3 degrees of freedom: median 2.37, 5 % of the frames over 7.81.
  A median far above says the covariance a filter fuses (vpLaserConicFilter) is too small on these frames, far
  below that it is too large.
*/
class vpCovarianceCheck
{
public:
  /*!
    Adds the NEES of \e error (3) with \e covariance (3 x 3); a covariance that is not finite or not positive
    definite is counted apart (notUsable()).
  */
  void add(const vpColVector &error, const vpMatrix &covariance);
  //! Frames added with a usable covariance.
  size_t count() const { return m_nees.size(); }
  //! Frames whose covariance was not usable.
  size_t notUsable() const { return m_notUsable; }
  //! Median NEES (NaN without a frame).
  double median() const;
  //! Share of the frames whose NEES exceeds 7.81, the 95 % point of the chi-square law of 3 degrees of freedom.
  double shareOver95() const;
  /*!
    Share of the frames whose error in component \e k (0 altitude, 1 roll, 2 pitch) lies within 3 of its
    standard deviations, the square roots of the covariance's diagonal (what vsp-laser-altimeter writes in its
    sd_* columns): 99.7 % for honest standard deviations and Gaussian errors.
  */
  double shareWithin3Sd(unsigned int k) const;
  /*!
    One line: the variance scale \e inflation of the covariance, the median NEES, the share over 7.81 and the
    shares within 3 standard deviations.
  */
  std::string summary(double inflation) const;

private:
  std::vector<double> m_nees;
  size_t m_within3Sd[3] = {0, 0, 0}; //!< usable frames whose error k lies within 3 standard deviations
  size_t m_notUsable = 0;
};

#endif
