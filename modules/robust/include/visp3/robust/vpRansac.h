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

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <utility>
#include <vector>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>

/*!
  \ingroup group_robust
  \brief Settings of vpRansacLoop().
*/
struct vpRansacOptions
{
  double threshold = 1.0;        //!< Inlier threshold on the residual returned by the estimator (same unit).
  double probability = 0.99;     //!< Confidence p that one all-inlier sample was drawn (paper eq. 28).
  int maxTrials = 1000;          //!< Hard cap on the number of minimal samples.
  int minTrials = 0;             //!< Samples drawn at least, whatever the adaptive count says.
  unsigned int seed = 0;         //!< Seed of the sampler: the same seed gives the same result.
  bool localOptimisation = true; //!< Refit each new best model on its inliers (LO-RANSAC).
  /*!
    Refits of the local optimisation at most: a refit that gathers more inliers than the model it
    started from is refitted again on its own consensus set.
  */
  int localRounds = 1;
  /*!
    Relative gain of inliers over the last locally optimised model that a new best model needs for
    its own local optimisation (0: every new best model is refitted). Once a refit has gathered the
    consensus, the later best models are mostly other samples of the same structure, a few inliers
    better: refitting them again costs a full scoring per round and seldom changes the consensus.
  */
  double localOptimisationGain = 0.0;
  /*!
    Size of the preemptive test subset (0 disables the test): a fixed random subset of the data, drawn
    once per call, on which every hypothesis of the main loop is scored first, by blocks of
    vpRansacPretestBlock data. A hypothesis is dropped before the full scoring as soon as its inliers
    on the subset make it implausible that it has as many inliers as the best model so far
    (Chernoff-Hoeffding bound of the binomial tail, risk pretestRisk per look): most hypotheses of a
    contaminated data set are dropped after a few data instead of being scored on about half of them.
    Only worth it for large data sets (ignored when the data are fewer than four times the subset, rounded
    up to whole blocks).
  */
  int pretestSize = 0;
  /*!
    Probability bound of dropping, by the preemptive test, a hypothesis that has at least as many
    inliers as the best model so far (per look at the subset).
  */
  double pretestRisk = 1e-3;
};

//! Data scored at a time by the preemptive test of vpRansacLoop() (see vpRansacOptions::pretestSize).
constexpr int vpRansacPretestBlock = 16;

/*!
  \ingroup group_robust
  \brief What vpRansacLoop() did.
*/
struct vpRansacReport
{
  int trials = 0;           //!< Minimal samples drawn.
  int models = 0;           //!< Hypotheses scored (a sample may give several, or none).
  int inlierCount = 0;      //!< Inliers of the returned model.
  double score = 0.0;       //!< Sum of truncated squared residuals of the returned model (lower is better).
  std::vector<int> inliers; //!< Indices of the inliers of the returned model.
};

/*!
  Number of RANSAC trials that draw, with probability \e p, at least one sample of \e s points free
  of outliers when a fraction \e outlierRatio of the data are outliers:
  \f$ N = \log(1-p) / \log(1-(1-\epsilon)^s) \f$ (Boutteau et al., JMIV 2018, eq. 28).
  Saturates at \e maxTrials; returns 0 when there are no outliers and 1 for p <= 0.
*/
VISP_EXPORT int vpRansacTrialCount(double probability, double outlierRatio, int sampleSize, int maxTrials);

