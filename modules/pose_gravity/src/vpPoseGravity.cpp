/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpPoseGravity: the ViSP-typed facade over the pure Eigen solvers of vpGravitySolvers.h.
  Input is validated here (exceptions), the solvers themselves never throw; every closed-form result
  is checked against the points before it is returned. The RANSAC adapter is in
  vpPoseGravityRansac.cpp, the display helpers in vpPoseGravityDisplay.cpp.
*/
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

#include "gravity_geometry.h"
#include "pose_gravity_facade.h"

namespace
{
using vpGravitySolvers::Pose;
using namespace vsp::pose_gravity_facade;

// Sine of the angle under which three object points are collinear (P3P).
const double kCollinearTolerance = 1e-10;

vpHomogeneousMatrix toHomogeneous(const Pose &pose)
{
  vpHomogeneousMatrix cMo;
  storePose(pose, cMo);
  return cMo;
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

void checkStdDev(double sigma, const char *what)
{
  if (!(sigma >= 0.0) || !std::isfinite(sigma))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 std::string("vpPoseGravity::") + what + ": must be finite and >= 0");
}

/*!
  Consistency of a closed-form pose with the points it came from: STATUS_BEHIND_CAMERA when a point
  is not in front of the camera, STATUS_INCONSISTENT_GRAVITY when the reprojection error (the largest
  one when !median, the median one otherwise) exceeds tol, STATUS_OK otherwise; \e error receives it.
*/
vpPoseGravity::vpPoseGravityStatus checkPose(const Pose &pose, const std::vector<Eigen::Vector3d> &x,
                                             const std::vector<Eigen::Vector3d> &X, bool median, double tol,
                                             double &error)
{
  error = std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!((pose.R * X[i] + pose.t).z() > 0.0))
      return vpPoseGravity::STATUS_BEHIND_CAMERA;
    worst = std::max(worst, vpGravitySolvers::detail::reprojectionError2(pose, x[i], X[i]));
  }
  if (median) {
    std::vector<double> e2(x.size());
    for (size_t i = 0; i < x.size(); ++i)
      e2[i] = vpGravitySolvers::detail::reprojectionError2(pose, x[i], X[i]);
    std::nth_element(e2.begin(), e2.begin() + static_cast<long>(e2.size() / 2), e2.end());
    worst = e2[e2.size() / 2];
  }
  error = std::sqrt(worst);
  return (error <= tol) ? vpPoseGravity::STATUS_OK : vpPoseGravity::STATUS_INCONSISTENT_GRAVITY;
}

//! True when every object point lies on one line along the object gravity (the yaw is then free).
bool onOneVerticalLine(const std::vector<Eigen::Vector3d> &X, const Eigen::Vector3d &gObj)
{
  const Eigen::Vector3d g = gObj.normalized();
  double scale = 0.0, offLine = 0.0;
  for (const Eigen::Vector3d &P : X) {
    scale = std::max(scale, (P - X.front()).norm());
    offLine = std::max(offLine, (P - X.front()).cross(g).norm());
  }
  return offLine <= 1e-9 * std::max(scale, 1e-300);
}

// The settings of the refinement and of the covariance.
vpGravitySolvers::detail::RefineOptions refineOptions(double imageSigma, double cameraSigma, double objectSigma,
                                                      vpPoseGravity::vpRobustLoss loss, double lossScale)
{
  vpGravitySolvers::detail::RefineOptions options;
  options.imageSigma = imageSigma;
  options.cameraGravitySigma = cameraSigma;
  options.objectGravitySigma = objectSigma;
  options.loss = loss;
  options.lossScale = lossScale;
  return options;
}

void storeMatrix(const Eigen::Matrix<double, 6, 6> &from, vpMatrix &to)
{
  to.resize(6, 6, false);
  for (unsigned int r = 0; r < 6; ++r)
    for (unsigned int c = 0; c < 6; ++c)
      to[r][c] = from(static_cast<int>(r), static_cast<int>(c));
}
} // namespace

