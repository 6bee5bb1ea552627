/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicSelfCalibration.h
  \brief Laser/camera calibration from ordinary frames of the ground (no chessboard): one plane per
  frame and the shared laser cone, fitted jointly to the traces.
*/
#ifndef VP_LASER_CONIC_SELF_CALIBRATION_H
#define VP_LASER_CONIC_SELF_CALIBRATION_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPlane.h>
#include <visp3/laser_conic/vpLaserConicException.h>

namespace vpLaserSelfCal
{
struct StepsOutcome;
}

/*!
  \ingroup group_laser_conic
  \brief Self-calibration of the laser cone (axis, apex, optionally opening angle) from the laser
  traces of frames of an unknown ground plane, taken at different attitudes.

  Every frame shows the trace of the cone on the ground; its image is a conic (5 numbers) of a plane
  (3 unknowns). The estimator fits one plane per frame (roll, pitch, altitude) and the laser shared by
  all the frames, minimising the Sampson distances (pixels) of the trace points to the conics they
  predict, as vpLaserConicCalibration does with chessboard views (Sec. 6 of Boutteau et al., JMIV 2018),
  but with the planes unknown. Conventions of vpLaserConicPose: laser frame l with the apex at its
  origin and the cone axis along +Z, pose cMl, \b full opening angle, pixels converted with
  vpPixelMeterConversion (distortion included).

  <b>What the images determine.</b>
  - \b Scale: scaling the scene about the camera centre (apex and ground together) leaves every image
    unchanged: the apex distance is never seen. One length must be given: the apex distance
    (setApexDistance(): a ruler, or the baseline of the previous calibration), the altitude of at
    least one frame (setKnownAltitude(): the better one, see Accuracy) or the whole apex (setApexHeld()).
    An error of the given length is an error of the same ratio on every altitude measured afterwards (a ruler off by 10 % gives altitudes off by 10 %; roll, pitch and
    the axis are unaffected).
  - \b Opening angle: the only constraint the cone puts on the image of a trace is its tangency to
    the two epipolar lines (the lines through the image of the apex tangent to every trace, Sec. 5.2):
    every conic tangent to them is the trace of the cone on some plane. Hence the images determine these
    two lines (4 numbers: the apex direction and two angles) and nothing more: the cones with the same apex
    whose tangent planes through the camera centre are the same (a one-parameter family: wider cones with
    their axis turned accordingly) explain the images equally well, each with its own planes. The opening
    angle is therefore \b held at the given value (the manufacturer's or a chessboard calibration's), and
    the axis is determined with it. Estimating it (setOpeningAngleEstimation(true)) needs altitudes of
    frames at different attitudes (setKnownAltitude() on several frames: 5 of 20 in the tests give it to
    0.007 degree); otherwise compute() refuses with STATUS_DEGENERATE_FRAMES and says so. A wrong held
    angle turns the recovered axis (the tangent planes are kept) and biases the altitudes: take it from the
    previous calibration.
  - \b Attitudes: the frames must be tilted relative to the ground in two directions (roll and pitch);
    altitude differences help too. Frames all at one attitude and nearly one altitude (a hover) do not
    determine the cone. compute() evaluates the covariance of the laser parameters and refuses with
    STATUS_DEGENERATE_FRAMES when the axis would be known worse than setMaxAngularStdDeviation() (the apex
    direction worse than twice it); getStatusDetails() then gives the spread of the frames' attitudes and
    the spread needed (the standard deviations scale as the inverse of the spread).
  - \b Accuracy: the weakest combination is a tilt of the axis towards the apex traded against the
    altitudes of all the planes; it is what limits the altitudes measured afterwards (an axis error
    \f$ \delta \f$ moves a triangulated altitude by about \f$ h^2 \delta / b \f$, b the baseline).
    Measured (testLaserConicSelfCalibration: 34 degree laser 10 cm beside a 1000 px camera with barrel
    distortion, 20 frames with roll and pitch uniform in +-15 degrees at 0.8-1.3 m, 1000 points per
    frame, 0.5 px noise): axis and apex direction standard deviations about 0.08 and 0.09 degree (errors
    0.05-0.17 and 0.08-0.16 degree over 3 flights); GP3 on new frames afterwards: roll/pitch RMS 1.1-1.4
    times that of the true calibration, altitude RMS 2-7 times (1.6-4.8 mm against 0.7 mm at 1 m) with one
    known altitude as the scale, 23 times (17 mm) with the apex distance as the scale (with 300 points
    per frame, altitudes biased by up to 6 %: prefer a known altitude, or setApexHeld() after a knock).
    With the apex held at a trusted previous calibration (setApexHeld(), a knocked mount), 40 frames of 300 points give the
    axis to 0.014 degree. The same frames used as chessboard views (planes known, vpLaserConicCalibration)
    give the axis to 0.007 degree: a chessboard calibration stays the reference; the self-calibration
    repairs a calibration in the field and tells when it is needed (vpLaserConicDriftMonitor).

  <b>Steps of compute().</b>
  -# each frame's plane is estimated with vpLaserConicPose (GP3, RANSAC, the initial laser) unless the
     frame came with one; a frame without a plane is left out (getFrameUsed());
  -# when more than setMaxFrames() frames are usable, frames are chosen greedily by the information
     they add on the laser parameters (D-optimal: each pick maximises the determinant of the summed
     information, the planes eliminated): hundreds of frames of one flight cost little more than the
     chosen ones;
  -# the joint Levenberg-Marquardt problem (Ceres, DENSE_SCHUR: the planes are eliminated) is solved
     under Cauchy weights at the MAD scale of the residuals (rounds of reweighting); points farther
     than 3 scales from their conic are outliers; a final plain least-squares fit on the inliers gives
     the result and the covariance.

  The previous calibration is never replaced by a failed one: compute() writes its outputs only on success.

  \code
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(cam);                    // with distortion if the camera has it
  selfcal.setLaser(vpMath::rad(34), cMlPrevious);      // initial guess: previous calibration or a drawing
  selfcal.setApexDistance(0.1);                        // the one length: ruler, or the previous baseline
  for (const std::vector<vpImagePoint> &trace : traces) // laser points of ordinary frames of the ground
    selfcal.addFrame(trace);
  vpHomogeneousMatrix cMl;
  double openingAngle;
  if (selfcal.compute(cMl, openingAngle))
    estimator.setLaser(openingAngle, cMl);
  else
    std::cerr << selfcal.getStatusMessage(selfcal.getStatus()) << ": " << selfcal.getStatusDetails() << std::endl;
  \endcode
*/
class VISP_EXPORT vpLaserConicSelfCalibration
{
public:
  //! Outcome of the last compute().
  typedef enum {
    STATUS_NOT_COMPUTED,      //!< compute() not called yet, or frames changed since
    STATUS_OK,                //!< calibrated; the covariance is available
    STATUS_NOT_ENOUGH_FRAMES, //!< fewer than 3 frames with a plane (getFrameUsed())
    STATUS_DEGENERATE_FRAMES, //!< the frames do not determine the laser: too little attitude variety, or the
                              //!< opening angle estimated without the altitudes that determine it
    STATUS_NO_CONVERGENCE,    //!< Levenberg-Marquardt stopped at the iteration limit
    STATUS_SOLVER_FAILURE,    //!< Ceres failed or the result is not finite
    STATUS_TOO_MANY_OUTLIERS, //!< fewer than half the points of the chosen frames are inliers
    STATUS_LARGE_RESIDUALS    //!< the inliers' RMS exceeds setMaxRmsPixels(): the model does not fit
  } vpSelfCalibrationStatus;

