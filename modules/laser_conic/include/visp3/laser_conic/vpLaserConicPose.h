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
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPlane.h>
#include <visp3/laser_conic/vpLaserConicException.h>

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
    Refit the best model on its inliers (default true), during the RANSAC loop (kept when it scores
    better) and after it (kept unless it loses more than a tenth of the inliers; refitted again, a
    few rounds at most, while it gathers more inliers): PP5 and PP3 refit a least-squares ellipse,
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
    \return false, with getFailureReason() telling why, when no plane was found; cPlane is then untouched.
    The reasons: all points collinear; the least-squares conic is not an ellipse (PLANE_PAIR); no
    consensus (no hypothesis with enough inliers); the camera centre inside the laser cone, where no
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
  //! Indices of the inliers of the last estimate (all points for PLANE_PAIR).
  std::vector<unsigned int> getInliers() const { return m_inliers; }
  //! Number of RANSAC samples drawn by the last estimate.
  int getRansacTrials() const { return m_trials; }
  /*! Image conic (pixel coordinates, x^T C x = 0 with x = (u, v, 1)) of the last estimate, for display:
      the fitted ellipse for PLANE_PAIR, PP5 and PP3, the image of the trace on the estimated plane for GP3.
      With a distorted camera it is the conic in the undistorted pixel image (x = K x_n). */
  vpMatrix getImageConic() const { return m_conic; }
  //! Why the last computePlane() returned false (empty after a success).
  std::string getFailureReason() const { return m_failure; }

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
};

#endif
