/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpPoseGravity: the ViSP-typed facade over the pure Eigen solvers of vpGravitySolvers.h.
  Input is validated here (exceptions), the solvers themselves never throw.
*/
#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>
#include <visp3/robust/vpRansac.h>

#include "gravityGeometry.h"
#include "gravityPairSolver.h"

namespace
{
using vpGravitySolvers::Pose;

// Relative tolerance under which two object points are the same point.
const double kDuplicateTolerance = 1e-12;
// Sine of the angle under which three object points are collinear (P3P).
const double kCollinearTolerance = 1e-10;

Eigen::Vector3d toEigen(const vpColVector &v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

// Writes the pose into cMo in place (no temporary matrix: vpHomogeneousMatrix allocates).
void storePose(const Pose &pose, vpHomogeneousMatrix &cMo)
{
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 3; ++c)
      cMo[r][c] = pose.R(static_cast<int>(r), static_cast<int>(c));
    cMo[r][3] = pose.t(static_cast<int>(r));
    cMo[3][r] = 0.0;
  }
  cMo[3][3] = 1.0;
}

vpHomogeneousMatrix toHomogeneous(const Pose &pose)
{
  vpHomogeneousMatrix cMo;
  storePose(pose, cMo);
  return cMo;
}

Pose toPose(const vpHomogeneousMatrix &cMo)
{
  Pose pose;
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 3; ++c)
      pose.R(static_cast<int>(r), static_cast<int>(c)) = cMo[r][c];
    pose.t(static_cast<int>(r)) = cMo[r][3];
  }
  return pose;
}

// Writes the normalized gravity of a user vector into unit; throws on anything that is not a usable
// direction.
void normalizeGravity(const vpColVector &g, const char *which, vpColVector &unit)
{
  if (g.size() != 3) {
    std::ostringstream msg;
    msg << "vpPoseGravity: " << which << " gravity must be a 3-vector (got " << g.size() << " elements)";
    throw vpPoseGravityException(vpPoseGravityException::badGravityError, msg.str());
  }
  // Scale by the largest component first so that neither tiny nor huge norms under/overflow.
  const double largest = std::max({std::abs(g[0]), std::abs(g[1]), std::abs(g[2])});
  if (!std::isfinite(g[0]) || !std::isfinite(g[1]) || !std::isfinite(g[2]) || !(largest > 0.0)) {
    std::ostringstream msg;
    msg << "vpPoseGravity: " << which << " gravity must be finite and non-zero (got " << g.t() << ")";
    throw vpPoseGravityException(vpPoseGravityException::badGravityError, msg.str());
  }
  const Eigen::Vector3d v = Eigen::Vector3d(g[0], g[1], g[2]) / largest;
  const Eigen::Vector3d n = v / v.norm();
  unit.resize(3, false); // no reallocation: the members are 3-vectors from construction
  for (unsigned int i = 0; i < 3; ++i)
    unit[i] = n[static_cast<int>(i)];
}

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
    const int count = vpGravitySolvers::detail::solvePairPoses(m_frame, m_x[sample[0]], m_x[sample[1]],
                                                               m_X[sample[0]], m_X[sample[1]], models, p2pCase);
    // A pose known only up to a ray cannot be scored.
    return (p2pCase == vpGravitySolvers::P2PCase::TwoSolutions) ? count : 0;
  }
  //! Reprojection error in normalized coordinates (infinite behind the camera).
  double residual(const Model &m, int i) const
  {
    return std::sqrt(vpGravitySolvers::detail::reprojectionError2(m, m_x[i], m_X[i]));
  }
  //! Local optimisation: the closed-form least squares on the consensus set.
  bool refine(const std::vector<int> &inliers, Model &m) const
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
    return vpGravitySolvers::leastSquares(m_gCam, m_gObj, x.data(), X.data(), static_cast<int>(x.size()), m);
  }

private:
  Eigen::Vector3d m_gCam, m_gObj;
  vpGravitySolvers::detail::vpYawFrame m_frame;
  const std::vector<Eigen::Vector3d> &m_x, &m_X;
};
} // namespace

vpPoseGravity::vpPoseGravity()
  : m_points(), m_gCam(3, 0.0), m_gObj(3, 0.0), m_hasGCam(false), m_hasGObj(false), m_ransacThreshold(1e-3),
    m_ransacMaxTrials(1000), m_ransacProbability(0.99), m_ransacSeed(0), m_inlierIndex(), m_ransacTrials(0),
    m_imageStdDev(1e-3), m_gravityStdDev(0.0), m_status(STATUS_NOT_COMPUTED), m_refineOnInliers(false)
{
}