  //! Self-calibration with no camera, no laser, no scale constraint and no frame.
  vpLaserConicSelfCalibration();

  /*!
    Camera intrinsics, with or without distortion (as vpLaserConicPose::setCameraParameters()).
    \exception vpLaserConicException::badCameraError on non-finite or non-positive focal lengths.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    Initial laser: full opening angle (rad, the held value unless setOpeningAngleEstimation(true)) and
    pose cMl (apex, axis = third column). Its apex distance is the starting value when the scale comes
    from setKnownAltitude().
    \exception vpLaserConicException::badLaserError on an angle outside (0, pi), a pose that is not a finite
    rigid transformation or an apex at the camera centre.
  */
  void setLaser(double openingAngle, const vpHomogeneousMatrix &cMl);
  /*!
    The scale constraint of a measured apex distance |apex| (metres): a ruler, or the baseline of the
    previous calibration. 0 removes it.
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setApexDistance(double metres);
  /*!
    The scale constraint of a known altitude (metres, camera centre above the ground) of frame \e frame
    (index returned by addFrame()); may be given for several frames. A frame with a known altitude is
    always used.
    \exception vpLaserConicException::badValueError on an unknown frame or an altitude not positive and finite.
  */
  void setKnownAltitude(unsigned int frame, double altitude);
  /*!
    Hold the apex at the initial laser's (setLaser()) and estimate the axis only (default false): for a
    mount that turned about the apex (a knock on a rigid bracket), when the previous calibration's apex
    is trusted. The apex position is then the scale constraint (no other is needed), and the axis is
    determined far better than with the apex free (see the class description).
  */
  void setApexHeld(bool hold) { m_holdApex = hold; }
  /*!
    Estimate the opening angle too (default false: held at setLaser()'s value). Only altitudes of
    frames at different attitudes determine it (see the class description).
  */
  void setOpeningAngleEstimation(bool estimate) { m_estimateAngle = estimate; }
  /*!
    Largest number of frames entering the joint problem (default 40); more usable frames are chosen by
    information. \exception vpLaserConicException::badValueError below 3.
  */
  void setMaxFrames(unsigned int n);
  /*!
    Observability limit: compute() refuses (STATUS_DEGENERATE_FRAMES) when the standard deviation of the
    cone axis direction, or of the apex direction, exceeds it (rad, default 0.1 degree).
    \exception vpLaserConicException::badValueError when not positive and finite.
  */
  void setMaxAngularStdDeviation(double radians);
  /*!
    Largest accepted RMS residual of the inliers, pixels (default 3).
    \exception vpLaserConicException::badValueError when not positive and finite.
  */
  void setMaxRmsPixels(double pixels);

