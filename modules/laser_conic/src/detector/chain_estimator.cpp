/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Five-point conics sampled chain by chain: see chain_estimator.h.
#include "chain_estimator.h"

#include <unordered_map>

#include "guided_detail.h"

namespace vsp::laser_detector
{
namespace
{
// Draws of a point outside the chains already taken before the sample falls back to points one by one: a
// chain of nearly all the points leaves the others a small chance per draw.
constexpr int kOutsideTries = 16;
} // namespace

ChainPp5Estimator::ChainPp5Estimator(const vsp::laser_estimators::PointList &points, const std::vector<int> &chainOf)
  : Pp5Estimator(points), m_rank(chainOf.size())
{
  std::unordered_map<int, size_t> rankOf;
  for (size_t k = 0; k < chainOf.size(); ++k)
    m_rank[k] = rankOf.emplace(chainOf[k], rankOf.size()).first->second;
  groupByKey(m_rank, rankOf.size(), m_start, m_members);
}

int ChainPp5Estimator::drawOutside(vpRansacSampler &sampler, const int *sample, int taken) const
{
  for (int attempt = 0; attempt < kOutsideTries; ++attempt) {
    const int p = sampler.index(size());
    bool outside = true;
    for (int j = 0; j < taken; ++j)
      outside = outside && m_rank[static_cast<size_t>(p)] != m_rank[static_cast<size_t>(sample[j])];
    if (outside)
      return p;
  }
  return -1;
}

int ChainPp5Estimator::drawPartner(vpRansacSampler &sampler, int point) const
{
  const size_t chain = m_rank[static_cast<size_t>(point)];
  const size_t first = m_start[chain], count = m_start[chain + 1] - first;
  if (count < 2)
    return -1;
  // One of the chain's other points, uniformly: the k-th member, skipping the point itself.
  const int partner =
      static_cast<int>(m_members[first + static_cast<size_t>(sampler.index(static_cast<int>(count) - 1))]);
  return partner == point ? static_cast<int>(m_members[first + count - 1]) : partner;
}

void ChainPp5Estimator::drawSample(vpRansacSampler &sampler, int *sample) const
{
  // Every other sample, on average, five points drawn one by one: a ring that is one or two long chains among
  // the clutter's has no three chains to draw.
  if (static_cast<int>(m_rank.size()) != size() || size() < kSampleSize || sampler.index(2) == 0) {
    sampler.draw(kSampleSize, sample);
    return;
  }
  // Chains A, B, C: points 0 and 1 of A, 2 and 3 of B, 4 of C.
  sample[0] = sampler.index(size());
  sample[1] = drawPartner(sampler, sample[0]);
  sample[2] = sample[1] < 0 ? -1 : drawOutside(sampler, sample, 2);
  sample[3] = sample[2] < 0 ? -1 : drawPartner(sampler, sample[2]);
  sample[4] = sample[3] < 0 ? -1 : drawOutside(sampler, sample, 4);
  if (sample[4] < 0)
    sampler.draw(kSampleSize, sample);
}
} // namespace vsp::laser_detector
