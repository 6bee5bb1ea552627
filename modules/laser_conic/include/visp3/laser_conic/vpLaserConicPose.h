/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicPose.h
  \brief Altitude and attitude of a camera/circular-laser rig over a ground plane.
*/
#ifndef VP_LASER_CONIC_POSE_H
#define VP_LASER_CONIC_POSE_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicException.h>

struct vpRansacOptions;
namespace vpLaserRobustFit
{
struct Settings;
struct Result;
} // namespace vpLaserRobustFit

/*!
  \ingroup group_laser_conic
  \brief Ground plane, altitude, roll and pitch from the image of a circular laser trace, modelled on vpPose.

  A laser rigidly attached to the camera projects a cone of light; its trace on the ground is a
  conic whose image is measured. From it the ground plane is recovered in the camera frame
  (Boutteau, Sturm, Vasseur, Demonceaux, "Circular laser/camera-based attitude and altitude
  estimation: minimal and robust solutions", JMIV 2018).

  \code
  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);
  estimator.setLaser(vpMath::rad(34), cMl);  // full opening angle, laser pose in the camera frame
  vpPlane cPlane;
  if (estimator.computePlane(points, vpLaserConicPose::GP3, cPlane))
    std::cout << estimator.getAltitude() << " m" << std::endl;
  \endcode

  Attitude convention: with \f$ \mathbf{g} \f$ the unit downward normal of the ground in the camera
  frame, \f$ \mathbf{g} = R_x(\mathrm{roll}) R_y(\mathrm{pitch})\,(0,0,1)^T \f$; both angles are zero
  when the optical axis is perpendicular to the ground.
*/
class VISP_EXPORT vpLaserConicPose
{
public:
  //! Estimation methods.
  typedef enum {
    PLANE_PAIR, //!< least-squares conic on all points, then the plane pair (Sec. 4, 5.1); no outlier rejection.
    PP5,        //!< 5-point RANSAC on the image conic, plane pair on the best conic (Sec. 5.1).
    PP3,        //!< 3-point RANSAC with the two epipolar tangency constraints (Sec. 5.2).
    GP3         //!< 3-point RANSAC directly on the ground plane from ray/cone intersections (Sec. 5.3).
  } vpLaserConicMethod;

  //! Outcome of the last computePlane() (getStatusMessage() says it in words).
  typedef enum {
    STATUS_NOT_COMPUTED,       //!< computePlane() not called yet
    STATUS_OK,                 //!< a plane was found
    STATUS_COLLINEAR_POINTS,   //!< all points lie on one line
    STATUS_NOT_AN_ELLIPSE,     //!< the least-squares conic of the points (or of the trace) is not an ellipse
    STATUS_NO_CONSENSUS,       //!< no hypothesis gathers enough inliers
    STATUS_CAMERA_INSIDE_CONE, //!< PP3 only: no epipolar tangent, the camera centre lies inside the laser cone
    STATUS_NO_PLANE_PAIR,      //!< the plane pair of the conic has no ground plane
    STATUS_PLANE_NOT_FINITE,   //!< the estimated plane is not finite
    STATUS_PLANE_BEHIND,       //!< the plane is behind the system (its trace cannot be seen there)
    STATUS_SHORT_ARC           //!< the trace found covers too short an arc (setArcCoverageThreshold())
  } vpLaserConicStatus;

  /*!
    Final fit on the trace, after the RANSAC search (setFinalFit()).
    - FINAL_FIT_FREE: least-squares conic on the trace (5 degrees of freedom: it ignores the
      tangency of the image conic to the two epipolar lines of the rig), then its plane pair. This is
      what PP5 does, and what the paper's PP3 does after its 3-point search: PP3 with this final fit is
      PP5 on PP3's inliers, it optimises the algebraic conic residual, not the rig's constraints.
    - FINAL_FIT_CONSTRAINED: the plane refined on the trace (3 degrees of freedom, Sampson distances
      to the trace it predicts, Huber IRLS): the conic keeps its tangency to the epipolar lines.
    - FINAL_FIT_SELECT: the constrained fit, unless the data reject it against the free fit (F-test
      of the two extra degrees of freedom at 1 %): then the calibration cannot explain the trace
      (getCalibrationHealth()), the constrained fit absorbs the calibration error into the plane, and
      the free fit is used.
    - FINAL_FIT_DEFAULT: FREE for PLANE_PAIR and PP5, SELECT for PP3 and GP3.
  */
  typedef enum {
    FINAL_FIT_DEFAULT,     //!< FREE for PLANE_PAIR and PP5, SELECT for PP3 and GP3
    FINAL_FIT_FREE,        //!< least-squares conic (5 DOF) on the trace, then its plane pair
    FINAL_FIT_CONSTRAINED, //!< plane refined on the trace (3 DOF, tangency to the epipolar lines kept)
    FINAL_FIT_SELECT       //!< CONSTRAINED unless an F-test at 1 % rejects it against FREE
  } vpLaserConicFinalFit;

