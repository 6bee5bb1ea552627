/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpPoseGravity.h
  \brief Pose from 2, 3 or n points when the camera and the object both measure gravity.
*/
#ifndef VP_POSE_GRAVITY_H
#define VP_POSE_GRAVITY_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/pose_gravity/vpPoseGravityException.h>
#include <visp3/robust/vpRobustScale.h>

/*!
  \ingroup group_pose_gravity
  \brief Gravity-aided pose estimation, modelled on vpPose.

  A camera and an object each carry an IMU measuring the direction of gravity in their own frame.
  The rotation \f$ {}^c\mathbf{R}_o \f$ is then known up to one angle about the vertical, so that two
  points give two candidate poses and a third point selects one (D'Alfonso, Garone, Muraca,
  Pugliese, "P3P and P2P problems with known camera and object vertical directions", MED 2013).

  <b>Conventions</b> (the same in every header of the module):
  - cMo is the pose of the object in the camera frame: \f$ {}^c\mathbf{X} = {}^c\mathbf{R}_o\, {}^o\mathbf{X} + {}^c\mathbf{t}_o \f$.
  - Gravity vectors point \b down (the direction a dropped object falls), each in the frame of the
    sensor it refers to (camera or object), i.e. after the IMU-to-sensor rotation; any positive norm.
    An accelerometer at rest measures the specific force, which points \b up: pass its opposite, or
    use vpImuGravity, which converts raw readings, applies the IMU-to-sensor rotation and flags
    readings taken in motion.
  - Image points are normalized and undistorted (vpPixelMeterConversion): \f$ x = (u-u_0)/p_x \f$.
  - Thresholds are in normalized units: a value of \f$ k / f \f$ is \f$ k \f$ pixels for a focal
    length of \f$ f \f$ pixels.

  Usage in short:
  - setCameraGravity() / setObjectGravity(): gravity measured by each IMU.
  - addPoint() / addPoints(): as in vpPose, object coordinates from vpPoint::get_oX(), get_oY(),
    get_oZ() and normalized image coordinates from vpPoint::get_x(), get_y().
  - computePoseCandidates(): the (up to) two P2P poses from the first two points.
  - computePose(P3P, cMo): first three points; LEAST_SQUARES: all points; RANSAC: 2-point samples,
    setRansacThreshold(), setRansacNbInliersToReachConsensus(), getRansacInliers().
  - Every method checks its result (details in computePose()): P3P its three points in front of the
    camera and the third one reprojected within setConsistencyThreshold(); LEAST_SQUARES every point
    in front and the median reprojection error within it; RANSAC a consensus larger than chance
    explains. An inconsistent result returns false with STATUS_GRAVITY_SIGN_REVERSED (the data fit
    with one gravity reversed: a specific force passed as gravity), STATUS_GRAVITY_SWAPPED (the data
    fit with the camera and object gravity exchanged), STATUS_INCONSISTENT_GRAVITY (wrong
    IMU-to-camera rotation, IMU in motion, mismatched points) or STATUS_BEHIND_CAMERA; RANSAC
    without a consensus returns false with STATUS_NO_CONSENSUS, getSuspectedMistake() naming the
    reversed or exchanged gravity under which one exists.
  - refinePose(): Ceres maximum likelihood, optional robust loss (setRefineLoss()), gravity priors
    (setCameraGravityStdDev(), setObjectGravityStdDev()); setCovarianceComputation() /
    getCovarianceMatrix() as in vpPose.
  - Bad input throws vpPoseGravityException; degenerate-but-legal geometry (paper's Lemma 1)
    returns false / no candidate and getStatus() tells why.

  \code
  vpPoseGravity pose;
  pose.setCameraGravity(g_cam);   // down, in the camera frame (NOT the raw accelerometer reading)
  pose.setObjectGravity(g_obj);   // down, in the object frame
  pose.addPoints(points);         // >= 3 vpPoint with oX,oY,oZ and x,y set
  vpHomogeneousMatrix cMo;
  if (pose.computePose(vpPoseGravity::P3P, cMo))
    pose.refinePose(cMo);         // optional maximum-likelihood refinement
  else
    std::cout << vpPoseGravity::getStatusMessage(pose.getStatus()) << std::endl;
  \endcode

  The solvers themselves are pure Eigen functions in vpGravitySolvers.h.
*/
class VISP_EXPORT vpPoseGravity
{
public:
  //! Pose estimation methods.
  typedef enum {
    P3P, //!< P3P on the first three points: P2P on the pair chosen by setP3PPairRule(), the third point selects and checks.
    LEAST_SQUARES, //!< least squares on all n >= 3 points: global minimum of the inverse-depth reweighted cost (1-DOF rotation + translation).
    RANSAC //!< 2-point RANSAC on n >= 3 points with local optimisation; see setRansacThreshold() and setRansacNbInliersToReachConsensus().
  } vpPoseGravityMethod;