vpPoseGravity::vpPoseGravity()
  : m_points(), m_gCam(3, 0.0), m_gObj(3, 0.0), m_hasGCam(false), m_hasGObj(false), m_consistencyThreshold(0.04),
    m_pairRule(P3P_BEST_THIRD_POINT), m_ransacThreshold(4e-3), m_ransacMaxTrials(1000), m_ransacProbability(0.99),
    m_ransacSeed(0), m_ransacNbInliersConsensus(4), m_ransacSignificance(0.01),
    m_ransacFilter(PREFILTER_DEGENERATE_POINTS), m_inlierIndex(), m_ransacTrials(0), m_imageStdDev(1e-3),
    m_gCamStdDev(0.0), m_gObjStdDev(0.0), m_loss(LOSS_NONE), m_lossScale(3e-3), m_computeCovariance(false),
    m_hasCovariance(false), m_covariance(), m_status(STATUS_NOT_COMPUTED), m_refineOnInliers(false),
    m_mistake(GRAVITY_MISTAKE_NONE)
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
  m_mistake = GRAVITY_MISTAKE_NONE;
}

void vpPoseGravity::checkReady(unsigned int minPoints, unsigned int usedPoints, const char *what,
                               bool checkDuplicates) const
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
  }
  if (!checkDuplicates)
    return;
  // Duplicate object points make a 2-point sample degenerate and the closed forms ill-posed.
  std::vector<double> coords(3 * static_cast<size_t>(n));
  for (unsigned int i = 0; i < n; ++i) {
    coords[3 * i] = m_points[i].get_oX();
    coords[3 * i + 1] = m_points[i].get_oY();
    coords[3 * i + 2] = m_points[i].get_oZ();
  }
  std::vector<int> firstEqual;
  findDuplicates(coords, 3, kDuplicateTolerance * objectScale(m_points, n), firstEqual);
  for (unsigned int j = 0; j < n; ++j)
    if (firstEqual[j] >= 0) {
      const vpPoint &A = m_points[j];
      std::ostringstream msg;
      msg << "vpPoseGravity::" << what << ": object points " << firstEqual[j] << " and " << j << " are identical ("
          << A.get_oX() << ", " << A.get_oY() << ", " << A.get_oZ() << ")";
      throw vpPoseGravityException(vpPoseGravityException::degeneratePointsError, msg.str());
    }
}

std::vector<vpHomogeneousMatrix> vpPoseGravity::computePoseCandidates()
{
  checkReady(2, 2, "computePoseCandidates");
  forgetInliers();
  std::vector<Eigen::Vector3d> x, X;
  collectFirst(m_points, 2, x, X);
  std::array<Pose, 2> poses;
  vpGravitySolvers::P2PCase p2pCase;
  const int count = vpGravitySolvers::p2p(toEigen(m_gCam), toEigen(m_gObj), x.data(), X.data(), poses, &p2pCase);
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
  const Eigen::Vector3d A(m_points[0].get_oX(), m_points[0].get_oY(), m_points[0].get_oZ());
  const Eigen::Vector3d AB = Eigen::Vector3d(m_points[1].get_oX(), m_points[1].get_oY(), m_points[1].get_oZ()) - A;
  const Eigen::Vector3d AC = Eigen::Vector3d(m_points[2].get_oX(), m_points[2].get_oY(), m_points[2].get_oZ()) - A;
  // Squared form of |AB x AC| <= tol |AB| |AC|: no square root.
  if (AB.cross(AC).squaredNorm() <= kCollinearTolerance * kCollinearTolerance * AB.squaredNorm() * AC.squaredNorm())
    throw vpPoseGravityException(vpPoseGravityException::degeneratePointsError,
                                 "vpPoseGravity::computePose(P3P): the three object points are collinear");
  return finishClosedForm(P3P, cMo);
}

bool vpPoseGravity::computeLeastSquares(vpHomogeneousMatrix &cMo)
{
  checkReady(3, static_cast<unsigned int>(m_points.size()), "computePose(LEAST_SQUARES)");
  forgetInliers();
  return finishClosedForm(LEAST_SQUARES, cMo);
}

