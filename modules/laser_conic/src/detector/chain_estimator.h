/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file chain_estimator.h
  \brief Five-point conics sampled chain by chain (internal header): the RANSAC estimator of the ellipse that
  locates a ring broken into short pieces among clutter.
*/
#ifndef VP_LASER_CHAIN_ESTIMATOR_H
#define VP_LASER_CHAIN_ESTIMATOR_H

#include <vector>

#include <visp3/robust/vpRansac.h>

#include "../laser_estimators.h"

namespace vsp::laser_detector
{
/*!
  PP-5 over points that come in chains (the first pass's linked crossings): each minimal sample takes two
  points of one chain, two of a second and one of a third, each chain drawn with a probability proportional
  to its points (see vpRansacLoop(), drawSample()). Through strong JPEG on a colourful floor the ring is a few
  dozen pieces of 15-50 px among several times as many pieces of the patches' red edges: five points drawn
  one by one all lie on the ring once in a few thousand samples, and then often on one or two pieces, whose
  conic is any curve through them. Three chains drawn by their points all lie on the ring about once in a
  hundred samples, spread round it. Half the samples are still drawn point by point: a ring that is one or two
  long chains has no three chains to draw.
*/
class ChainPp5Estimator : public vsp::laser_estimators::Pp5Estimator
{
public:
  /*!
    \e points and the chain of each (any integer labels, one per point); \e points must outlive the estimator.
  */
  ChainPp5Estimator(const vsp::laser_estimators::PointList &points, const std::vector<int> &chainOf);
  /*!
    Five distinct indices: with probability one half, two of the chain of a point drawn at random, two of the
    chain of another drawn outside it, one of a third chain; otherwise, and where the chains do not allow it
    (fewer than three chains, or a chain of one point), five drawn one by one.
  */
  void drawSample(vpRansacSampler &sampler, int *sample) const;

private:
  //! A point drawn at random outside the chains of sample[0, taken) (a few tries, then -1).
  int drawOutside(vpRansacSampler &sampler, const int *sample, int taken) const;
  //! Another point of the chain of \e point (-1 when that chain has no other).
  int drawPartner(vpRansacSampler &sampler, int point) const;

  std::vector<size_t> m_rank;    //!< chain of each point, numbered from 0
  std::vector<size_t> m_start;   //!< the members of chain c are m_members[m_start[c], m_start[c + 1])
  std::vector<size_t> m_members; //!< the points, chain by chain
};
} // namespace vsp::laser_detector

#endif