/*!
  \ingroup group_robust
  \brief Draws \e k distinct indices in [0, n) with a seeded Mersenne twister, without allocating.
*/
class vpRansacSampler
{
public:
  //! Sampler over [0, n) drawing k-subsets, seeded for reproducibility.
  vpRansacSampler(int n, unsigned int seed) : m_n(n), m_rng(seed) {}
  /*!
    Writes k distinct indices into \e out (k is small, rejection is cheap).
    \exception vpException::badValue when k is negative or larger than n (no k distinct indices exist).
  */
  void draw(int k, int *out)
  {
    if (k < 0 || k > m_n)
      throw vpException(vpException::badValue, "vpRansacSampler::draw: %d distinct indices among %d", k, m_n);
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
  /*!
    One index drawn uniformly in [0, bound), from the same generator as draw(): for an estimator that draws
    its own samples (see vpRansacLoop()).
    \exception vpException::badValue when \e bound is not positive.
  */
  int index(int bound)
  {
    if (bound <= 0)
      throw vpException(vpException::badValue, "vpRansacSampler::index: no index below %d", bound);
    return std::uniform_int_distribution<int>(0, bound - 1)(m_rng);
  }

private:
  int m_n;
  std::mt19937 m_rng;
};

namespace vsp::detail
{
//! Detects the optional `scoreRange()` member of an estimator (see vpRansacLoop()).
template <class E, class = void> struct HasScoreRange : std::false_type
{
};
template <class E>
struct HasScoreRange<E, std::void_t<decltype(std::declval<const E &>().scoreRange(
                            std::declval<const typename E::Model &>(), 0, 0, 0.0, std::declval<double &>(),
                            static_cast<int *>(nullptr)))> > : std::true_type
{
};

//! Detects the optional `drawSample()` member of an estimator (see vpRansacLoop()).
template <class E, class = void> struct HasDrawSample : std::false_type
{
};
template <class E>
struct HasDrawSample<E, std::void_t<decltype(std::declval<const E &>().drawSample(std::declval<vpRansacSampler &>(),
                                                                                  static_cast<int *>(nullptr)))> >
  : std::true_type
{
};

/*!
  Throws vpException::badValue unless sample[0, s) holds s distinct indices in [0, n): a minimal sample an
  estimator drew itself (drawSample(), see vpRansacLoop()), checked before its solver reads the data.
*/
inline void requireSample(const int *sample, int s, int n)
{
  for (int i = 0; i < s; ++i) {
    if (sample[i] < 0 || sample[i] >= n)
      throw vpException(vpException::badValue, "vpRansacLoop: drawSample() gave index %d, outside [0, %d)", sample[i],
                        n);
    for (int j = 0; j < i; ++j)
      if (sample[j] == sample[i])
        throw vpException(vpException::badValue, "vpRansacLoop: drawSample() gave index %d twice", sample[i]);
  }
}

//! Detects the optional `countInliers()` member of an estimator (see vpRansacLoop()).
template <class E, class = void> struct HasCountInliers : std::false_type
{
};
template <class E>
struct HasCountInliers<E, std::void_t<decltype(std::declval<const E &>().countInliers(
                              std::declval<const typename E::Model &>(), static_cast<const int *>(nullptr), 0, 0.0))> >
  : std::true_type
{
};

/*!
  Number of inliers among the data indices[0, count): the estimator's own countInliers() when it has
  one, otherwise one residual() call per datum.
*/
template <class Estimator>
int countInliers(const Estimator &estimator, const typename Estimator::Model &m, const int *indices, int count,
                 double thr2)
{
  if constexpr (HasCountInliers<Estimator>::value) {
    return estimator.countInliers(m, indices, count, thr2);
  } else {
    int inliers = 0;
    for (int k = 0; k < count; ++k) {
      const double r = estimator.residual(m, indices[k]);
      inliers += r * r < thr2 ? 1 : 0; // NaN is never an inlier
    }
    return inliers;
  }
}

/*!
  Inliers among the data [begin, end), their truncated squared residuals added to \e cost and, when
  \e inliers is not null, their indices written there: the estimator's own scoreRange() when it has
  one, otherwise one residual() call per datum.
*/
template <class Estimator>
int scoreRange(const Estimator &estimator, const typename Estimator::Model &m, int begin, int end, double thr2,
               double &cost, int *inliers)
{
  if constexpr (HasScoreRange<Estimator>::value) {
    return estimator.scoreRange(m, begin, end, thr2, cost, inliers);
  } else {
    int count = 0;
    for (int i = begin; i < end; ++i) {
      const double r = estimator.residual(m, i);
      const double r2 = r * r;
      if (r2 < thr2) { // NaN residuals are never inliers
        if (inliers)
          inliers[count] = i;
        ++count;
        cost += r2;
      } else {
        cost += thr2;
      }
    }
    return count;
  }
}

/*!
  Smallest number of inliers among \e m random data that does not reject, at risk \e risk, a model
  whose inlier ratio is at least \e p: the Chernoff bound P(X <= c) <= exp(-m KL(c/m || p)) of the
  binomial tail, which also holds for sampling without replacement (Hoeffding 1963). 0 for p <= 0.
*/
inline int pretestMinimum(int m, double p, double risk)
{
  if (!(p > 0.0))
    return 0;
  const double bound = std::log(1.0 / risk);
  int c = static_cast<int>(std::ceil(m * p)); // never rejected at or above the expected count
  while (c > 0) {
    const double q = double(c - 1) / m; // would c - 1 inliers be rejected?
    const double kl = (q > 0.0 ? q * std::log(q / p) : 0.0) +
                      (p < 1.0 ? (1.0 - q) * std::log((1.0 - q) / (1.0 - p)) : std::numeric_limits<double>::infinity());
    if (m * kl > bound)
      break;
    --c;
  }
  return c;
}

//! True when score a ranks before score b: more inliers, then a lower truncated cost.
inline bool better(const std::pair<int, double> &a, const std::pair<int, double> &b)
{
  return a.first > b.first || (a.first == b.first && a.second < b.second);
}
} // namespace vsp::detail

/*!
  \ingroup group_robust
  Scores a model: (inlier count, sum of truncated squared residuals). Scoring stops early, by blocks
  of data, as soon as the model cannot reach \e mustReach inliers any more; the count returned is
  then below \e mustReach (the model cannot win a ranking against a model with that many inliers),
  which leaves the outcome of the ranking unchanged and skips most of the data for bad hypotheses.
  When \e inliers is not null (room for size() indices), the indices of the inliers counted are
  written there: the whole consensus set whenever the scoring did not stop early.
*/
template <class Estimator>
std::pair<int, double> vpRansacScore(const Estimator &estimator, const typename Estimator::Model &m, double thr2,
                                     int mustReach = 0, int *inliers = nullptr)
{
  constexpr int kBlock = 64;
  const int n = estimator.size();
  int count = 0;
  double cost = 0.0;
  for (int begin = 0; begin < n; begin += kBlock) {
    const int end = std::min(n, begin + kBlock);
    count += vsp::detail::scoreRange(estimator, m, begin, end, thr2, cost, inliers ? inliers + count : nullptr);
    if (count + (n - end) < mustReach)
      break; // even if every remaining datum were an inlier, the count would stay below mustReach
  }
  return std::make_pair(count, cost);
}

/*!
  \ingroup group_robust
  Collects into \e inliers the indices of the data whose squared residual is below \e thr2, with the
  same test as vpRansacScore() (so that counts and index lists always agree).
*/
template <class Estimator>
void vpRansacInliers(const Estimator &estimator, const typename Estimator::Model &m, double thr2,
                     std::vector<int> &inliers)
{
  inliers.resize(static_cast<size_t>(estimator.size()));
  double cost = 0.0;
  const int count = vsp::detail::scoreRange(estimator, m, 0, estimator.size(), thr2, cost, inliers.data());
  inliers.resize(static_cast<size_t>(count));
}

namespace vsp::detail
{
/*!
  Scores a hypothesis against the best model so far (with its consensus set \e bestInliers) and
  takes its place when it ranks before it. \e scratch is a buffer of the same kind, swapped in.
  \return true when the hypothesis became the best model.
*/
template <class Estimator>
bool challenge(const Estimator &estimator, const typename Estimator::Model &candidate, double thr2,
               typename Estimator::Model &best, std::pair<int, double> &bestScore, std::vector<int> &bestInliers,
               std::vector<int> &scratch)
{
  scratch.resize(static_cast<size_t>(estimator.size()));
  const std::pair<int, double> sc = vpRansacScore(estimator, candidate, thr2, bestScore.first, scratch.data());
  if (!better(sc, bestScore))
    return false;
  scratch.resize(static_cast<size_t>(sc.first));
  bestInliers.swap(scratch);
  best = candidate;
  bestScore = sc;
  return true;
}

/*!
  Local optimisation of a new best model (LO-RANSAC): refit on its consensus set and keep the refit
  only if it scores better; while a kept refit gathers more inliers, its own consensus set is refitted
  again (\e rounds refits at most), since a better model may collect inliers the first set missed.
*/
template <class Estimator>
void localOptimisation(const Estimator &estimator, int rounds, double thr2, typename Estimator::Model &best,
                       std::pair<int, double> &bestScore, std::vector<int> &bestInliers, std::vector<int> &scratch)
{
  for (int round = 0; round < rounds; ++round) {
    const int before = bestScore.first;
    typename Estimator::Model refit = best;
    if (!estimator.refine(bestInliers, refit) ||
        !challenge(estimator, refit, thr2, best, bestScore, bestInliers, scratch))
      return;
    if (bestScore.first <= before)
      return;
  }
}

/*!
  The preemptive test of vpRansacLoop() (see vpRansacOptions::pretestSize): a fixed random subset of
  the data (drawn by its own generator, so that the sample sequence does not depend on it) and, for
  each look at it, the fewest inliers a hypothesis as good as the best so far would show there.
*/
template <class Estimator> class Pretest
{
public:
  //! The subset for \e n data: none when \e n is under four times the pretest size, rounded up to whole blocks
  //! (a full count is then cheap, and the subset is never larger than the data).
  Pretest(int n, const vpRansacOptions &options)
    : m_size(subsetSize(n, options)), m_n(n), m_risk(options.pretestRisk), m_subset(static_cast<size_t>(m_size)),
      m_minimum(static_cast<size_t>(m_size / vpRansacPretestBlock), 0), m_minimumFor(0)
  {
    if (m_size == 0)
      return;
    std::mt19937 rng(options.seed ^ 0x5bd1e995u);
    std::vector<int> all(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      all[static_cast<size_t>(i)] = i;
    for (int k = 0; k < m_size; ++k) { // partial Fisher-Yates shuffle
      std::uniform_int_distribution<int> pick(k, n - 1);
      std::swap(all[static_cast<size_t>(k)], all[static_cast<size_t>(pick(rng))]);
    }
    std::copy(all.begin(), all.begin() + m_size, m_subset.begin());
  }

  //! The pretest size rounded up to whole blocks of vpRansacPretestBlock, 0 when \e n is under four times that.
  static int subsetSize(int n, const vpRansacOptions &options)
  {
    if (options.pretestSize <= 0)
      return 0;
    const int rounded = (options.pretestSize + vpRansacPretestBlock - 1) / vpRansacPretestBlock * vpRansacPretestBlock;
    return n / 4 >= rounded ? rounded : 0;
  }

  //! False when hypothesis \e m shows too few inliers on the subset to beat a best model of \e bestCount inliers.
  bool passes(const Estimator &estimator, const typename Estimator::Model &m, int bestCount, double thr2)
  {
    if (m_size == 0 || bestCount <= 0)
      return true;
    const int looks = m_size / vpRansacPretestBlock;
    if (m_minimumFor != bestCount) {
      for (int l = 0; l < looks; ++l)
        m_minimum[static_cast<size_t>(l)] =
            pretestMinimum((l + 1) * vpRansacPretestBlock, double(bestCount) / m_n, m_risk);
      m_minimumFor = bestCount;
    }
    if (m_minimum[static_cast<size_t>(looks - 1)] == 0)
      return true; // the best model has too few inliers for the subset to reject anything
    int count = 0;
    for (int l = 0; l < looks; ++l) {
      count += countInliers(estimator, m, m_subset.data() + l * vpRansacPretestBlock, vpRansacPretestBlock, thr2);
      if (count < m_minimum[static_cast<size_t>(l)])
        return false;
    }
    return true;
  }

private:
  int m_size; // data in the subset: a multiple of vpRansacPretestBlock, 0 without the test
  int m_n;
  double m_risk;
  std::vector<int> m_subset;
  std::vector<int> m_minimum; // per look, for the best inlier count m_minimumFor
  int m_minimumFor;
};
} // namespace vsp::detail

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
  - `bool refine(const std::vector<int> &inliers, Model &m) const`: refit on inliers (may return false);
  - optionally `int scoreRange(const Model &m, int begin, int end, double thr2, double &cost, int *inliers) const`:
    the number of data of [begin, end) whose squared residual is below thr2, adding their squared
    residual (thr2 for the others) to cost and, when inliers is not null, writing their indices
    there. An estimator provides it to score a block of data in one tight loop (no per-datum call,
    no square root); it must agree with residual() up to rounding at the threshold;
  - optionally `int countInliers(const Model &m, const int *indices, int count, double thr2) const`:
    the number of the listed data whose squared residual is below thr2 (the preemptive test), with
    the same agreement with residual();
  - optionally `void drawSample(vpRansacSampler &sampler, int *sample) const`: writes kSampleSize distinct
    indices in [0, size()) of its own choosing (vpException::badValue otherwise), drawn with sampler.index()
    (seeded, reproducible): minimal samples taken
    from distinct groups of the data, say, where the inliers come in groups (GroupSAC, Ni, Jin and Dellaert,
    ICCV 2009); sampler.draw(kSampleSize, ...) otherwise. The adaptive trial count stays that of uniform
    sampling, which a sampler that favours inliers only makes more cautious.