  /*!
    Adds a frame: the laser trace points (pixels) detected in it, outliers allowed.
    \return the frame index (for setKnownAltitude()).
    \exception vpLaserConicException::badPointError on a non-finite point, notEnoughPointError with fewer
    than 5 points (a frame without laser is not a frame of the calibration: leave it out).
  */
  unsigned int addFrame(const std::vector<vpImagePoint> &points);
  /*!
    Adds a frame with a rough ground plane (camera frame, normal towards the camera, d > 0), e.g. the
    estimate of the frame by vpLaserConicPose; no plane is searched for it. Exceptions of addFrame(), and
    badValueError on a plane that is not a finite ground plane in front of the camera.
  */
  unsigned int addFrame(const std::vector<vpImagePoint> &points, const vpPlane &roughPlane);
  //! Removes every frame and known altitude.
  void clearFrames();
  //! Number of frames added.
  unsigned int getNbFrames() const { return static_cast<unsigned int>(m_frames.size()); }

  /*!
    Runs the self-calibration (see the class description).
    \param cMl : on success the calibrated laser pose (rotation Rx(alpha) Ry(beta), translation the apex);
    untouched on failure.
    \param openingAngle : on success the full opening angle (the held one unless estimated); untouched on failure.
    \return true when getStatus() is STATUS_OK.
    \exception vpLaserConicException when the camera or laser is unset, no frame was added, or no scale
    constraint was given (badValueError: the apex distance is not observable from images).
  */
  bool compute(vpHomogeneousMatrix &cMl, double &openingAngle);

