/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpPoseGravity::computePose(RANSAC): the 2-point minimal solver plugged into the shared loop of
  vpRansac.h, the filtering of repeated points, and the acceptance of the consensus.

  A consensus is accepted only if it is both large enough (setRansacNbInliersToReachConsensus(),
  vpPose's meaning) and unlikely to be chance. With a threshold tau, an outlier lands within tau of
  a model's prediction with probability p = pi tau^2 / A, A the area of the region the image points
  span (their bounding box grown by tau, so that points along a line give the 1-D probability). A
  model through 2 sample points then collects Bin(n - 2, p) chance inliers; over m scored models
  the best one reaches k inliers with probability at most m P(Bin(n - 2, p) >= k - 2) (union bound).
  The smallest k that brings this below the significance is required. Without it, random points
  with a loose threshold give a "consensus" of 3 or 4 in a good share of the runs.
*/
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <visp3/pose_gravity/vpPoseGravity.h>
#include <visp3/robust/vpRansac.h>

#include "gravity_geometry.h"
#include "gravity_pair_solver.h"
#include "pose_gravity_facade.h"

namespace
{
using vpGravitySolvers::Pose;
using namespace vsp::pose_gravity_facade;

// The RANSAC estimator over 2-point minimal samples (see vpRansacLoop()).
class GravityRansacEstimator
{
public:
  using Model = Pose;
  static constexpr int kSampleSize = 2;
  static constexpr int kMaxModels = 2;

  // The points were validated by checkReady(): the P2P fast path takes them as they are, and the
  // upright frames of the two gravity vectors are built once for all samples.
  GravityRansacEstimator(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj,
                         const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X)
    : m_gCam(gCam), m_gObj(gObj), m_frame(gCam, gObj), m_x(x), m_X(X)
  {
  }
  int size() const { return static_cast<int>(m_x.size()); }
  int solveMinimal(const int *sample, Model *models) const
  {
    vpGravitySolvers::P2PCase p2pCase = vpGravitySolvers::P2PCase::NoSolution;
    // Two identical object points (a repeated match) give NoSolution: the sample is skipped.
    const int count = vpGravitySolvers::detail::solvePairPoses(m_frame, m_x[sample[0]], m_x[sample[1]], m_X[sample[0]],
                                                               m_X[sample[1]], models, p2pCase);
    // A pose known only up to a ray cannot be scored.
    return (p2pCase == vpGravitySolvers::P2PCase::TwoSolutions) ? count : 0;
  }
  //! Reprojection error in normalized coordinates (infinite behind the camera).
  double residual(const Model &m, int i) const
  {
    return std::sqrt(vpGravitySolvers::detail::reprojectionError2(m, m_x[i], m_X[i]));
  }
  //! Local optimisation: the least squares on the consensus set (unweighted: the loop only needs the
  //! consensus; the final refit reweights, see refit()).
  bool refine(const std::vector<int> &inliers, Model &m) const { return refit(inliers, m, 0); }
  //! The least squares on \e inliers with \e passes inverse-depth reweighting passes.
  bool refit(const std::vector<int> &inliers, Model &m, int passes) const
  {
    if (inliers.size() < 3)
      return false;
    std::vector<Eigen::Vector3d> x, X;
    x.reserve(inliers.size());
    X.reserve(inliers.size());
    for (int i : inliers) {
      x.push_back(m_x[i]);
      X.push_back(m_X[i]);
    }
    return vpGravitySolvers::leastSquares(m_gCam, m_gObj, x.data(), X.data(), static_cast<int>(x.size()), m, passes);
  }

private:
  Eigen::Vector3d m_gCam, m_gObj;
  vpGravitySolvers::detail::vpYawFrame m_frame;
  const std::vector<Eigen::Vector3d> &m_x, &m_X;
};

// Indices of the points kept by the filter: all, or those repeating no earlier point's object
// coordinates nor image coordinates.
std::vector<unsigned int> filteredPoints(const std::vector<vpPoint> &points, bool prefilter)
{
  const size_t n = points.size();
  std::vector<unsigned int> kept;
  kept.reserve(n);
  if (!prefilter) {
    for (size_t i = 0; i < n; ++i)
      kept.push_back(static_cast<unsigned int>(i));
    return kept;
  }
  std::vector<double> object(3 * n), image(2 * n);
  double imageScale = 0.0;
  for (size_t i = 0; i < n; ++i) {
    object[3 * i] = points[i].get_oX();
    object[3 * i + 1] = points[i].get_oY();
    object[3 * i + 2] = points[i].get_oZ();
    image[2 * i] = points[i].get_x();
    image[2 * i + 1] = points[i].get_y();
    imageScale = std::max({imageScale, std::abs(image[2 * i]), std::abs(image[2 * i + 1])});
  }
  std::vector<int> sameObject, sameImage;
  findDuplicates(object, 3, kDuplicateTolerance * objectScale(points, static_cast<unsigned int>(n)), sameObject);
  findDuplicates(image, 2, kDuplicateTolerance * imageScale, sameImage);
  for (size_t i = 0; i < n; ++i)
    if (sameObject[i] < 0 && sameImage[i] < 0)
      kept.push_back(static_cast<unsigned int>(i));
  return kept;
}

/*!
  Smallest consensus that chance explains with probability below alpha (see the file description):
  n points, chance-inlier probability p per point and model, m models scored. Returns n + 1 when
  even n inliers are not significant, 0 when alpha >= 1.
*/
unsigned int chanceConsensus(int n, double p, int models, double alpha)
{
  if (alpha >= 1.0 || n < 3)
    return 0;
  if (!(p < 1.0))
    return static_cast<unsigned int>(n + 1);
  const int N = n - 2;
  // log P(Bin(N, p) = k) by the recurrence of the binomial terms (one logarithm per term, no
  // underflow), then the tails P(>= k) summed from the top so that small tails keep precision.
  std::vector<double> tail(static_cast<size_t>(N) + 2, 0.0);
  const double logOdds = std::log(std::max(p, 1e-300)) - std::log1p(-p);
  double logPmf = N * std::log1p(-p);
  std::vector<double> logPmfs(static_cast<size_t>(N) + 1);
  for (int k = 0; k <= N; ++k) {
    logPmfs[static_cast<size_t>(k)] = logPmf;
    logPmf += std::log(double(N - k) / double(k + 1)) + logOdds;
  }
  for (int k = N; k >= 0; --k)
    tail[static_cast<size_t>(k)] = tail[static_cast<size_t>(k) + 1] + std::exp(logPmfs[static_cast<size_t>(k)]);
  const double m = std::max(1, models);
  for (int k = 0; k <= N; ++k)
    if (m * tail[static_cast<size_t>(k)] < alpha)
      return static_cast<unsigned int>(k + 2);
  return static_cast<unsigned int>(n + 1);
}

// Probability that a point uniformly spread over the region of the image points falls within tau
// of a given prediction.
double chanceInlierProbability(const std::vector<Eigen::Vector3d> &x, double tau)
{
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  for (const Eigen::Vector3d &b : x) {
    xmin = std::min(xmin, b.x());
    xmax = std::max(xmax, b.x());
    ymin = std::min(ymin, b.y());
    ymax = std::max(ymax, b.y());
  }
  const double area = (xmax - xmin + 2.0 * tau) * (ymax - ymin + 2.0 * tau);
  return std::min(1.0, 3.14159265358979323846 * tau * tau / area);
}

//! The settings and the acceptance rule of a RANSAC run (see the file description).
struct ConsensusRule
{
  vpRansacOptions options;
  unsigned int minimum; //!< the user's minimum consensus
  double significance;  //!< of the chance consensus
};

/*!
  The RANSAC loop with the given gravity vectors: true, with \e best and \e report, when the
  consensus is both large enough and unlikely to be chance.
*/
bool ransacConsensus(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const std::vector<Eigen::Vector3d> &x,
                     const std::vector<Eigen::Vector3d> &X, const ConsensusRule &rule, Pose &best,
                     vpRansacReport &report)
{
  const int n = static_cast<int>(x.size());
  const GravityRansacEstimator estimator(gCam, gObj, x, X);
  const bool found = n >= 3 && vpRansacLoop(estimator, rule.options, best, report);
  // The consensus needed: the user's minimum (at least 3, for the least squares refit) and the
  // count that chance does not explain.
  const unsigned int needed = std::max(
      {3u, rule.minimum,
       chanceConsensus(n, chanceInlierProbability(x, rule.options.threshold), report.models, rule.significance)});
  return found && static_cast<unsigned int>(report.inlierCount) >= needed;
}

/*!
  The camera and object gravity exchanged, checked on a consensus: a wrong tilt can be absorbed by the
  yaw and the translation of a small object within the threshold for part of the points, so a
  consensus alone does not prove the vectors (with the vectors exchanged, 20 of 100 scenes of 20
  points at 1 px reach one: 4 to 20 inliers). The least squares with the two vectors exchanged,
  started on the same inliers and re-collected twice, is then compared: the stated vectors are refused
  when the exchange explains more points, and the points it explains that the stated consensus calls
  outliers are more than chance explains (an outlier falls within the threshold of a prediction with
  the probability of chanceInlierProbability(); the same significance as the consensus itself). With
  the stated vectors right, the exchange is a wrong tilt: it collects fewer points, or, when the tilt
  it makes is small, the same ones. An exchange that tilts the stated pose by less than \e noise (the
  image noise, or 3 sigma of the gravity noise given by setGravityStdDev()) is not compared: the
  points cannot tell it from the stated vectors, and taking it would move the pose by no more than
  that. Gravity noise not given: with 0.01 per component, 0.4 % of right scenes are refused.
*/
bool exchangeExplainsMore(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj,
                          const std::vector<Eigen::Vector3d> &x, const std::vector<Eigen::Vector3d> &X,
                          const std::vector<int> &inliers, const Pose &stated, const ConsensusRule &rule, double noise)
{
  // The tilt the exchange makes, seen from the stated pose (gCam = R gObj): R gCam against gObj. It is
  // nothing when the two vectors are equal (in their frames), and when the rotation is a half turn.
  if ((stated.R * gCam - gObj).norm() <= noise)
    return false;
  const GravityRansacEstimator exchanged(gObj, gCam, x, X);
  const double tau = rule.options.threshold;
  Pose pose;
  std::vector<int> collected = inliers;
  for (int pass = 0; pass < 2; ++pass) {
    if (!exchanged.refit(collected, pose, 2))
      return false;
    vpRansacInliers(exchanged, pose, tau * tau, collected);
  }
  if (collected.size() <= inliers.size())
    return false;
  std::vector<bool> statedInlier(x.size(), false);
  for (int i : inliers)
    statedInlier[static_cast<size_t>(i)] = true;
  int extra = 0;
  for (int i : collected)
    extra += statedInlier[static_cast<size_t>(i)] ? 0 : 1;
  const int outliers = static_cast<int>(x.size() - inliers.size());
  // chanceConsensus() counts the 2 sample points of a model on top of the chance inliers.
  const int needed =
      static_cast<int>(chanceConsensus(outliers + 2, chanceInlierProbability(x, tau), 1, rule.significance)) - 2;
  return extra >= std::max(1, needed);
}
} // namespace

bool vpPoseGravity::computeRansac(vpHomogeneousMatrix &cMo)
{
  const unsigned int nAll = static_cast<unsigned int>(m_points.size());
  // Repeated points are filtered (or left to the minimal solver), never an error here.
  checkReady(3, nAll, "computePose(RANSAC)", false);
  forgetInliers();
  m_ransacTrials = 0;
  const std::vector<unsigned int> kept = filteredPoints(m_points, m_ransacFilter == PREFILTER_DEGENERATE_POINTS);
  std::vector<Eigen::Vector3d> x, X;
  collectPoints(m_points, &kept, x, X);
  const Eigen::Vector3d gCam = toEigen(m_gCam), gObj = toEigen(m_gObj);
  const GravityRansacEstimator estimator(gCam, gObj, x, X);

  ConsensusRule rule;
  rule.options.threshold = m_ransacThreshold;
  rule.options.probability = m_ransacProbability;
  rule.options.maxTrials = m_ransacMaxTrials;
  rule.options.seed = m_ransacSeed;
  rule.options.localOptimisation = true;
  rule.minimum = m_ransacNbInliersConsensus;
  rule.significance = m_ransacSignificance;
  Pose best;
  vpRansacReport report;
  const bool found = ransacConsensus(gCam, gObj, x, X, rule, best, report);
  m_ransacTrials = report.trials;
  if (!found) {
    // The same search with the standard mix-ups of the gravity vectors: a consensus under one of
    // them names the mistake.
    const struct
    {
      vpGravityMistake mistake;
      Eigen::Vector3d gCam, gObj;
    } alternatives[] = {{GRAVITY_MISTAKE_SIGN_REVERSED, -gCam, gObj}, {GRAVITY_MISTAKE_SWAPPED, gObj, gCam}};
    int bestCount = 0;
    for (const auto &alternative : alternatives) {
      Pose pose;
      vpRansacReport alternativeReport;
      if (ransacConsensus(alternative.gCam, alternative.gObj, x, X, rule, pose, alternativeReport) &&
          alternativeReport.inlierCount > bestCount) {
        bestCount = alternativeReport.inlierCount;
        m_mistake = alternative.mistake;
      }
    }
    m_status = STATUS_NO_CONSENSUS;
    return false;
  }

  // Final refit on the whole consensus set (reweighted towards maximum likelihood), kept only if it
  // does not lose inliers.
  std::vector<int> inliers = report.inliers;
  Pose refit = best;
  if (estimator.refit(inliers, refit, 2)) {
    std::vector<int> refitInliers;
    vpRansacInliers(estimator, refit, m_ransacThreshold * m_ransacThreshold, refitInliers);
    if (refitInliers.size() >= inliers.size()) {
      best = refit;
      inliers = refitInliers;
    }
  }
  // The exchange is not told apart from the stated vectors when it tilts them by less than their noise.
  const double tiltNoise = std::max(m_imageStdDev, 3.0 * std::hypot(m_gCamStdDev, m_gObjStdDev));
  if (exchangeChangesTheProblem(gCam, gObj, m_gCamStdDev, m_gObjStdDev) &&
      exchangeExplainsMore(gCam, gObj, x, X, inliers, best, rule, tiltNoise)) {
    m_mistake = GRAVITY_MISTAKE_SWAPPED;
    m_status = STATUS_GRAVITY_SWAPPED;
    return false;
  }
  m_inlierIndex.clear();
  for (int i : inliers)
    m_inlierIndex.push_back(kept[static_cast<size_t>(i)]);
  m_refineOnInliers = true;
  storePose(best, cMo);
  m_status = STATUS_OK;
  updateCovariance(cMo, &m_inlierIndex);
  return true;
}
