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
    least one frame (setKnownAltitude(); a second length determines the axis far better, see below) or the whole apex (setApexHeld()).
    An error of the given length is an error of the same ratio on every altitude measured afterwards (a ruler off by 10 % gives altitudes off by 10 %; roll, pitch and
    the axis are unaffected).
  - \b Opening angle, and the axis tilt towards the apex: the cone's tangent planes through the camera centre
    O contain the line from O to the apex; their images are the two lines from the image of the apex tangent
    to every trace (Sec. 5.2), whatever the plane. They are the only constraint the cone puts on a trace:
    the conics tangent to two lines are a 3-parameter set, the planes too, so every such conic is the trace
    on some plane. Hence the images determine 4 numbers of the cone (the apex direction, and the two angles
    psi0 of the tangent planes about the O-apex line) out of its 5 scale-free ones. The fifth is a
    one-parameter \b family of cones with the same apex and the same tangent planes, each explaining every
    image exactly with its own planes: with phi the angle of the axis to the O-apex line, the axis turns in
    the plane of that line and the axis (towards or away from the apex) as the full angle A changes, with
    \f$ \sin(A/2) = \sin\phi \cos\psi_0 \f$, i.e. \f$ d\phi = \tan\phi \, dA / (2 \tan(A/2)) \f$.
    The axis component out of that plane and the apex direction are determined with any angle.
    testLaserConicSelfCalibration (WrongHeldAngleIsExplainedByTheConeFamily) checks it: noise-free frames,
    the angle held 0.05 degree too small, fit to 3e-13 px by the predicted member, axis turned 0.79 degree
    (phi = 95.5 degrees for its rig: 17 times the angle error), altitudes 15 % off; the normal matrix with the
    angle free has condition number 3e15. So:
    - with \b one length (the apex distance, the held apex or one known altitude) the angle must be \b held
      (setLaser(): a chessboard calibration's value). Only the held value breaks the family then, through
      \f$ dA/d\phi = 2 \cos\phi \cos\psi_0 / \cos(A/2) \f$, which vanishes for an axis perpendicular to
      the O-apex line (phi = 90 degrees): the axis tilt towards the apex is the weakest direction, its
      standard deviation is \f$ |\tan\phi| \tan\psi_0 \f$ times that of the tangent-plane angles
      (34 for the rig of the tests), and an error of the held angle turns the axis by the factor above;
    - with \b two lengths (known altitudes of two frames at different heights, or the apex distance or held
      apex and one known altitude), the family and the scale are both fixed (the family's altitude change
      is not a scaling): the axis is known 10-30 times better and the angle can be estimated
      (setOpeningAngleEstimation(true); otherwise compute() refuses with STATUS_DEGENERATE_FRAMES).
  - \b Attitudes: the frames must be tilted relative to the ground in two directions (roll and pitch);
    altitude differences help too. Frames all at one attitude and nearly one altitude (a hover) do not
    determine the cone. compute() evaluates the covariance of the laser parameters and refuses with
    STATUS_DEGENERATE_FRAMES when the axis would be known worse than setMaxAngularStdDeviation() (the apex
    direction worse than twice it); getStatusDetails() then gives the spread of the frames' attitudes and
    the spread needed (the standard deviations scale as the inverse of the spread).
  - \b Accuracy (testLaserConicSelfCalibration, DISABLED_ProtocolStudy for the table of the tutorial: 34
    degree laser 10 cm beside a 1000 px camera with barrel distortion, roll and pitch uniform in +-15
    degrees at 0.8-1.3 m, 1000 points per frame, 0.5 px noise). An axis error \f$ \delta \f$ along the
    family moves a triangulated altitude by about \f$ h^2 \delta / b \f$ (b the baseline), less the part
    a known altitude absorbs. The covariance (getCovarianceMatrix()) propagated through GP3 predicts the
    altitude error GP3 makes afterwards to within about 20 %:
    | frames and lengths | axis std | GP3 altitude RMS / true laser's |
    |---|---:|---:|
    | 20, one known altitude (30 flights) | 0.076 deg (0.1 deg met in 24 of 30) | 5.8 (predicted 4.7) |
    | 20, ruler | 0.074 deg | 23 |
    | 20 at 0.4-2.5 m, one known altitude | 0.023 deg | 3.0 |
    | 100 / 200 / 500 (all used), one known altitude | 0.034 / 0.024 / 0.015 deg | 2.2 / 2.3 / 1.4 |
    | 40 chosen by information among 500 | 0.034 deg | 3.1 |
    | 20, \b two known altitudes (0.5 m apart) | 0.006 deg | \b 1.09 |
    | 20, ruler and one known altitude | 0.002 deg | 1.09 |
    With one length the 1.2x of GP3 with the true laser needs about 1300-1400 frames of 1000 points (the
    calibration part falls as 1 / sqrt(frames)); with two lengths 20 frames suffice. Roll and pitch after
    self-calibration are within 1.0-1.4 times those of the true laser in every case.
    With the apex held at a trusted previous calibration (setApexHeld(), a knocked mount), 40 frames of 300
    points give the axis to 0.014 degree. The same frames used as chessboard views (planes known,
    vpLaserConicCalibration) give the axis to 0.007 degree and estimate the angle: a chessboard calibration
    stays the reference; the self-calibration repairs a calibration in the field and tells when it is needed
    (vpLaserConicDriftMonitor).

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
     the result and the covariance;
  -# when that ends at the iteration limit, degenerate or with too many outliers, the whole is run once more
     from the initial laser's axis tilted on a grid (up to 12 degrees in steps of 4, about both axes of the laser
     frame), the tilt under which GP-3 explains the most points of 10 frames, and kept when it succeeds: a mount
     knocked by 8 or 12 degrees otherwise started the joint problem in another valley.

  The previous calibration is never replaced by a failed one: compute() writes its outputs only on success.

  \code
  vpLaserConicSelfCalibration selfcal;
  selfcal.setCameraParameters(cam);                    // with distortion if the camera has it
  selfcal.setLaser(vpMath::rad(34), cMlPrevious);      // initial guess: previous calibration (knocked by
                                                       // degrees: its planes are taken unchecked) or a drawing
  selfcal.setApexDistance(0.1);                        // a length: ruler, or the previous baseline
  for (const std::vector<vpImagePoint> &trace : traces) // laser points of ordinary frames of the ground
    selfcal.addFrame(trace);
  selfcal.setKnownAltitude(0, 0.312);                  // a second length: the altitude of frame 0 (e.g. landed)
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
    \exception vpLaserConicException::badCameraError as vpLaserConicPose::setCameraParameters(): on
    non-finite parameters (distortion coefficients included), non-positive focal lengths or a projection model
    other than the two perspective ones.
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
    always used when it has a plane (one given, or GP-3's with the initial laser); left out, its length goes
    with it, and compute() refuses (STATUS_DEGENERATE_FRAMES, "no length") when no other length is left.
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
    Estimate the opening angle too (default false: held at setLaser()'s value). Only two lengths determine
    it: known altitudes of two frames at different heights, or the apex distance (or held apex) and one known
    altitude (see the class description); with fewer compute() refuses with STATUS_DEGENERATE_FRAMES.
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
    \exception vpLaserConicException::badPointError on a point not finite or beyond 1e6 px (at 1e200 px the
    residuals overflowed and such points counted as perfect inliers), notEnoughPointError with fewer
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
    frames were refused as degenerate: huge when they nearly fix every parameter, NaN when they leave one free
    (the normal matrix singular; getAxisStdDeviation() is then infinite).
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
    the jointly fitted plane for the frames used; for the others, after a success, the plane GP-3 finds with the
    calibrated laser (zero when it finds none), after a failure the initial one (zero when none).
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