void vpPoseGravity::setCameraGravity(const vpColVector &g_cam)
{
  normalizeGravity(g_cam, "camera", m_gCam);
  m_hasGCam = true;
}

void vpPoseGravity::setObjectGravity(const vpColVector &g_obj)
{
  normalizeGravity(g_obj, "object", m_gObj);
  m_hasGObj = true;
}

vpColVector vpPoseGravity::getCameraGravity() const { return m_gCam; }
vpColVector vpPoseGravity::getObjectGravity() const { return m_gObj; }

void vpPoseGravity::addPoint(const vpPoint &P)
{
  m_points.push_back(P);
  forgetInliers();
}

void vpPoseGravity::addPoints(const std::vector<vpPoint> &lP)
{
  m_points.insert(m_points.end(), lP.begin(), lP.end());
  forgetInliers();
}

void vpPoseGravity::clearPoint()
{
  m_points.clear();
  forgetInliers();
}

void vpPoseGravity::forgetInliers()
{
  m_inlierIndex.clear();
  m_refineOnInliers = false;
}

void vpPoseGravity::checkReady(unsigned int minPoints, unsigned int usedPoints, const char *what) const
{
  if (!m_hasGCam || !m_hasGObj) {
    std::ostringstream msg;
    msg << "vpPoseGravity::" << what << ": " << (m_hasGCam ? "object" : "camera")
        << " gravity is not set (call setCameraGravity() and setObjectGravity())";
    throw vpPoseGravityException(vpPoseGravityException::badGravityError, msg.str());
  }
  if (m_points.size() < minPoints) {
    std::ostringstream msg;
    msg << "vpPoseGravity::" << what << " needs at least " << minPoints << " points, got " << m_points.size();
    throw vpPoseGravityException(vpPoseGravityException::notEnoughPointError, msg.str());
  }
  const unsigned int n = std::min<unsigned int>(usedPoints, static_cast<unsigned int>(m_points.size()));
  double scale = 0.0;
  for (unsigned int i = 0; i < n; ++i) {
    const vpPoint &P = m_points[i];
    const double v[5] = {P.get_oX(), P.get_oY(), P.get_oZ(), P.get_x(), P.get_y()};
    for (double c : v)
      if (!std::isfinite(c)) {
        std::ostringstream msg;
        msg << "vpPoseGravity::" << what << ": point " << i << " has a non-finite coordinate (oX, oY, oZ, x, y) = ("
            << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3] << ", " << v[4] << ")";
        throw vpPoseGravityException(vpPoseGravityException::badPointError, msg.str());
      }
    scale = std::max({scale, std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
  }
  // Duplicate object points make a 2-point sample degenerate and the closed forms ill-posed.
  const double tolerance = kDuplicateTolerance * scale;
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = i + 1; j < n; ++j) {
      const vpPoint &A = m_points[i], &B = m_points[j];
      const double d = std::max({std::abs(A.get_oX() - B.get_oX()), std::abs(A.get_oY() - B.get_oY()),
                                 std::abs(A.get_oZ() - B.get_oZ())});
      if (d <= tolerance) {
        std::ostringstream msg;
        msg << "vpPoseGravity::" << what << ": object points " << i << " and " << j << " are identical ("
            << A.get_oX() << ", " << A.get_oY() << ", " << A.get_oZ() << ")";
        throw vpPoseGravityException(vpPoseGravityException::degeneratePointsError, msg.str());
      }
    }
}

namespace
{
// Bearings (x, y, 1) and object points of the first count points, into arrays of that size.
void collectPoints(const std::vector<vpPoint> &points, unsigned int count, Eigen::Vector3d *x, Eigen::Vector3d *X)
{
  for (unsigned int i = 0; i < count; ++i) {
    const vpPoint &P = points[i];
    x[i] = Eigen::Vector3d(P.get_x(), P.get_y(), 1.0);
    X[i] = Eigen::Vector3d(P.get_oX(), P.get_oY(), P.get_oZ());
  }
}

// The same into vectors resized to count.
void collectPoints(const std::vector<vpPoint> &points, unsigned int count, std::vector<Eigen::Vector3d> &x,
                   std::vector<Eigen::Vector3d> &X)
{
  x.resize(count);
  X.resize(count);
  collectPoints(points, count, x.data(), X.data());
}

// Common end of the closed-form methods: the pose into cMo and STATUS_OK, or STATUS_NO_SOLUTION.
bool finishClosedForm(bool found, const Pose &pose, vpHomogeneousMatrix &cMo, vpPoseGravity::vpPoseGravityStatus &status)
{
  status = found ? vpPoseGravity::STATUS_OK : vpPoseGravity::STATUS_NO_SOLUTION;
  if (found)
    storePose(pose, cMo);
  return found;
}
} // namespace