namespace
{
// The closed-form pose of a method (P3P on the 3 points given, least squares on all) with the given
// gravity directions, and its consistency status (see checkPose()).
vpPoseGravity::vpPoseGravityStatus solveClosedForm(bool p3p, vpPoseGravity::vpP3PPairRule rule,
                                                   const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj,
                                                   const std::vector<Eigen::Vector3d> &x,
                                                   const std::vector<Eigen::Vector3d> &X, double tolerance, Pose &pose,
                                                   double &error)
{
  const bool found =
      p3p ? vpGravitySolvers::p3p(gCam, gObj, x.data(), X.data(), pose,
                                  rule == vpPoseGravity::P3P_WIDEST_PAIR
                                      ? vpGravitySolvers::P3PPairRule::WidestPair
                                      : vpGravitySolvers::P3PPairRule::BestThirdPoint)
          : vpGravitySolvers::leastSquares(gCam, gObj, x.data(), X.data(), static_cast<int>(x.size()), pose);
  error = std::numeric_limits<double>::infinity();
  if (!found)
    return vpPoseGravity::STATUS_NO_SOLUTION;
  return checkPose(pose, x, X, !p3p, tolerance, error);
}
} // namespace

bool vpPoseGravity::finishClosedForm(vpPoseGravityMethod method, vpHomogeneousMatrix &cMo)
{
  std::vector<Eigen::Vector3d> x, X;
  collectFirst(m_points, method == P3P ? 3 : m_points.size(), x, X);
  const Eigen::Vector3d gCam = toEigen(m_gCam), gObj = toEigen(m_gObj);
  Pose pose, reversed;
  double error = 0.0, reversedError = 0.0;
  m_status = solveClosedForm(method == P3P, m_pairRule, gCam, gObj, x, X, m_consistencyThreshold, pose, error);
  // The same solve with the camera gravity reversed (a specific force passed as gravity) and with
  // the two gravity vectors exchanged tells these mix-ups apart. With 3 points the two redundant
  // equations cannot always reject a wrong vector on their own, so a fit that passes the tolerance
  // is still not trusted when it leaves more error than the noise explains (3 sigma of the image and
  // gravity noise) and an alternative fits with less than half of it (the exchange: within twice the noise).
  // A fit within the noise needs no comparison.
  const double noise =
      3.0 * std::sqrt(m_imageStdDev * m_imageStdDev + m_gCamStdDev * m_gCamStdDev + m_gObjStdDev * m_gObjStdDev);
  m_mistake = GRAVITY_MISTAKE_NONE;
  if (m_status != STATUS_OK || error > noise) {
    const struct
    {
      Eigen::Vector3d gCam, gObj;
      vpGravityMistake mistake;
      vpPoseGravityStatus status;
    } alternatives[] = {{-gCam, gObj, GRAVITY_MISTAKE_SIGN_REVERSED, STATUS_GRAVITY_SIGN_REVERSED},
                        {gObj, gCam, GRAVITY_MISTAKE_SWAPPED, STATUS_GRAVITY_SWAPPED}};
    double bestError = std::numeric_limits<double>::infinity();
    const bool fitted = m_status == STATUS_OK;
    const bool distinctVectors = exchangeChangesTheProblem(gCam, gObj, m_gCamStdDev, m_gObjStdDev);
    const bool vertical = m_status == STATUS_NO_SOLUTION && onOneVerticalLine(X, gObj);
    for (const auto &alternative : alternatives) {
      const bool exchange = alternative.mistake == GRAVITY_MISTAKE_SWAPPED;
      // The exchange is not even solved when the points lie on one vertical line (no solution with the
      // given vectors, but a pose with any other) or the vectors are equal within their noise (an upright
      // camera facing an upright target: three points then fit either by chance).
      if (exchange && (vertical || !distinctVectors))
        continue;
      const vpPoseGravityStatus status = solveClosedForm(method == P3P, m_pairRule, alternative.gCam, alternative.gObj,
                                                         x, X, m_consistencyThreshold, reversed, reversedError);
      // The exchange must also fit within twice the noise (a wrong IMU rotation leaves some tilt that
      // the exchanged vectors may absorb a little better) or, for P3P, leave a quarter of the error at
      // most (its third point amplifies the noise: a right exchange left 6.2 sigma against 33). Least
      // squares keeps the bound alone: the relative rule called 7 of 300 wrong IMU rotations an exchange
      // (1 with the bound).
      const bool withinNoise = reversedError <= 2.0 * noise || (method == P3P && 4.0 * reversedError <= error);
      if (exchange && !withinNoise)
        continue;
      if (status == STATUS_OK && (!fitted || 2.0 * reversedError < error) && reversedError < bestError) {
        bestError = reversedError;
        m_mistake = alternative.mistake;
        m_status = alternative.status;
      }
    }
  }
  if (m_status != STATUS_OK)
    return false;
  storePose(pose, cMo);
  // P3P's covariance is that of the three points it solved: with all the points added it was 28 times too
  // small in variance when 20 were (mean NEES 182 for 4 expected).
  const std::vector<unsigned int> firstThree = {0, 1, 2};
  updateCovariance(cMo, method == P3P ? &firstThree : nullptr);
  return true;
}