  //! Estimator with the default settings (2 px threshold, 1000 samples, p = 0.99, scale-adaptive final stage).
  vpLaserConicPose();

  /*!
    Camera intrinsics, with or without radial distortion. Image points are converted to normalized
    (undistorted) coordinates with vpPixelMeterConversion, i.e. with the distorted-to-undistorted
    coefficient kdu when the model is vpCameraParameters::perspectiveProjWithDistortion (the
    conversion vpLaserConicCalibration uses).
    \exception vpLaserConicException::badCameraError on non-finite parameters, non-positive focal
    lengths or a projection model other than the two perspective ones.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    Laser cone: \e openingAngle is the full opening angle in radians, in (0, pi); \e cMl the pose of
    the laser frame in the camera frame (apex at its origin, cone axis along +Z).
    \exception vpLaserConicException::badLaserError on a bad angle, a non-finite pose or an apex at
    the camera centre.
  */
  void setLaser(double openingAngle, const vpHomogeneousMatrix &cMl);

  /*!
    RANSAC inlier threshold, in pixels; default 2. Residuals are measured in the undistorted image:
    the geometric (Sampson) distance of a point to the conic in normalized coordinates, multiplied
    by the mean focal length (px + py) / 2. Without distortion this is the distance in pixels; with
    distortion it is the distance in the undistorted image, which differs from the distorted one by
    the local magnification of the distortion, 1 + kdu r^2 to first order.
  */
  void setRansacThreshold(double pixels);
  //! Maximum number of RANSAC samples; default 1000.
  void setRansacMaxTrials(int trials);
  //! Confidence of the adaptive stop (eq. 28); default 0.99.
  void setRansacProbability(double p);
  //! Seed of the RANSAC sampler; default 0.
  void setRansacSeed(unsigned int seed);
  /*!
    Smallest number of inliers a consensus needs (default 0: the method's minimal sample size);
    fewer gives STATUS_NO_CONSENSUS.
  */
  void setRansacNbInliersToReachConsensus(unsigned int n) { m_nbInliersToReachConsensus = n; }
  /*!
    Scale-adaptive final stage (default true). The RANSAC threshold separates gross outliers; then
    the trace is collected around the least-squares conic of the consensus at max(threshold, 3 sigma),
    sigma being the residual scale of the consensus (MAD, pixels), repeatedly while it grows, and the
    final fit (setFinalFit()) runs on that trace. Unlike a fixed threshold around the model, this keeps
    the whole trace when the calibration is imperfect. false: the RANSAC inliers and a plain
    least-squares final fit.
  */
  void setScaleAdaptive(bool enable) { m_scaleAdaptive = enable; }
  /*!
    Smallest arc of the trace, in radians around the fitted ellipse (its centre, in the frame where it
    is a circle), a consensus must cover (default pi/2; 0 disables the test): a short arc leaves the
    tilt weakly constrained. Fewer gives STATUS_SHORT_ARC.
    \exception vpLaserConicException::badValueError outside [0, 2 pi].
  */
  void setArcCoverageThreshold(double radians);
  //! Final fit on the trace (see vpLaserConicFinalFit); default FINAL_FIT_DEFAULT.
  void setFinalFit(vpLaserConicFinalFit fit) { m_finalFit = fit; }
  /*!
    Compute the covariance of the estimate (default false): getCovarianceMatrix() and
    getPlaneCovarianceMatrix(), first order, from the Jacobian of the final fit's residuals and their
    scale (RMS residual with the fit's degrees of freedom removed).
  */
  void setCovarianceComputation(bool enable) { m_computeCovariance = enable; }

  /*!
    Refit the best model on its inliers (default true), during the RANSAC loop (kept when it scores
    better) and, without the scale-adaptive stage (setScaleAdaptive(false)), after it (kept unless
    it loses more than a tenth of the inliers; refitted again, a few rounds at most, while it gathers
    more inliers): PP5 and PP3 refit a least-squares ellipse,
    GP3 refines the plane geometrically (refinePlane(), 3 degrees of freedom, Sampson distances to
    the predicted trace; inside the loop on at most 64 evenly spread inliers, again on the consensus
    set of a refit that gathers more inliers, 3 refits at most).
  */
  void setLocalOptimisation(bool enable);