  //! What the last computation found (see getStatus()).
  typedef enum {
    STATUS_NOT_COMPUTED,            //!< nothing computed yet.
    STATUS_OK,                      //!< a pose (or two candidates) was found.
    STATUS_COINCIDENT_IMAGE_POINTS, //!< Lemma 1, second case: both image points on one ray not parallel to gravity; rotation unique, translation only up to the ray.
    STATUS_VERTICAL_RAY, //!< Lemma 1, third case: both image points on one ray parallel to gravity; infinitely many poses. Also reported when the yaw is unobservable from the pair for another reason (vertical object segment, both rays horizontal).
    STATUS_NO_SOLUTION,  //!< the measurements admit no pose (e.g. too inconsistent for the trigonometric equation).
    STATUS_NO_CONSENSUS, //!< RANSAC found no model with at least setRansacNbInliersToReachConsensus() inliers and more than chance explains (getSuspectedMistake() tells whether the gravity reversed or exchanged has one).
    STATUS_REFINEMENT_FAILED, //!< refinePose() did not converge or moved a point behind the camera; the input pose was left unchanged.
    STATUS_INCONSISTENT_GRAVITY, //!< the best pose leaves points beyond setConsistencyThreshold(): wrong IMU-to-camera rotation, IMU in motion, wrong matches or outliers (use RANSAC).
    STATUS_GRAVITY_SIGN_REVERSED, //!< the points fit a pose only with one of the two gravity vectors reversed: an accelerometer reading (specific force, pointing up) was passed as gravity (which points down).
    STATUS_BEHIND_CAMERA,         //!< the best pose puts a used point behind the camera.
    STATUS_GRAVITY_SWAPPED //!< the points fit a pose only with the camera and object gravity exchanged (RANSAC: the exchange explains more of them).
  } vpPoseGravityStatus;

  /*!
    A standard mistake in the gravity vectors that explains a failure (getSuspectedMistake()): the
    computation is run again with the alternative vectors and the points fit them.
  */
  typedef enum {
    GRAVITY_MISTAKE_NONE,          //!< no failure, or no alternative explains it
    GRAVITY_MISTAKE_SIGN_REVERSED, //!< the points fit the camera gravity reversed (a specific force passed as gravity)
    GRAVITY_MISTAKE_SWAPPED        //!< the points fit the camera and object gravity exchanged
  } vpGravityMistake;

  //! Pair choice of the P3P method (see vpGravitySolvers::p3p()).
  typedef enum {
    P3P_BEST_THIRD_POINT, //!< the three pairs are solved, the pose that reprojects its third point best is kept (default).
    P3P_WIDEST_PAIR       //!< the paper's rule: the pair farthest apart in the image.
  } vpP3PPairRule;

  /*!
    Robust loss of refinePose() on each point's reprojection error (see setRefineLoss()): the
    project's one loss enum (::vpRobustLoss, visp3/robust/vpRobustScale.h) under its former name.
  */
  typedef ::vpRobustLoss vpRobustLoss;
  //! Squared error: maximum likelihood under Gaussian noise (default); vpRobustLoss::NONE.
  static constexpr vpRobustLoss LOSS_NONE = vpRobustLoss::NONE;
  //! Quadratic below the scale, linear beyond; vpRobustLoss::HUBER.
  static constexpr vpRobustLoss LOSS_HUBER = vpRobustLoss::HUBER;
  //! \f$ \log(1 + (r/s)^2) \f$: the influence of large errors vanishes; vpRobustLoss::CAUCHY.
  static constexpr vpRobustLoss LOSS_CAUCHY = vpRobustLoss::CAUCHY;

  //! Filtering of degenerate points before RANSAC, as vpPose::RANSAC_FILTER_FLAGS.
  typedef enum {
    NO_FILTER, //!< points used as given; a sample of two identical object points is skipped.
    PREFILTER_DEGENERATE_POINTS //!< points whose object or image coordinates repeat an earlier point's (within 1e-12 relative) are left out (default).
  } RANSAC_FILTER_FLAGS;