void vpPoseGravity::updateCovariance(const vpHomogeneousMatrix &cMo, const std::vector<unsigned int> *used)
{
  m_hasCovariance = false;
  if (!m_computeCovariance)
    return;
  std::vector<Eigen::Vector3d> x, X;
  collectPoints(m_points, used, x, X);
  Eigen::Matrix<double, 6, 6> covariance;
  if (!vpGravitySolvers::detail::poseCovariance(
          toEigen(m_gCam), toEigen(m_gObj), x.data(), X.data(), static_cast<int>(x.size()),
          refineOptions(m_imageStdDev, m_gCamStdDev, m_gObjStdDev, m_loss, m_lossScale), toPose(cMo), covariance))
    return;
  storeMatrix(covariance, m_covariance);
  m_hasCovariance = true;
}

bool vpPoseGravity::refinePose(vpHomogeneousMatrix &cMo)
{
  checkReady(2, static_cast<unsigned int>(m_points.size()), "refinePose", false);
  if (!cMo.isAnHomogeneousMatrix()) { // a pose that is not rigid would be refined into another one
    m_status = STATUS_REFINEMENT_FAILED;
    return false;
  }
  const std::vector<unsigned int> *used = m_refineOnInliers ? &m_inlierIndex : nullptr;
  std::vector<Eigen::Vector3d> x, X;
  collectPoints(m_points, used, x, X);
  const vpGravitySolvers::detail::RefineOptions options =
      refineOptions(m_imageStdDev, m_gCamStdDev, m_gObjStdDev, m_loss, m_lossScale);
  Pose pose = toPose(cMo);
  if (x.size() < 2 || !vpGravitySolvers::detail::refinePose(toEigen(m_gCam), toEigen(m_gObj), x.data(), X.data(),
                                                            static_cast<int>(x.size()), options, pose)) {
    m_status = STATUS_REFINEMENT_FAILED;
    return false;
  }
  storePose(pose, cMo);
  // A singular covariance (the yaw unobservable: every point on one vertical line) leaves the refined pose,
  // without a covariance (the refinement was refused before when only its covariance could not be had).
  updateCovariance(cMo, used);
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

void vpPoseGravity::setConsistencyThreshold(double t)
{
  if (!(t > 0.0) || !std::isfinite(t))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setConsistencyThreshold: threshold must be finite and > 0");
  m_consistencyThreshold = t;
}

void vpPoseGravity::setRansacThreshold(double t)
{
  if (!(t > 0.0) || !std::isfinite(t))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setRansacThreshold: threshold must be > 0");
  m_ransacThreshold = t;
}

void vpPoseGravity::setRansacMaxTrials(int trials)
{
  if (trials <= 0)
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setRansacMaxTrials: must be > 0");
  m_ransacMaxTrials = trials;
}

void vpPoseGravity::setRansacProbability(double p)
{
  if (!(p > 0.0 && p < 1.0))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setRansacProbability: must be in (0, 1)");
  m_ransacProbability = p;
}

void vpPoseGravity::setRansacSeed(unsigned int seed) { m_ransacSeed = seed; }

void vpPoseGravity::setRansacSignificance(double alpha)
{
  if (!(alpha > 0.0 && alpha <= 1.0))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setRansacSignificance: must be in (0, 1]");
  m_ransacSignificance = alpha;
}

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
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setImageStdDev: must be > 0");
  m_imageStdDev = sigma;
}