std::vector<vpHomogeneousMatrix> vpPoseGravity::computePoseCandidates()
{
  checkReady(2, 2, "computePoseCandidates");
  forgetInliers();
  Eigen::Vector3d x[2], X[2];
  collectPoints(m_points, 2, x, X);
  std::array<Pose, 2> poses;
  vpGravitySolvers::P2PCase p2pCase;
  const int count = vpGravitySolvers::p2p(toEigen(m_gCam), toEigen(m_gObj), x, X, poses, &p2pCase);
  std::vector<vpHomogeneousMatrix> candidates;
  switch (p2pCase) {
  case vpGravitySolvers::P2PCase::TwoSolutions:
    for (int k = 0; k < count; ++k)
      candidates.push_back(toHomogeneous(poses[k]));
    m_status = STATUS_OK;
    break;
  case vpGravitySolvers::P2PCase::UniqueRotation:
    m_status = STATUS_COINCIDENT_IMAGE_POINTS;
    break;
  case vpGravitySolvers::P2PCase::Undetermined:
    m_status = STATUS_VERTICAL_RAY;
    break;
  case vpGravitySolvers::P2PCase::NoSolution:
    m_status = STATUS_NO_SOLUTION;
    break;
  }
  return candidates;
}

bool vpPoseGravity::computePose(vpPoseGravityMethod method, vpHomogeneousMatrix &cMo)
{
  switch (method) {
  case P3P:
    return computeP3P(cMo);
  case LEAST_SQUARES:
    return computeLeastSquares(cMo);
  case RANSAC:
    return computeRansac(cMo);
  }
  throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::computePose: unknown method");
}

bool vpPoseGravity::computeP3P(vpHomogeneousMatrix &cMo)
{
  checkReady(3, 3, "computePose(P3P)");
  forgetInliers();
  Eigen::Vector3d x[3], X[3];
  collectPoints(m_points, 3, x, X);
  const Eigen::Vector3d AB = X[1] - X[0], AC = X[2] - X[0];
  // Squared form of |AB x AC| <= tol |AB| |AC|: no square root.
  if (AB.cross(AC).squaredNorm() <= kCollinearTolerance * kCollinearTolerance * AB.squaredNorm() * AC.squaredNorm())
    throw vpPoseGravityException(vpPoseGravityException::degeneratePointsError,
                                 "vpPoseGravity::computePose(P3P): the three object points are collinear");
  Pose pose;
  return finishClosedForm(vpGravitySolvers::p3p(toEigen(m_gCam), toEigen(m_gObj), x, X, pose), pose, cMo, m_status);
}

bool vpPoseGravity::computeLeastSquares(vpHomogeneousMatrix &cMo)
{
  const unsigned int n = static_cast<unsigned int>(m_points.size());
  checkReady(3, n, "computePose(LEAST_SQUARES)");
  forgetInliers();
  std::vector<Eigen::Vector3d> x, X;
  collectPoints(m_points, n, x, X);
  Pose pose;
  const bool found = vpGravitySolvers::leastSquares(toEigen(m_gCam), toEigen(m_gObj), x.data(), X.data(),
                                                    static_cast<int>(n), pose);
  return finishClosedForm(found, pose, cMo, m_status);
}

bool vpPoseGravity::computeRansac(vpHomogeneousMatrix &cMo)
{
  const unsigned int n = static_cast<unsigned int>(m_points.size());
  checkReady(3, n, "computePose(RANSAC)");
  forgetInliers();
  std::vector<Eigen::Vector3d> x, X;
  collectPoints(m_points, n, x, X);
  const Eigen::Vector3d gCam = toEigen(m_gCam), gObj = toEigen(m_gObj);
  const GravityRansacEstimator estimator(gCam, gObj, x, X);

  vpRansacOptions options;
  options.threshold = m_ransacThreshold;
  options.probability = m_ransacProbability;
  options.maxTrials = m_ransacMaxTrials;
  options.seed = m_ransacSeed;
  options.localOptimisation = true;
  Pose best;
  vpRansacReport report;
  const bool found = vpRansacLoop(estimator, options, best, report);
  m_ransacTrials = report.trials;
  // The closed-form least squares needs three points: a 2-point consensus is no consensus.
  if (!found || report.inlierCount < 3) {
    m_status = STATUS_NO_CONSENSUS;
    return false;
  }

  // Final refit on the whole consensus set, kept only if it does not lose inliers.
  std::vector<int> inliers = report.inliers;
  Pose refit = best;
  if (estimator.refine(inliers, refit)) {
    std::vector<int> refitInliers;
    vpRansacInliers(estimator, refit, m_ransacThreshold * m_ransacThreshold, refitInliers);
    if (refitInliers.size() >= inliers.size()) {
      best = refit;
      inliers = refitInliers;
    }
  }
  m_inlierIndex.assign(inliers.begin(), inliers.end());
  m_refineOnInliers = true;
  storePose(best, cMo);
  m_status = STATUS_OK;
  return true;
}