  //! Estimator without points nor gravity; RANSAC and refinement settings at their defaults.
  vpPoseGravity();

  /*! Gravity direction in the camera frame, pointing down (any positive norm; normalized inside).
      Not the accelerometer reading, which points up (see vpImuGravity).
      \exception vpPoseGravityException::badGravityError on a zero, non-finite or non-3-vector. */
  void setCameraGravity(const vpColVector &g_cam);
  /*! Gravity direction in the object frame, pointing down (any positive norm; normalized inside).
      \exception vpPoseGravityException::badGravityError on a zero, non-finite or non-3-vector. */
  void setObjectGravity(const vpColVector &g_obj);
  //! Unit gravity in the camera frame (zero vector until set).
  vpColVector getCameraGravity() const;
  //! Unit gravity in the object frame (zero vector until set).
  vpColVector getObjectGravity() const;

  /*! Adds a point (object coordinates and normalized image coordinates), like vpPose::addPoint().
      The coordinates are checked when a pose is computed. Forgets the last RANSAC inliers. */
  void addPoint(const vpPoint &P);
  //! Adds several points, like vpPose::addPoints(). Forgets the last RANSAC inliers.
  void addPoints(const std::vector<vpPoint> &lP);
  //! Removes all points (and the last RANSAC inliers).
  void clearPoint();
  //! Points added so far, in order.
  const std::vector<vpPoint> &getPoints() const { return m_points; }

  /*!
    All P2P solutions from the first two points, ordered by increasing yaw angle about the vertical
    (as defined in vpGravitySolvers.h); roots that would put a point behind the camera are left out,
    so that one candidate is common. Empty, with getStatus() telling why, in the degenerate cases
    of Lemma 1 (STATUS_COINCIDENT_IMAGE_POINTS, STATUS_VERTICAL_RAY; vpGravitySolvers::p2p() gives
    the rotation in the first case) and when no real solution exists (STATUS_NO_SOLUTION). Two
    points give no redundancy: nothing checks the candidates.
    \exception vpPoseGravityException on missing gravity, fewer than 2 points, bad coordinates or
    identical object points.
  */
  std::vector<vpHomogeneousMatrix> computePoseCandidates();

  /*!
    Computes cMo with the given method. Returns false, with getStatus() telling why, when the
    geometry is degenerate but legal, when the result fails its consistency check or when RANSAC
    finds no consensus; cMo is then untouched.
    - P3P uses the first three points only; all three must be in front of the camera and reproject
      within setConsistencyThreshold() (the two points of the solved pair do by construction, the
      third one checks the gravity directions: 6 equations for 4 unknowns).
    - LEAST_SQUARES uses all points: every point in front and the median reprojection error within
      setConsistencyThreshold() (STATUS_NO_SOLUTION when all the points lie on one vertical line: the
      yaw is then unobservable). The median targets what misplaces every point (gravity sign, IMU
      rotation); a few outliers pull the least-squares pose without failing the check: use RANSAC.
    - RANSAC draws 2-point samples, scores the P2P candidates by reprojection error against
      setRansacThreshold(), refits each new best model by LEAST_SQUARES on its inliers and finally on
      the whole consensus set; it succeeds only when the consensus reaches both
      setRansacNbInliersToReachConsensus() and the count that chance alone explains with probability
      below setRansacSignificance() (else STATUS_NO_CONSENSUS).
    The same solve is also run with the camera gravity reversed: if that one is consistent and the
    given one is not, or leaves more error than the noise explains (3 times the root sum of squares
    of setImageStdDev() and the two gravity standard deviations) and more than twice the reversed
    one's, the status is STATUS_GRAVITY_SIGN_REVERSED and no pose is returned (with 3 points the two
    redundant equations alone cannot always reject a wrong sign). The same holds for the two vectors
    exchanged (STATUS_GRAVITY_SWAPPED), unless they are equal within their noise (see
    getSuspectedMistake()). Setting the sensors' standard deviations before computePose() thus makes the
    test fit their noise.
    \param method : P3P, LEAST_SQUARES or RANSAC.
    \param cMo : receives the pose on success.
    \exception vpPoseGravityException on missing gravity, too few points for the method (3),
    non-finite coordinates, duplicate object points (equal within 1e-12 times the largest object
    coordinate; RANSAC filters them instead, see setRansacFilterFlag()) or (P3P) collinear object points.
  */
  bool computePose(vpPoseGravityMethod method, vpHomogeneousMatrix &cMo);