  A datum is an inlier when residual < threshold. With options.pretestSize > 0, each hypothesis is
  first scored on a fixed random subset of the data and dropped when its inliers there make it
  implausible that it beats the best model (see vpRansacOptions::pretestSize). Hypotheses are ranked by inlier count, then by
  the sum of truncated squared residuals. The loop stops after the adaptive count computed from the
  best inlier ratio so far, at least options.minTrials and at most options.maxTrials samples.
  Local optimisation runs only when a sample gives a new best model.

  \return true when a model with at least kSampleSize inliers was found; then \e best and \e report
  describe it. False, with no trial, when there are fewer data than kSampleSize, options.maxTrials is not
  positive, options.threshold is not positive or options.probability is not in (0, 1].
*/
template <class Estimator>
bool vpRansacLoop(const Estimator &estimator, const vpRansacOptions &options, typename Estimator::Model &best,
                  vpRansacReport &report)
{
  using Model = typename Estimator::Model;
  constexpr int s = Estimator::kSampleSize;
  const int n = estimator.size();
  report = vpRansacReport();
  if (n < s || options.maxTrials <= 0 || !(options.threshold > 0.0) ||
      !(options.probability > 0.0 && options.probability <= 1.0))
    return false;

  const double thr2 = options.threshold * options.threshold;

  vpRansacSampler sampler(n, options.seed);
  std::array<int, s> sample{};
  std::array<Model, Estimator::kMaxModels> hypotheses{};
  std::vector<int> scratch; // consensus set of the hypothesis being scored
  std::pair<int, double> bestScore(0, std::numeric_limits<double>::infinity());
  vsp::detail::Pretest<Estimator> pretest(n, options);
  int needed = options.maxTrials;
  int trial = 0;
  int optimisedCount = 0; // inliers of the last locally optimised model
  for (; trial < needed || trial < options.minTrials; ++trial) {
    if (trial >= options.maxTrials)
      break;
    if constexpr (vsp::detail::HasDrawSample<Estimator>::value) {
      estimator.drawSample(sampler, sample.data());
      vsp::detail::requireSample(sample.data(), s, n);
    } else
      sampler.draw(s, sample.data());
    const int count = estimator.solveMinimal(sample.data(), hypotheses.data());
    for (int k = 0; k < count; ++k) {
      ++report.models;
      if (!pretest.passes(estimator, hypotheses[k], bestScore.first, thr2))
        continue;
      if (!vsp::detail::challenge(estimator, hypotheses[k], thr2, best, bestScore, report.inliers, scratch))
        continue;
      if (options.localOptimisation && bestScore.first > s &&
          bestScore.first > (1.0 + options.localOptimisationGain) * optimisedCount) {
        vsp::detail::localOptimisation(estimator, options.localRounds, thr2, best, bestScore, report.inliers, scratch);
        optimisedCount = bestScore.first;
      }
      needed = vpRansacTrialCount(options.probability, 1.0 - double(bestScore.first) / n, s, options.maxTrials);
    }
  }
  report.trials = trial;
  if (bestScore.first < s) {
    report.inliers.clear();
    return false;
  }
  report.inlierCount = bestScore.first;
  report.score = bestScore.second;
  return true;
}

#endif