void vpPoseGravity::setCameraGravityStdDev(double sigma)
{
  checkStdDev(sigma, "setCameraGravityStdDev");
  m_gCamStdDev = sigma;
}

void vpPoseGravity::setObjectGravityStdDev(double sigma)
{
  checkStdDev(sigma, "setObjectGravityStdDev");
  m_gObjStdDev = sigma;
}

void vpPoseGravity::setGravityStdDev(double sigma)
{
  checkStdDev(sigma, "setGravityStdDev");
  m_gCamStdDev = m_gObjStdDev = sigma;
}

void vpPoseGravity::setRefineLoss(vpRobustLoss loss, double scale)
{
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw vpPoseGravityException(vpPoseGravityException::badParameterError,
                                 "vpPoseGravity::setRefineLoss: the scale must be finite and > 0");
  m_loss = loss;
  m_lossScale = scale;
}

vpMatrix vpPoseGravity::getCovarianceMatrix() const
{
  if (!m_hasCovariance)
    throw vpPoseGravityException(vpPoseGravityException::notComputedError,
                                 "vpPoseGravity::getCovarianceMatrix: no covariance computed; call "
                                 "setCovarianceComputation(true) before computePose() or refinePose()");
  return m_covariance;
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
    return "the measurements admit no pose (check the gravity vectors: down, in the sensor frame, after the "
           "IMU-to-sensor rotation)";
  case STATUS_NO_CONSENSUS:
    return "RANSAC found no model with at least the minimum consensus of inliers and more than chance explains";
  case STATUS_REFINEMENT_FAILED:
    return "the refinement gave no usable solution or put a point behind the camera; the pose was left unchanged";
  case STATUS_INCONSISTENT_GRAVITY:
    return "the points do not fit any pose with these gravity directions beyond the consistency threshold: check "
           "the IMU-to-camera (object) rotation, that the IMUs were at rest, the point matches (outliers: use RANSAC)";
  case STATUS_GRAVITY_SIGN_REVERSED:
    return "the points fit a pose only with one gravity vector reversed: gravity must point down, an accelerometer "
           "at rest measures the specific force, which points up (negate it, or use vpImuGravity)";
  case STATUS_BEHIND_CAMERA:
    return "the best pose puts a point behind the camera: check the gravity sign and the IMU-to-camera rotation";
  case STATUS_GRAVITY_SWAPPED:
    return "the points fit a pose only with the camera and object gravity exchanged: setCameraGravity() takes the "
           "gravity in the camera frame, setObjectGravity() the one in the object frame";
  }
  return "unknown status";
}

std::string vpPoseGravity::getMistakeMessage(vpGravityMistake mistake)
{
  switch (mistake) {
  case GRAVITY_MISTAKE_NONE:
    return "no standard mistake explains it (check the IMU-to-camera and IMU-to-object rotations: missing, "
           "transposed or of another IMU)";
  case GRAVITY_MISTAKE_SIGN_REVERSED:
    return "the points fit the camera gravity reversed: an accelerometer reading (specific force, pointing up) was "
           "passed as gravity";
  case GRAVITY_MISTAKE_SWAPPED:
    return "the points fit the camera and object gravity exchanged";
  }
  return "unknown mistake";
}