  /*!
    Maximum-likelihood refinement with Ceres of the reprojection error in normalized coordinates
    over all points (RANSAC inliers only after a RANSAC computation), with the robust loss of
    setRefineLoss().
    With both gravity standard deviations 0 (the default) the refinement has 4 DOF: the yaw angle
    and the translation, both gravity vectors held exact. Otherwise all 6 DOF are refined and the two
    gravity measurements enter as a soft prior \f$ ({}^c\mathbf{R}_o \mathbf{g}_o - \mathbf{g}_c) /
    \sqrt{\sigma_c^2 + \sigma_o^2} \f$ (see setCameraGravityStdDev(), setObjectGravityStdDev()).
    The covariance is computed at the result when setCovarianceComputation(true); when it is singular (every
    used point on one vertical line: the yaw is unobservable) the refined pose is still returned, without a
    covariance (getCovarianceMatrix() throws).
    \param cMo : initial pose (any method), replaced by the refined pose on success.
    \return true if Ceres returned a usable solution with every used point in front of the camera
    (cMo updated), false otherwise (cMo unchanged, status STATUS_REFINEMENT_FAILED), e.g. for a
    non-finite initial pose or one that is not a rigid transformation.
    \exception vpPoseGravityException on missing gravity, fewer than 2 points or bad coordinates.
  */
  bool refinePose(vpHomogeneousMatrix &cMo);

  /*! Sum of squared reprojection errors in normalized coordinates over all points, like
      vpPose::computeResidual(): \f$ \sum_i (x_i - X_c/Z_c)^2 + (y_i - Y_c/Z_c)^2 \f$. Needs no gravity. */
  double computeResidual(const vpHomogeneousMatrix &cMo) const;

  /*!
    Tolerance of the consistency check of computePose(), in normalized units (pixels / focal
    length); default 0.04 (32 px at f = 800). It must cover the image noise and what the gravity
    error does to the points: a relative tilt error of \f$ \delta \f$ rad between the two IMUs moves
    them by up to about \f$ \delta \f$ (1 degree = 14 px at f = 800); the default covers the 3-sigma
    tilt of two IMUs of 0.01 per component. A reversed gravity sign or a wrong IMU-to-camera rotation
    leaves errors of the order of the image size; the sign is also tested by comparison (see
    computePose()). Throws badParameterError unless > 0.
  */
  void setConsistencyThreshold(double t);
  //! Tolerance of the consistency check (normalized units).
  double getConsistencyThreshold() const { return m_consistencyThreshold; }
  //! Pair choice of the P3P method; default P3P_BEST_THIRD_POINT.
  void setP3PPairRule(vpP3PPairRule rule) { m_pairRule = rule; }