  //! Status of the last compute().
  vpSelfCalibrationStatus getStatus() const { return m_status; }
  //! One-line explanation of a status.
  static std::string getStatusMessage(vpSelfCalibrationStatus status);
  //! Numbers behind the last status (attitude spread, standard deviations, condition, Ceres message).
  std::string getStatusDetails() const { return m_details; }

  /*!
    Covariance (6x6) of (alpha, beta, apex x, y, z, A) of the last compute() (rad, metres), same order
    and units as vpLaserConicCalibration::getCovarianceMatrix(); rows of held quantities are zero (the
    apex distance with setApexDistance(), A unless estimated). First order, the residual variance
    RSS / (N - p) times the inverse of the normal matrix with the planes eliminated. Also computed when the
    frames were refused as degenerate (then possibly huge).
  */
  vpMatrix getCovarianceMatrix() const { return m_fig.covariance; }
  //! Square roots of the diagonal of getCovarianceMatrix().
  vpColVector getStdDeviations() const;
  //! Standard deviation (rad) of the direction of the cone axis (both components, RMS sum).
  double getAxisStdDeviation() const { return m_fig.axisStd; }
  //! Standard deviation (rad) of the direction of the apex seen from the camera centre.
  double getApexDirectionStdDeviation() const { return m_fig.apexDirStd; }
  /*!
    Spread of the attitudes (roll, pitch) of the frames used, rad: RMS deviation from their mean along
    the weakest (\e weakest) and strongest (\e strongest) direction.
  */
  void getAttitudeSpread(double &weakest, double &strongest) const
  {
    weakest = m_fig.spreadWeak;
    strongest = m_fig.spreadStrong;
  }
  //! RMS residual (pixels, undistorted image) of the inliers of the last compute().
  double getRmsPixels() const { return m_fig.rms; }
  //! Residual scale (pixels, MAD) of the last compute().
  double getResidualScale() const { return m_fig.sigma; }
  //! Points of the frames used, and inliers among them.
  unsigned int getNbPoints() const { return m_fig.nbPoints; }
  //! Inliers of the last compute() (within 3 residual scales).
  unsigned int getNbInliers() const { return m_fig.nbInliers; }
  //! For each frame added, true when it entered the joint problem of the last compute().
  std::vector<bool> getFrameUsed() const { return m_fig.used; }
  /*!
    Ground plane of each frame added (camera frame, normal towards the camera) after the last compute():
    the jointly fitted plane for the frames used, the initial one for the others (zero when none).
  */
  std::vector<vpPlane> getFramePlanes() const { return m_fig.planes; }
  //! Condition number of the laser normal matrix (parameters scaled to radians) of the last compute().
  double getConditionNumber() const { return m_fig.condition; }

private:
  //! What the last compute() measured (the getters read it), filled by the steps of the solve.
  struct Figures
  {
    vpMatrix covariance = vpMatrix(6, 6, 0.0);
    double axisStd = 0.0, apexDirStd = 0.0, spreadWeak = 0.0, spreadStrong = 0.0, rms = 0.0, sigma = 0.0,
           condition = 0.0;
    unsigned int nbPoints = 0, nbInliers = 0;
    std::vector<bool> used;
    std::vector<vpPlane> planes;
  };
  friend struct vpLaserSelfCal::StepsOutcome;

  struct FrameData
  {
    std::vector<vpImagePoint> points;
    bool hasPlane = false;
    vpPlane plane;
    double knownAltitude = 0.0; // 0: unknown
  };
  bool fail(vpSelfCalibrationStatus status, const std::string &details);
  void checkReady() const;
  bool solve(vpHomogeneousMatrix &cMl, double &openingAngle);

  vpCameraParameters m_cam;
  bool m_hasCam, m_hasLaser, m_estimateAngle, m_holdApex;
  double m_openingAngle, m_apexDistance, m_maxStd, m_maxRms;
  unsigned int m_maxFrames;
  vpHomogeneousMatrix m_cMl;
  std::vector<FrameData> m_frames;

  vpSelfCalibrationStatus m_status;
  std::string m_details;
  Figures m_fig;
};

#endif
