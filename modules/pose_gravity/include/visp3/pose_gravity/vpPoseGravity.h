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

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>

/*!
  \ingroup group_pose_gravity
  \brief Error thrown by vpPoseGravity on invalid input (the message says what is wrong).
*/
class VISP_EXPORT vpPoseGravityException : public vpException
{
public:
  //! Error codes.
  enum errorCodeEnum {
    badGravityError = 1,  //!< zero, non-finite or unset gravity vector
    notEnoughPointError,  //!< fewer points than the method needs
    badPointError,        //!< non-finite coordinates
    degeneratePointsError, //!< duplicate or collinear object points where the method cannot use them
    badParameterError      //!< a setting out of its range (threshold, probability, standard deviation, method)
  };
  //! Builds the exception with a code and a message.
  vpPoseGravityException(int errorCode, const std::string &msg) : vpException(errorCode, msg) {}
};

/*!
  \ingroup group_pose_gravity
  \brief Gravity-aided pose estimation, modelled on vpPose.

  A camera and an object each carry an IMU measuring the direction of gravity in their own frame.
  The rotation \f$ {}^c\mathbf{R}_o \f$ is then known up to one angle about the vertical, so that two
  points give two candidate poses and a third point selects one (D'Alfonso, Garone, Muraca,
  Pugliese, "P3P and P2P problems with known camera and object vertical directions", MED 2013).

  Usage in short:
  - setCameraGravity() / setObjectGravity(): gravity measured by each IMU, any positive norm.
  - addPoint() / addPoints(): as in vpPose, object coordinates from vpPoint::get_oX(), get_oY(),
    get_oZ() and normalized image coordinates from vpPoint::get_x(), get_y().
  - computePoseCandidates(): the (up to) two P2P poses from the first two points.
  - computePose(P3P, cMo): first three points; LEAST_SQUARES: all points, closed form;
    RANSAC: 2-point samples, setRansacThreshold() in normalized units, getRansacInliers().
  - refinePose(): Ceres maximum likelihood; setGravityStdDev() > 0 also refines the tilt.
  - Bad input throws vpPoseGravityException; degenerate-but-legal geometry (paper's Lemma 1)
    returns false / no candidate and getStatus() tells why.

  \code
  vpPoseGravity pose;
  pose.setCameraGravity(g_cam);   // from the camera IMU, any positive norm
  pose.setObjectGravity(g_obj);   // from the object IMU
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
    P3P,           //!< the paper's P3P: P2P on the widest image pair, third point selects (exactly 3 points used: the first three).
    LEAST_SQUARES, //!< closed-form least squares on all n >= 3 points (1-DOF rotation + translation, no iteration).
    RANSAC         //!< 2-point RANSAC on n >= 3 points with local optimisation; see setRansacThreshold().
  } vpPoseGravityMethod;

  //! What the last computation found (see getStatus()).
  typedef enum {
    STATUS_NOT_COMPUTED,        //!< nothing computed yet.
    STATUS_OK,                  //!< a pose (or two candidates) was found.
    STATUS_COINCIDENT_IMAGE_POINTS, //!< Lemma 1, second case: both image points on one ray not parallel to gravity; rotation unique, translation only up to the ray.
    STATUS_VERTICAL_RAY,        //!< Lemma 1, third case: both image points on one ray parallel to gravity; infinitely many poses. Also reported when the yaw is unobservable from the pair for another reason (vertical object segment, both rays horizontal).
    STATUS_NO_SOLUTION,         //!< the measurements admit no pose (e.g. too inconsistent for the trigonometric equation).
    STATUS_NO_CONSENSUS,        //!< RANSAC found no model with enough inliers.
    STATUS_REFINEMENT_FAILED    //!< refinePose() did not converge; the input pose was left unchanged.
  } vpPoseGravityStatus;

  //! Estimator without points nor gravity; RANSAC and refinement settings at their defaults.
  vpPoseGravity();

  /*! Gravity direction in the camera frame (any positive norm; normalized inside).
      \exception vpPoseGravityException::badGravityError on a zero, non-finite or non-3-vector. */
  void setCameraGravity(const vpColVector &g_cam);
  /*! Gravity direction in the object frame (any positive norm; normalized inside).
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
    the rotation in the first case) and when no real solution exists (STATUS_NO_SOLUTION).
    \exception vpPoseGravityException on missing gravity, fewer than 2 points, bad coordinates or
    identical object points.
  */
  std::vector<vpHomogeneousMatrix> computePoseCandidates();

  /*!
    Computes cMo with the given method. Returns false, with getStatus() telling why, when the
    geometry is degenerate but legal or when RANSAC finds no consensus; cMo is then untouched.
    - P3P uses (and checks) the first three points only.
    - LEAST_SQUARES uses all points, closed form (STATUS_NO_SOLUTION when all the points lie on one
      vertical line: the yaw is then unobservable).
    - RANSAC draws 2-point samples, scores the P2P candidates by reprojection error against
      setRansacThreshold(), refits each new best model by LEAST_SQUARES on its inliers and finally on
      the whole consensus set; it needs at least 3 inliers (else STATUS_NO_CONSENSUS).
    \param method : P3P, LEAST_SQUARES or RANSAC.
    \param cMo : receives the pose on success.
    \exception vpPoseGravityException on missing gravity, too few points for the method (3),
    non-finite coordinates, duplicate object points (equal within 1e-12 times the largest object
    coordinate) or (P3P) collinear object points.
  */
  bool computePose(vpPoseGravityMethod method, vpHomogeneousMatrix &cMo);

  /*!
    Maximum-likelihood refinement with Ceres of the reprojection error in normalized coordinates
    over all points (RANSAC inliers only after a RANSAC computation).
    Without gravity priors (setGravityStdDev(0), the default) the refinement has 4 DOF: the yaw
    angle and the translation, both gravity vectors held exact. With a positive gravity standard
    deviation all 6 DOF are refined and the two gravity measurements enter as soft priors.
    The gravity priors are whitened residuals \f$ ({}^c\mathbf{R}_o \mathbf{g}_o - \mathbf{g}_c) / (\sqrt{2}\sigma_g) \f$.
    \param cMo : initial pose (any method), replaced by the refined pose on success.
    \return true if Ceres returned a usable solution (cMo updated), false otherwise (cMo unchanged,
    status STATUS_REFINEMENT_FAILED), e.g. for a non-finite initial pose.
    \exception vpPoseGravityException on missing gravity, fewer than 2 points or bad coordinates.
  */
  bool refinePose(vpHomogeneousMatrix &cMo);

  /*! Sum of squared reprojection errors in normalized coordinates over all points, like
      vpPose::computeResidual(): \f$ \sum_i (x_i - X_c/Z_c)^2 + (y_i - Y_c/Z_c)^2 \f$. Needs no gravity. */
  double computeResidual(const vpHomogeneousMatrix &cMo) const;

  //! RANSAC inlier threshold on the reprojection error in normalized coordinates (as vpPose); default 1e-3. Throws badParameterError unless > 0.
  void setRansacThreshold(double t);
  //! Maximum number of RANSAC samples; default 1000. Throws badParameterError unless > 0.
  void setRansacMaxTrials(int trials);
  //! Confidence of the adaptive RANSAC stop; default 0.99. Throws badParameterError unless in (0, 1).
  void setRansacProbability(double p);
  //! Seed of the RANSAC sampler; default 0.
  void setRansacSeed(unsigned int seed);
  //! Inliers of the last RANSAC computation.
  std::vector<vpPoint> getRansacInliers() const;
  //! Indices (into getPoints()) of the inliers of the last RANSAC computation.
  std::vector<unsigned int> getRansacInlierIndex() const { return m_inlierIndex; }
  //! Number of samples drawn by the last RANSAC computation.
  int getRansacTrials() const { return m_ransacTrials; }

  //! Standard deviation of image measurements in normalized coordinates, used by refinePose(); default 1e-3. Throws badParameterError unless > 0.
  void setImageStdDev(double sigma);
  //! Standard deviation of each gravity component (unit vectors); 0 (default) holds gravity exact in refinePose(). Throws badParameterError if < 0.
  void setGravityStdDev(double sigma);

  //! Status of the last computation.
  vpPoseGravityStatus getStatus() const { return m_status; }
  //! A sentence describing a status.
  static std::string getStatusMessage(vpPoseGravityStatus status);

private:
  // Throws unless both gravities are set, at least minPoints points exist and the first usedPoints
  // points have finite coordinates and distinct object points.
  void checkReady(unsigned int minPoints, unsigned int usedPoints, const char *what) const;
  void forgetInliers();
  bool computeP3P(vpHomogeneousMatrix &cMo);
  bool computeLeastSquares(vpHomogeneousMatrix &cMo);
  bool computeRansac(vpHomogeneousMatrix &cMo);

  std::vector<vpPoint> m_points;
  vpColVector m_gCam, m_gObj;
  bool m_hasGCam, m_hasGObj;
  double m_ransacThreshold;
  int m_ransacMaxTrials;
  double m_ransacProbability;
  unsigned int m_ransacSeed;
  std::vector<unsigned int> m_inlierIndex;
  int m_ransacTrials;
  double m_imageStdDev, m_gravityStdDev;
  vpPoseGravityStatus m_status;
  bool m_refineOnInliers; // refinePose() uses m_inlierIndex (set by a successful RANSAC)
};

#endif