  /*!
    RANSAC inlier threshold on the reprojection error in normalized coordinates, i.e. pixels over
    the focal length in pixels: default 4e-3, 3.2 px at f = 800, which keeps more than 95 % of the
    true inliers under 1 px image noise (a true inlier's error is about Rayleigh-distributed).
    Throws badParameterError unless > 0.
  */
  void setRansacThreshold(double t);
  //! RANSAC inlier threshold (normalized units).
  double getRansacThreshold() const { return m_ransacThreshold; }
  //! Maximum number of RANSAC samples; default 1000. Throws badParameterError unless > 0.
  void setRansacMaxTrials(int trials);
  //! Confidence of the adaptive RANSAC stop; default 0.99. Throws badParameterError unless in (0, 1).
  void setRansacProbability(double p);
  //! Seed of the RANSAC sampler; default 0.
  void setRansacSeed(unsigned int seed);
  /*!
    Inliers a RANSAC model needs at least to be accepted, as vpPose::setRansacNbInliersToReachConsensus();
    default 4 (vpPose's default). Values below 3 are raised to 3 (the least squares refit needs 3).
  */
  void setRansacNbInliersToReachConsensus(unsigned int nb) { m_ransacNbInliersConsensus = nb; }
  //! The minimum consensus set by setRansacNbInliersToReachConsensus().
  unsigned int getRansacNbInliersToReachConsensus() const { return m_ransacNbInliersConsensus; }
  /*!
    Significance of the RANSAC consensus against chance, default 0.01: a model is accepted only if
    the probability that this many points agree with the best of the models tried by chance alone
    is below it. An outlier falls within the threshold \f$ \tau \f$ of a prediction with probability
    \f$ p = \pi\tau^2 / A \f$ (A: area of the bounding box of the image points grown by
    \f$ \tau \f$ on each side); with m models scored on n points the consensus k must satisfy
    \f$ m\, P(\mathrm{Bin}(n-2, p) \ge k-2) < \f$ significance.
    1 disables the test. Throws badParameterError unless in (0, 1].
  */
  void setRansacSignificance(double alpha);
  //! Degenerate-point filtering before RANSAC, as vpPose::setRansacFilterFlag(); default PREFILTER_DEGENERATE_POINTS.
  void setRansacFilterFlag(RANSAC_FILTER_FLAGS flag) { m_ransacFilter = flag; }
  //! Inliers of the last RANSAC computation.
  std::vector<vpPoint> getRansacInliers() const;
  //! Indices (into getPoints()) of the inliers of the last RANSAC computation.
  std::vector<unsigned int> getRansacInlierIndex() const { return m_inlierIndex; }
  //! Number of inliers of the last RANSAC computation, as vpPose::getRansacNbInliers().
  unsigned int getRansacNbInliers() const { return static_cast<unsigned int>(m_inlierIndex.size()); }
  //! Number of samples drawn by the last RANSAC computation.
  int getRansacTrials() const { return m_ransacTrials; }

  //! Standard deviation of image measurements in normalized coordinates, used by refinePose() and the covariance; default 1e-3. Throws badParameterError unless > 0.
  void setImageStdDev(double sigma);
  /*! Standard deviation of each component of the unit camera gravity; 0 (default) holds it exact in
      refinePose(). Throws badParameterError if < 0. */
  void setCameraGravityStdDev(double sigma);
  /*! Standard deviation of each component of the unit object gravity; 0 (default) holds it exact in
      refinePose(). Throws badParameterError if < 0. */
  void setObjectGravityStdDev(double sigma);
  /*! Sets both gravity standard deviations (setCameraGravityStdDev(), setObjectGravityStdDev()) to \e sigma.
      Throws badParameterError if < 0. */
  void setGravityStdDev(double sigma);
  /*!
    Robust loss of refinePose() on each point's reprojection error and its scale in normalized units
    (e.g. 3 px / f); default LOSS_NONE. Use LOSS_HUBER or LOSS_CAUCHY when the points may hold
    outliers (after P3P or LEAST_SQUARES; after RANSAC only the inliers are used).
    Throws badParameterError unless scale > 0.
  */
  void setRefineLoss(vpRobustLoss loss, double scale = 3e-3);

  /*!
    Whether computePose() (at its result) and refinePose() (at the refined pose) compute the
    covariance of the pose, as vpPose::setCovarianceComputation(); default false.
  */
  void setCovarianceComputation(bool flag) { m_computeCovariance = flag; }
  /*!
    Covariance of the last pose computed with setCovarianceComputation(true), as
    vpPose::getCovarianceMatrix(), from the points the pose was computed on (P3P: the first three; RANSAC:
    its inliers): 6x6, parameter order \f$ (t_x, t_y, t_z, \theta_x, \theta_y,
    \theta_z) \f$ with \f$ \mathbf{t} \f$ in the unit of the object points and \f$ \theta \f$ in rad, a
    rotation perturbation on the left in the camera frame: \f$ {}^c\mathbf{R}_o = \exp([\theta]_\times)
    {}^c\hat{\mathbf{R}}_o \f$. First order, from the image standard deviation (setImageStdDev()) and,
    when set, the gravity ones. With exact gravity (both gravity standard deviations 0) the rotation
    is known but for the yaw: the matrix has rank 4 and its rotation block is
    \f$ \sigma_\alpha^2\, \mathbf{g}_c \mathbf{g}_c^T \f$.
    \exception vpPoseGravityException::notComputedError when no covariance was computed.
  */
  vpMatrix getCovarianceMatrix() const;