  /*!
    Estimates the ground plane from image points (pixels) with the given method.
    \param points : image points (pixels) of the laser trace; every method but PLANE_PAIR rejects outliers.
    \param method : PLANE_PAIR, PP5, PP3 or GP3.
    \param cPlane : the ground plane in the camera frame, unit normal pointing from the plane towards the camera.
    \return false, with getStatus() telling why, when no plane was found; cPlane is then untouched.
    The reasons: all points collinear; the least-squares conic is not an ellipse; no consensus (no
    hypothesis with enough inliers); a trace covering too short an arc (setArcCoverageThreshold());
    the camera centre inside the laser cone, where no
    epipolar tangent exists (PP3 only); no plane of the plane pair has both optical centres on its side;
    the plane is behind the system (the inliers' rays do not meet it ahead of the camera on the lit
    nappe of the laser cone).
    \exception vpLaserConicException when the camera or laser is unset, too few points are given for
    the method, or a point is not finite.
  */
  bool computePlane(const std::vector<vpImagePoint> &points, vpLaserConicMethod method, vpPlane &cPlane);

  //! Altitude of the camera centre over the last plane, in metres.
  double getAltitude() const { return m_altitude; }
  //! Roll of the last estimate, in radians (see the class convention).
  double getRoll() const { return m_roll; }
  //! Pitch of the last estimate, in radians (see the class convention).
  double getPitch() const { return m_pitch; }
  //! Indices of the inliers (the points of the trace) of the last estimate (all points for PLANE_PAIR).
  std::vector<unsigned int> getRansacInlierIndex() const { return m_inliers; }
  //! The inlier points of the last estimate (pixels, as given).
  std::vector<vpImagePoint> getRansacInliers() const;
  //! Number of inliers of the last estimate.
  unsigned int getRansacNbInliers() const { return static_cast<unsigned int>(m_inliers.size()); }
  //! \deprecated Use getRansacInlierIndex().
  std::vector<unsigned int> getInliers() const { return m_inliers; }
  //! Number of RANSAC samples drawn by the last estimate.
  int getRansacTrials() const { return m_trials; }

  /*!
    Covariance (3x3) of (altitude [m], roll [rad], pitch [rad]) of the last estimate, in that order,
    computed with setCovarianceComputation(true), as vpPoseGravity::getCovarianceMatrix(). First order:
    sigma^2 (J^T J)^-1 of the final fit (3 plane parameters for a constrained fit; for a free fit the
    covariance of the 5 conic parameters propagated through the plane pair), sigma^2 the residual
    variance of the fit. NaN entries when it cannot be computed (e.g. a plane pair without a derivative
    at the estimate).
    \exception vpLaserConicException::notComputedError when the last estimate computed no covariance
    (not requested, or computePlane() failed).
  */
  vpMatrix getCovarianceMatrix() const;
  /*! Covariance (4x4) of the plane (a, b, c, d) of the last estimate (unit normal), as getCovarianceMatrix().
      \exception vpLaserConicException::notComputedError as getCovarianceMatrix(). */
  vpMatrix getPlaneCovarianceMatrix() const;

  /*!
    Calibration-health figure of the last estimate: RMS residual (pixels) of the constrained fit (the
    trace a plane predicts, 3 DOF) over that of a free conic fit (5 DOF) on the same inliers. Both are
    the noise level, and the ratio near 1, when the rig is well calibrated; a calibration error leaves
    the free fit at the noise level but not the constrained one (e.g. 0.5 px noise: ratio ~1.0 exact,
    several with intrinsics off by 5 px). NaN when no constrained fit could be made.
  */
  double getCalibrationHealth() const;
  //! RMS residual (pixels) of the constrained fit on the inliers of the last estimate.
  double getConstrainedRms() const { return m_rmsConstrained; }
  //! RMS residual (pixels) of the free conic fit on the inliers of the last estimate.
  double getFreeRms() const { return m_rmsFree; }
  //! Residual scale (pixels, MAD) of the free conic fit on the trace of the last estimate.
  double getResidualScale() const { return m_sigma; }
  //! Arc of the trace covered by the inliers of the last estimate (radians around the ellipse).
  double getArcCoverage() const { return m_coverage; }
  //! True when the last plane comes from the constrained fit (see vpLaserConicFinalFit).
  bool isConstrainedFit() const { return m_constrainedChosen; }
  /*! Image conic (pixel coordinates, x^T C x = 0 with x = (u, v, 1)) of the last estimate, for display:
      the fitted ellipse for PLANE_PAIR, PP5 and PP3, the image of the trace on the estimated plane for GP3.
      With a distorted camera it is the conic in the undistorted pixel image (x = K x_n). */
  vpMatrix getImageConic() const { return m_conic; }
  //! Outcome of the last computePlane().
  vpLaserConicStatus getStatus() const { return m_status; }
  //! What a status means, in words.
  static std::string getStatusMessage(vpLaserConicStatus status);
  /*!
    \deprecated Use getStatus() and getStatusMessage(). Why the last computePlane() returned false
    (the status message, with details; empty after a success).
  */
  std::string getFailureReason() const { return m_failure; }

