/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpRansac.h
  \brief A generic RANSAC loop with adaptive stopping and local optimisation, templated on a
  minimal solver ("estimator"), shared by the gravity-aided pose and the circular-laser modules.
*/
#ifndef VP_SENSOR_RANSAC_H
#define VP_SENSOR_RANSAC_H

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <visp3/core/vpConfig.h>

/*!
  \ingroup group_robust
  \brief Settings of vpRansacLoop().
*/
struct vpRansacOptions
{
  double threshold = 1.0;   //!< Inlier threshold on the residual returned by the estimator (same unit).
  double probability = 0.99; //!< Confidence p that one all-inlier sample was drawn (paper eq. 28).
  int maxTrials = 1000;      //!< Hard cap on the number of minimal samples.
  int minTrials = 0;         //!< Samples drawn at least, whatever the adaptive count says.
  unsigned int seed = 0;     //!< Seed of the sampler: the same seed gives the same result.
  bool localOptimisation = true; //!< Refit each new best model on its inliers (LO-RANSAC).
};

/*!
  \ingroup group_robust
  \brief What vpRansacLoop() did.
*/
struct vpRansacReport
{
  int trials = 0;              //!< Minimal samples drawn.
  int models = 0;              //!< Hypotheses scored (a sample may give several, or none).
  int inlierCount = 0;         //!< Inliers of the returned model.
  double score = 0.0;          //!< Sum of truncated squared residuals of the returned model (lower is better).
  std::vector<int> inliers;    //!< Indices of the inliers of the returned model.
};

/*!
  Number of RANSAC trials that draw, with probability \e p, at least one sample of \e s points free
  of outliers when a fraction \e outlierRatio of the data are outliers:
  \f$ N = \log(1-p) / \log(1-(1-\epsilon)^s) \f$ (Boutteau et al., JMIV 2018, eq. 28).
  Saturates at \e maxTrials; returns 0 when there are no outliers and 1 for p <= 0.
*/
int vpRansacTrialCount(double probability, double outlierRatio, int sampleSize, int maxTrials);

/*!
  \ingroup group_robust
  \brief Draws \e k distinct indices in [0, n) with a seeded Mersenne twister, without allocating.
*/
class vpRansacSampler
{
public:
  //! Sampler over [0, n) drawing k-subsets, seeded for reproducibility.
  vpRansacSampler(int n, unsigned int seed) : m_n(n), m_rng(seed) {}
  //! Writes k distinct indices into \e out (k must be <= n; k is small, rejection is cheap).
  void draw(int k, int *out)
  {
    std::uniform_int_distribution<int> pick(0, m_n - 1);
    for (int i = 0; i < k; ++i) {
      bool fresh = false;
      while (!fresh) {
        out[i] = pick(m_rng);
        fresh = true;
        for (int j = 0; j < i; ++j)
          fresh = fresh && (out[j] != out[i]);
      }
    }
  }

private:
  int m_n;
  std::mt19937 m_rng;
};

/*!
  \ingroup group_robust
  \brief The RANSAC loop of Fischler and Bolles with the adaptive trial count of eq. 28, MSAC-style
  tie break and optional local optimisation.

  The \e Estimator type supplies:
  - `using Model = ...;` a copyable hypothesis;
  - `static constexpr int kSampleSize` (points per minimal sample) and
    `static constexpr int kMaxModels` (hypotheses per sample at most);
  - `int size() const`: the number of data;
  - `int solveMinimal(const int *sample, Model *models) const`: fills up to kMaxModels hypotheses
    from kSampleSize indices and returns how many (0 for a degenerate sample);
  - `double residual(const Model &m, int i) const`: error of datum i (unit of options.threshold);
  - `bool refine(const std::vector<int> &inliers, Model &m) const`: refit on inliers (may return false).

  A datum is an inlier when residual < threshold. Hypotheses are ranked by inlier count, then by
  the sum of truncated squared residuals. The loop stops after the adaptive count computed from the
  best inlier ratio so far, at least options.minTrials and at most options.maxTrials samples.

  \return true when a model with at least kSampleSize inliers was found; then \e best and \e report
  describe it.
*/
template <class Estimator>
bool vpRansacLoop(const Estimator &estimator, const vpRansacOptions &options,
                  typename Estimator::Model &best, vpRansacReport &report)
{
  using Model = typename Estimator::Model;
  constexpr int s = Estimator::kSampleSize;
  const int n = estimator.size();
  report = vpRansacReport();
  if (n < s || options.maxTrials <= 0 || !(options.threshold > 0.0))
    return false;

  const double thr2 = options.threshold * options.threshold;
  // Inlier count and truncated squared cost of a model; optionally collects the inlier indices.
  auto score = [&](const Model &m, std::vector<int> *inliers) {
    int count = 0;
    double cost = 0.0;
    if (inliers)
      inliers->clear();
    for (int i = 0; i < n; ++i) {
      const double r = estimator.residual(m, i);
      const double r2 = r * r;
      if (r2 < thr2) { // NaN residuals are never inliers
        ++count;
        cost += r2;
        if (inliers)
          inliers->push_back(i);
      } else {
        cost += thr2;
      }
    }
    return std::make_pair(count, cost);
  };
  auto better = [](const std::pair<int, double> &a, const std::pair<int, double> &b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  };

  vpRansacSampler sampler(n, options.seed);
  std::array<int, s> sample{};
  std::array<Model, Estimator::kMaxModels> hypotheses{};
  std::pair<int, double> bestScore(0, std::numeric_limits<double>::infinity());
  int needed = options.maxTrials;
  int trial = 0;
  for (; trial < needed || trial < options.minTrials; ++trial) {
    if (trial >= options.maxTrials)
      break;
    sampler.draw(s, sample.data());
    const int count = estimator.solveMinimal(sample.data(), hypotheses.data());
    for (int k = 0; k < count; ++k) {
      ++report.models;
      std::pair<int, double> sc = score(hypotheses[k], nullptr);
      if (!better(sc, bestScore))
        continue;
      best = hypotheses[k];
      bestScore = sc;
      if (options.localOptimisation && sc.first > s) {
        // Local optimisation: refit on the consensus set, keep the refit only if it scores better.
        Model refit = best;
        std::vector<int> inliers;
        score(best, &inliers);
        if (estimator.refine(inliers, refit)) {
          std::pair<int, double> rs = score(refit, nullptr);
          if (better(rs, bestScore)) {
            best = refit;
            bestScore = rs;
          }
        }
      }
      needed = vpRansacTrialCount(options.probability, 1.0 - double(bestScore.first) / n, s, options.maxTrials);
    }
  }
  report.trials = trial;
  if (bestScore.first < s)
    return false;
  const std::pair<int, double> fin = score(best, &report.inliers);
  report.inlierCount = fin.first;
  report.score = fin.second;
  return true;
}

#endif