bool vpPoseGravity::refinePose(vpHomogeneousMatrix &cMo)
{
  checkReady(2, static_cast<unsigned int>(m_points.size()), "refinePose");
  std::vector<Eigen::Vector3d> xAll, XAll, x, X;
  collectPoints(m_points, static_cast<unsigned int>(m_points.size()), xAll, XAll);
  if (m_refineOnInliers) {
    for (unsigned int i : m_inlierIndex) {
      x.push_back(xAll[i]);
      X.push_back(XAll[i]);
    }
  } else {
    x = xAll;
    X = XAll;
  }
  Pose pose = toPose(cMo);
  if (x.size() < 2 || !vpGravitySolvers::detail::refinePose(toEigen(m_gCam), toEigen(m_gObj), x.data(), X.data(),
                                                            static_cast<int>(x.size()), m_imageStdDev,
                                                            m_gravityStdDev, pose)) {
    m_status = STATUS_REFINEMENT_FAILED;
    return false;
  }
  storePose(pose, cMo);
  m_status = STATUS_OK;
  return true;
}

double vpPoseGravity::computeResidual(const vpHomogeneousMatrix &cMo) const
{
  double residual = 0.0;
  for (const vpPoint &P : m_points) {
    const double X = P.get_oX(), Y = P.get_oY(), Z = P.get_oZ();
    const double cX = cMo[0][0] * X + cMo[0][1] * Y + cMo[0][2] * Z + cMo[0][3];
    const double cY = cMo[1][0] * X + cMo[1][1] * Y + cMo[1][2] * Z + cMo[1][3];
    const double cZ = cMo[2][0] * X + cMo[2][1] * Y + cMo[2][2] * Z + cMo[2][3];
    const double ex = cX / cZ - P.get_x(), ey = cY / cZ - P.get_y();
    residual += ex * ex + ey * ey;
  }
  return residual;
}

void vpPoseGravity::setRansacThreshold(double t)
{
  if (!(t > 0.0) || !std::isfinite(t))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::setRansacThreshold: threshold must be > 0");
  m_ransacThreshold = t;
}

void vpPoseGravity::setRansacMaxTrials(int trials)
{
  if (trials <= 0)
    throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::setRansacMaxTrials: must be > 0");
  m_ransacMaxTrials = trials;
}

void vpPoseGravity::setRansacProbability(double p)
{
  if (!(p > 0.0 && p < 1.0))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::setRansacProbability: must be in (0, 1)");
  m_ransacProbability = p;
}

void vpPoseGravity::setRansacSeed(unsigned int seed) { m_ransacSeed = seed; }

std::vector<vpPoint> vpPoseGravity::getRansacInliers() const
{
  std::vector<vpPoint> inliers;
  inliers.reserve(m_inlierIndex.size());
  for (unsigned int i : m_inlierIndex)
    inliers.push_back(m_points[i]);
  return inliers;
}

void vpPoseGravity::setImageStdDev(double sigma)
{
  if (!(sigma > 0.0) || !std::isfinite(sigma))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::setImageStdDev: must be > 0");
  m_imageStdDev = sigma;
}

void vpPoseGravity::setGravityStdDev(double sigma)
{
  if (!(sigma >= 0.0) || !std::isfinite(sigma))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpPoseGravity::setGravityStdDev: must be >= 0");
  m_gravityStdDev = sigma;
}

std::string vpPoseGravity::getStatusMessage(vpPoseGravityStatus status)
{
  switch (status) {
  case STATUS_NOT_COMPUTED:
    return "no pose computed yet";
  case STATUS_OK:
    return "pose computed";
  case STATUS_COINCIDENT_IMAGE_POINTS:
    return "both image points coincide on a ray not parallel to gravity: rotation unique, translation known only "
           "up to that ray";
  case STATUS_VERTICAL_RAY:
    return "the rotation about gravity is not observable (both image points on a vertical ray, vertical object "
           "segment, or both rays horizontal): infinitely many poses";
  case STATUS_NO_SOLUTION:
    return "the measurements admit no pose";
  case STATUS_NO_CONSENSUS:
    return "RANSAC found no model with at least three inliers";
  case STATUS_REFINEMENT_FAILED:
    return "the refinement gave no usable solution; the pose was left unchanged";
  }
  return "unknown status";
}