  //! Camera parameters set with setCameraParameters().
  vpCameraParameters getCameraParameters() const { return m_cam; }

  /*!
    Displays an estimate with vpDisplay (the image must be shown in a window): the detected \e points
    (those given to computePlane()) as crosses, inliers green and outliers red, the fitted conic in
    yellow (through the camera model, distortion included) and an altitude / roll / pitch caption
    (the status message when computePlane() failed). Call vpDisplay::flush() afterwards.
  */
  static void display(const vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                      const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  //! display() on a colour image.
  static void display(const vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                      const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  /*!
    Draws the same overlay as display() into the pixels of \e I with vpImageDraw (no window needed:
    headless overlays, files). In a gray image inliers, conic and caption are white and outliers gray.
  */
  static void draw(vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                   const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  //! draw() on a colour image (inliers green, outliers red, conic yellow).
  static void draw(vpImage<vpRGBa> &I, const vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points,
                   unsigned int thickness = 1);
  /*!
    Draws a trace without an estimator (e.g. results kept from several estimates): the \e points as
    crosses, those of \e inlierIndex green and the others red, and \e imageConic (3x3, the undistorted
    pixel image of \e cam, as getImageConic() gives it; empty for none) in yellow through the camera
    model, so that it lies on the distorted trace. Any conic is drawn: an ellipse, or the part near the
    image of a hyperbola or parabola (the trace with the horizon in view). No caption.
  */
  static void draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                   const vpCameraParameters &cam, unsigned int thickness = 1);
  //! The trace draw() above on a gray image: inliers and conic white, outliers gray.
  static void draw(vpImage<unsigned char> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                   const vpCameraParameters &cam, unsigned int thickness = 1);

  /*! Altitude, roll and pitch of a plane given in the camera frame (normal towards the camera).
      \exception vpLaserConicException::badValueError on a zero normal. */
  static void computeAltitudeRollPitch(const vpPlane &cPlane, double &altitude, double &roll, double &pitch);

private:
  vpCameraParameters m_cam;
  bool m_hasCam, m_hasLaser;
  double m_openingAngle;
  vpHomogeneousMatrix m_cMl;
  double m_threshold;
  int m_maxTrials;
  double m_probability;
  unsigned int m_seed;
  bool m_localOptimisation;
  double m_altitude, m_roll, m_pitch;
  std::vector<unsigned int> m_inliers;
  int m_trials;
  vpMatrix m_conic;
  std::string m_failure;
  vpLaserConicStatus m_status;
  unsigned int m_nbInliersToReachConsensus;
  bool m_scaleAdaptive;
  double m_minCoverage;
  vpLaserConicFinalFit m_finalFit;
  bool m_computeCovariance;
  vpMatrix m_covariance, m_planeCovariance;
  double m_rmsConstrained, m_rmsFree, m_sigma, m_coverage;
  bool m_constrainedChosen;
  std::vector<vpImagePoint> m_points;

  //! Records a failure (status and message with \e details) and returns false.
  bool fail(vpLaserConicStatus status, const std::string &details = std::string());
  //! The exceptions of computePlane(): estimator not configured, unknown method, too few points.
  void checkInput(const std::vector<vpImagePoint> &points, vpLaserConicMethod method) const;
  //! Clears the previous estimate; \e points become those of the new one.
  void resetEstimate(const std::vector<vpImagePoint> &points);
  //! RANSAC settings of the estimator, the threshold converted to normalized units with \e focal (pixels).
  vpRansacOptions ransacOptions(double focal) const;
  //! Settings of the final fit (laser_robust_fit.h) of \e method.
  vpLaserRobustFit::Settings finalFitSettings(vpLaserConicMethod method, double focal) const;
  //! Keeps a successful final fit: plane, attitude, inliers, fit statistics, covariances, pixel conic.
  void storeEstimate(const vpLaserRobustFit::Result &result, vpPlane &cPlane);
};

#endif