  //! Status of the last computation.
  vpPoseGravityStatus getStatus() const { return m_status; }
  //! A sentence describing a status, naming the likely cause for the failures.
  static std::string getStatusMessage(vpPoseGravityStatus status);
  /*!
    The standard mistake that explains the last failure: for P3P and LEAST_SQUARES the one their
    status names (STATUS_GRAVITY_SIGN_REVERSED, STATUS_GRAVITY_SWAPPED); after STATUS_NO_CONSENSUS of
    RANSAC, the alternative gravity under which a consensus exists (the same loop, threshold and
    significance); after STATUS_GRAVITY_SWAPPED of RANSAC (a consensus exists, but the exchanged
    vectors explain more of the points than chance explains), GRAVITY_MISTAKE_SWAPPED. Limits: P3P
    keeps about 1 % of exchanged-vector scenes, where the stated vectors fit the three points within
    3 times the image noise as the exchanged ones do (one frame cannot tell them); RANSAC accepts an
    exchange that tilts the pose by less than about a degree. Two vectors equal within their noise (3 times
    the root sum of squares of the gravity standard deviations, at least 1 degree: an upright camera facing
    an upright target) are never called exchanged, by any method. GRAVITY_MISTAKE_NONE after a success or
    when no alternative fits. A wrong or
    missing IMU-to-sensor rotation is not among the alternatives (the class only sees the rotated
    vectors): STATUS_INCONSISTENT_GRAVITY, or a consensus under no alternative, points to it.
  */
  vpGravityMistake getSuspectedMistake() const { return m_mistake; }
  //! A sentence describing a suspected mistake.
  static std::string getMistakeMessage(vpGravityMistake mistake);

  /*!
    Displays the frame of the pose cMo (axes of length \e size in object units) with vpDisplay, like
    vpPose::display(); the image must be attached to a display. \e color vpColor::none draws the
    axes in red, green, blue.
  */
  static void display(vpImage<unsigned char> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                      double size, const vpColor &color = vpColor::none, unsigned int thickness = 1);
  //! \copydoc display(vpImage<unsigned char> &, const vpHomogeneousMatrix &, const vpCameraParameters &, double, const vpColor &, unsigned int)
  static void display(vpImage<vpRGBa> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam, double size,
                      const vpColor &color = vpColor::none, unsigned int thickness = 1);
  /*!
    Draws the same frame as display() into the image pixels with vpImageDraw (no display needed:
    headless overlays, image files).
  */
  static void draw(vpImage<unsigned char> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                   double size, unsigned char grey = 255, unsigned int thickness = 1);
  //! The same as draw() into a colour image; \e color vpColor::none draws the axes in red, green, blue.
  static void draw(vpImage<vpRGBa> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam, double size,
                   const vpColor &color = vpColor::none, unsigned int thickness = 1);

private:
  // Throws unless both gravities are set, at least minPoints points exist and the first usedPoints
  // points have finite coordinates (and distinct object points when checkDuplicates).
  void checkReady(unsigned int minPoints, unsigned int usedPoints, const char *what, bool checkDuplicates = true) const;
  void forgetInliers();
  bool computeP3P(vpHomogeneousMatrix &cMo);
  bool computeLeastSquares(vpHomogeneousMatrix &cMo);
  bool computeRansac(vpHomogeneousMatrix &cMo);
  // The closed-form result of P3P or LEAST_SQUARES, its checks and status.
  bool finishClosedForm(vpPoseGravityMethod method, vpHomogeneousMatrix &cMo);
  void updateCovariance(const vpHomogeneousMatrix &cMo, const std::vector<unsigned int> *used);

  std::vector<vpPoint> m_points;
  vpColVector m_gCam, m_gObj;
  bool m_hasGCam, m_hasGObj;
  double m_consistencyThreshold;
  vpP3PPairRule m_pairRule;
  double m_ransacThreshold;
  int m_ransacMaxTrials;
  double m_ransacProbability;
  unsigned int m_ransacSeed;
  unsigned int m_ransacNbInliersConsensus;
  double m_ransacSignificance;
  RANSAC_FILTER_FLAGS m_ransacFilter;
  std::vector<unsigned int> m_inlierIndex;
  int m_ransacTrials;
  double m_imageStdDev, m_gCamStdDev, m_gObjStdDev;
  vpRobustLoss m_loss;
  double m_lossScale;
  bool m_computeCovariance;
  bool m_hasCovariance;
  vpMatrix m_covariance;
  vpPoseGravityStatus m_status;
  bool m_refineOnInliers; // refinePose() uses m_inlierIndex (set by a successful RANSAC)
  vpGravityMistake m_mistake;
};

#endif
