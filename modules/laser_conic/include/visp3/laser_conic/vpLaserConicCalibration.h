/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicCalibration.h
  \brief Laser/camera calibration by bundle adjustment over (alpha, beta, v, gamma_i) (Sec. 6 of the paper).
*/
#ifndef VP_LASER_CONIC_CALIBRATION_H
#define VP_LASER_CONIC_CALIBRATION_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/laser_conic/vpLaserConicException.h>
#include <visp3/robust/vpRobustScale.h>

namespace vsp::laser_calibration
{
class ConeProblem;
}

/*!
  \ingroup group_laser_conic
  \brief Estimates the pose of the laser cone relative to the camera (and optionally its opening angle)
  from views of a planar grid.

  Each view gives the grid pose cMg (grid plane Z = 0, e.g. from vpLaserConicGridCalibration or vpPose on
  the grid corners) and the image points of the laser trace on the grid. The image points are converted
  to normalized coordinates with vpPixelMeterConversion (so the camera model may include ViSP's
  distortion) and back-projected onto the grid plane; the unknowns are the two angles (alpha about X,
  beta about Y) of the cone axis, the apex v, optionally the opening angle A, and one angle gamma_i per
  point on the cone; the XY distances on the grid planes between measured and predicted points, mapped
  to pixels by the Jacobian of the grid-to-image projection at each point (the image noise is isotropic
  in pixels, not on a far or oblique grid), are minimised with Ceres' Levenberg-Marquardt. The rotation
  about the cone axis is unobservable and returned as zero.

  Model (paper Sec. 6, eq. 58-65): the ray i of the cone has the direction
  \f$ \mathbf{D}'_i = R_x(\alpha) R_y(\beta) R_z(\gamma_i) (\sin\frac{A}{2}, 0, \cos\frac{A}{2})^T \f$ in the
  camera frame, from the apex \f$ \mathbf{v} \f$; mapped into the grid frame with
  \f$ {}^g\mathbf{M}_c = {}^c\mathbf{M}_g^{-1} \f$ and cut with the plane Z = 0 it predicts the grid XY of
  the point. The returned laser pose is \f$ {}^c\mathbf{M}_l = [R_x(\alpha) R_y(\beta) \mid \mathbf{v}] \f$.
  The cone axis is \f$ (\sin\beta, -\sin\alpha\cos\beta, \cos\alpha\cos\beta)^T \f$: the parameterisation
  is singular only for an axis perpendicular to the optical axis (beta = +-90 degrees).

  Stages of compute():
  -# the gamma_i alone, the cone fixed at the initial guess (every point starts on its closest ray);
  -# all the parameters under a robust loss (setRobustLoss(), Cauchy by default) whose scale shrinks from
     the initial residuals down to the noise level, so that laser points off the grid (on the
     background, on the grid's frame) lose their weight without stopping the convergence from a rough guess;
  -# points farther than 3 loss scales from the cone are dropped and a plain least-squares fit is run on
     the others; it gives the result, the RMS and the covariance.

  A Ceres run stopped by the iteration limit (NO_CONVERGENCE) is a failure, not a result. The covariance
  of (alpha, beta, v, A), with the gamma_i eliminated (Schur complement of the normal equations), gives
  the standard deviations and an observability check: when the normal equations, in parameters scaled to
  metres at the grid distance, are conditioned worse than setMaxConditionNumber(), or when all the grids
  lie in one plane (one grid shown several times, fronto-parallel views at one depth: normals within 2
  degrees and distances within 2 %), the view set cannot determine the cone and compute() refuses with
  STATUS_DEGENERATE_VIEWS rather than return a cone that fits the points but is wrong (one plane is cut
  by several cones along the same conic). The one-plane test runs on all the views, then again on those
  that keep more than half of their points as inliers after the robust stage. Fewer than 2 views give
  STATUS_NOT_ENOUGH_VIEWS. Tilted grids at one distance, or parallel grids at several distances, do
  determine the cone (opening angle included).
  A fit whose inliers' RMS exceeds setMaxRmsPixels() (cone fitted to mostly outliers, wrong camera model
  or grid poses) ends with STATUS_LARGE_RESIDUALS. The formal standard deviations ignore the errors of
  the grid poses; setViewJackknife(true) adds leave-one-view-out standard deviations that include them.

  \code
  vpLaserConicCalibration calib;
  calib.setCameraParameters(cam);              // may include distortion
  calib.setOpeningAngle(vpMath::rad(34));      // known, or the initial value when estimated:
  calib.setOpeningAngleEstimation(true);       // needs grids at several distances or tilts
  for (size_t j = 0; j < cMg.size(); ++j)
    calib.addView(cMg[j], laserPoints[j]);     // grid pose, laser points from vpLaserConicDetector
  vpHomogeneousMatrix cMl(0.1, 0, 0, 0, 0, 0); // rough measurement, used as the initial guess
  if (calib.compute(cMl))
    std::cout << calib.getRms() << " m, apex std " << calib.getStdDeviations().t() << std::endl;
  else
    std::cerr << vpLaserConicCalibration::getStatusMessage(calib.getStatus()) << std::endl;
  \endcode
*/
class VISP_EXPORT vpLaserConicCalibration
{
public:
  //! Outcome of the last compute() (or calibrate()).
  typedef enum {
    STATUS_NOT_COMPUTED,      //!< compute() not called yet, or views changed since
    STATUS_OK,                //!< calibrated; the covariance and standard deviations are available
    STATUS_NOT_ENOUGH_VIEWS,  //!< fewer than 2 views: one conic does not determine the cone reliably
    STATUS_DEGENERATE_VIEWS,  //!< the views do not determine the cone: all the grids in one plane, or
                              //!< ill-conditioned normal equations (see setMaxConditionNumber())
    STATUS_NO_CONVERGENCE,    //!< Levenberg-Marquardt stopped at the iteration limit
    STATUS_SOLVER_FAILURE,    //!< Ceres failed or the result is not finite
    STATUS_TOO_MANY_OUTLIERS, //!< fewer than half the points are within 3 loss scales of the cone
    STATUS_LARGE_RESIDUALS    //!< the inliers' RMS exceeds setMaxRmsPixels(): the cone does not fit the points
  } vpLaserConicCalibrationStatus;

  /*!
    Robust loss applied to the grid residuals in the second stage (see the class description): the
    project's one loss enum (::vpRobustLoss, visp3/robust/vpRobustScale.h) under its former name.
  */
  typedef vpRobustLoss vpLaserConicLoss;
  //! Plain least squares on all the points (no outlier rejection); vpRobustLoss::NONE.
  static constexpr vpRobustLoss LOSS_NONE = vpRobustLoss::NONE;
  //! Huber loss; vpRobustLoss::HUBER.
  static constexpr vpRobustLoss LOSS_HUBER = vpRobustLoss::HUBER;
  //! Cauchy loss (default): gross outliers get a vanishing weight; vpRobustLoss::CAUCHY.
  static constexpr vpRobustLoss LOSS_CAUCHY = vpRobustLoss::CAUCHY;

  //! Calibration with no camera, no opening angle, no initial guess and no view.
  vpLaserConicCalibration();

  /*!
    Camera intrinsics (used to back-project the laser points on the grids).
    \exception vpLaserConicException::badCameraError as vpLaserConicPose::setCameraParameters(): on
    non-finite parameters (distortion coefficients included), non-positive focal lengths or a projection model
    other than the two perspective ones.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    Full opening angle of the laser (rad), known from the manufacturer; the initial value when
    setOpeningAngleEstimation(true).
    \exception vpLaserConicException::badLaserError when it is outside [1e-3, pi - 1e-3] (the solver's bounds).
  */
  void setOpeningAngle(double openingAngle);
  /*!
    When true, compute() also estimates the opening angle, starting from setOpeningAngle(). An error of
    0.5 degree on a known angle moves the apex by centimetres while the RMS still looks plausible, so
    estimate it unless it is known better than the calibration would give it. It is observable only from
    grids at several distances from the laser (otherwise STATUS_DEGENERATE_VIEWS). Default false.
  */
  void setOpeningAngleEstimation(bool estimate) { m_estimateAngle = estimate; }
  /*!
    Initial guess of the laser pose in the camera frame; only the direction of its Z axis (the cone
    axis) and its translation (the apex) matter. Without it, compute() uses its argument.
    \exception vpLaserConicException::badLaserError when the pose is not a finite rigid transformation.
  */
  void setInitialGuess(const vpHomogeneousMatrix &cMl);
  /*!
    Robust loss of the second stage and its scale in pixels (about 1.5 times the standard deviation of
    the laser points across the trace). A scale of 0 (default) lets compute() take 1.5 times a robust
    (median) estimate of that standard deviation. Points farther than 3 scales from the fitted cone are
    outliers, excluded from the final fit.
    \exception vpLaserConicException::badValueError on a negative or non-finite scale.
  */
  void setRobustLoss(vpLaserConicLoss loss, double scale = 0.0);
  /*!
    Largest iteration count of each Levenberg-Marquardt run (default 200); a final run that reaches it
    ends with STATUS_NO_CONVERGENCE.
    \exception vpLaserConicException::badValueError when it is not positive.
  */
  void setMaxIterations(int maxIterations);
  /*!
    Largest accepted condition number of the normal equations of (alpha, beta, v[, A]) with the gamma_i
    eliminated, the angles scaled to metres at the mean grid distance (default 1e5). Over it, compute()
    ends with STATUS_DEGENERATE_VIEWS. Measured (test view sets, 0.5 px noise): 10 grids at 0.5-1.1 m
    tilted up to 25 degrees, about 120 (500 with the opening angle); 8 grids at one distance tilted by
    20 degrees, 600 (2500); 8 parallel grids at 0.5-1.1 m, 80 (260); 3 grids 3 degrees apart with the
    opening angle estimated, 2.5e5. Views of a single plane are refused before, whatever
    this number (the cone is then ambiguous, not merely ill-conditioned).
    \exception vpLaserConicException::badValueError when it is not greater than 1.
  */
  void setMaxConditionNumber(double maxCondition);
  /*!
    When true, compute() also gives getJackknifeStdDeviations(): the calibration is repeated without each
    view in turn (n more fits, started from the result). Default false.
  */
  void setViewJackknife(bool jackknife) { m_jackknife = jackknife; }
  /*!
    Largest accepted RMS residual of the inliers, in pixels (default 3): over it compute() ends with
    STATUS_LARGE_RESIDUALS. Laser detectors reach a fraction of a pixel; a larger RMS means that the cone
    was fitted to outliers (with more than half outliers the robust scale follows them), that the camera
    model or the grid poses are wrong.
    \exception vpLaserConicException::badValueError when not positive and finite.
  */
  void setMaxRmsPixels(double maxRms);
  /*!
    Adds one view: grid pose in the camera frame and the laser points seen on the grid (pixels).
    \exception vpLaserConicException when the pose is not a finite rigid transformation, a point is not
    finite (badPointError) or fewer than 5 points are given (notEnoughPointError).
  */
  void addView(const vpHomogeneousMatrix &cMg, const std::vector<vpImagePoint> &laserPoints);
  //! Removes all views.
  void clearViews();
  //! Number of views added.
  unsigned int getNbViews() const { return static_cast<unsigned int>(m_views.size()); }

  /*!
    Runs the calibration (see the class description).
    \param cMl : on input ignored unless no initial guess was set (then used as the guess); on success
    the calibrated laser pose (rotation Rx(alpha) Ry(beta), translation the apex); untouched on failure.
    \return true when getStatus() is STATUS_OK; otherwise getStatus() says why and getStatusMessage()
    explains it.
    \exception vpLaserConicException when the camera, opening angle or views are missing, the initial
    guess is not a finite rigid transformation, or a laser point does not back-project in front of the
    camera on its grid plane (invalid input rather than a failed calibration).
  */
  bool compute(vpHomogeneousMatrix &cMl);
  /*!
    Same as compute() but returns the RMS distance (metres) on the grid planes between measured and
    predicted points (inliers) and throws on any failure.
    \exception vpLaserConicException (badValueError, with the status message) when compute() fails, and
    the exceptions of compute().
  */
  double calibrate(vpHomogeneousMatrix &cMl);

  //! Status of the last compute().
  vpLaserConicCalibrationStatus getStatus() const { return m_status; }
  //! One-line explanation of a status.
  static std::string getStatusMessage(vpLaserConicCalibrationStatus status);
  //! Details of the last failure (numbers: condition number, iterations, Ceres message); empty on success.
  std::string getStatusDetails() const { return m_statusDetails; }

  //! RMS distance (metres) on the grid planes between measured and predicted inlier points, after compute().
  double getRms() const { return m_rms; }
  //! RMS distance (pixels) in the images between measured and predicted inlier points (first order), after compute().
  double getRmsPixels() const { return m_rmsPixels; }
  //! RMS error (metres) of the initial cone (after the first stage, which fits only the gamma_i), available
  //! after compute().
  double getInitialRms() const { return m_initialRms; }
  //! Full opening angle (rad): the estimate after compute() with setOpeningAngleEstimation(true), else the given one.
  double getOpeningAngle() const { return m_openingAngleEstimate; }
  //! Number of laser points in all views.
  unsigned int getNbPoints() const;
  //! Number of points kept by the final fit (within 3 loss scales of the cone).
  unsigned int getNbInliers() const { return m_nbInliers; }
  //! Loss scale (pixels) of the final robust stage (0 with LOSS_NONE).
  double getRobustScale() const { return m_lossScale; }
  /*!
    Condition number of the scaled normal equations of the last compute() (see setMaxConditionNumber()),
    available also when it ended with STATUS_DEGENERATE_VIEWS.
  */
  double getConditionNumber() const { return m_condition; }
  /*!
    Covariance matrix of the last compute() when it succeeded (NaN when it failed): 6x6, parameter order
    (alpha, beta, vx, vy, vz, A), units rad and metres; alpha and beta are the angles of the axis (see the class description), v the
    apex, A the full opening angle (its row and column are zero when it is not estimated). It is the
    inverse of the normal matrix with the gamma_i eliminated, times the residual variance
    RSS / (N - p) (RSS in pixels, N inlier points, p = 5 or 6 parameters).
  */
  vpMatrix getCovarianceMatrix() const { return m_covariance; }
  /*!
    Standard deviations: square roots of the diagonal of getCovarianceMatrix(), same order and units.
    They account for the noise of the laser points only, the grid poses taken as exact; with grid poses
    from real corners, the errors of the poses usually dominate: see getJackknifeStdDeviations().
  */
  vpColVector getStdDeviations() const;
  /*!
    Leave-one-view-out jackknife standard deviations (same order and units as getStdDeviations()),
    \f$ \sqrt{\frac{n-1}{n} \sum_k (\theta_{(k)} - \bar\theta)^2} \f$: they include every error that
    differs from view to view (grid pose, detection bias), with a relative uncertainty of about
    \f$ 1/\sqrt{2(n-1)} \f$. Available after a successful compute() with setViewJackknife(true) when every
    leave-one-out fit succeeded (hasJackknifeStdDeviations()), zeros otherwise.
  */
  vpColVector getJackknifeStdDeviations() const { return m_jackknifeStd; }
  //! True when getJackknifeStdDeviations() was computed by the last compute().
  bool hasJackknifeStdDeviations() const { return m_hasJackknifeStd; }
  //! Predicted trace points on each grid (grid coordinates X, Y) for the calibrated laser, for figures.
  std::vector<std::vector<std::pair<double, double> > > getPredictedGridPoints() const { return m_predicted; }
  //! Predicted trace points on each grid for the initial guess (after the first stage), for before/after figures.
  std::vector<std::vector<std::pair<double, double> > > getInitialPredictedGridPoints() const
  {
    return m_initialPredicted;
  }
  //! Measured trace points on each grid (grid coordinates X, Y), for figures.
  std::vector<std::vector<std::pair<double, double> > > getMeasuredGridPoints() const { return m_measured; }
  //! For each view and point, true when the point is an inlier of the last compute().
  std::vector<std::vector<bool> > getInlierFlags() const { return m_inlier; }

private:
  //! One view: grid pose and laser image points.
  struct View
  {
    vpHomogeneousMatrix cMg;
    std::vector<vpImagePoint> points;
  };
  void checkReady(const vpHomogeneousMatrix &guess) const;
  void resetResults();
  void backProject();
  //! STATUS_NOT_ENOUGH_VIEWS or STATUS_DEGENERATE_VIEWS (one grid plane) as a failure, else true.
  bool checkViewSet(const std::vector<vpHomogeneousMatrix> &cMg);
  //! The three stages of compute() (see the class description) and their failures.
  bool fitCone(vsp::laser_calibration::ConeProblem &cone);
  //! Condition number (STATUS_DEGENERATE_VIEWS beyond the limit), RMS and covariance of the fitted cone.
  bool computeCovariance(vsp::laser_calibration::ConeProblem &cone);
  //! STATUS_DEGENERATE_VIEWS unless the views keeping more than half of their points show two grid planes.
  bool checkInlierViews(const vsp::laser_calibration::ConeProblem &cone, const std::vector<vpHomogeneousMatrix> &cMg);
  //! Whether most laser points of the grids (posed by \e cMg) lie behind the laser \e cMl: its other nappe.
  bool gridsBehind(const vpHomogeneousMatrix &cMl, const std::vector<vpHomogeneousMatrix> &cMg);
  //! The fitted cone's covariance, residual check and results, into \e cMl on success.
  bool finishCone(vsp::laser_calibration::ConeProblem &cone, vpHomogeneousMatrix &cMl);
  void computeJackknife(const vpHomogeneousMatrix &cMl);
  bool fail(vpLaserConicCalibrationStatus status, const std::string &details);

  vpCameraParameters m_cam;
  bool m_hasCam, m_hasGuess, m_estimateAngle, m_jackknife;
  double m_openingAngle;
  vpHomogeneousMatrix m_guess;
  vpLaserConicLoss m_loss;
  double m_userLossScale;
  int m_maxIterations;
  double m_maxCondition, m_maxRmsPixels;
  std::vector<View> m_views;

  vpLaserConicCalibrationStatus m_status;
  std::string m_statusDetails;
  double m_rms, m_rmsPixels, m_initialRms, m_openingAngleEstimate, m_lossScale, m_condition;
  unsigned int m_nbInliers;
  vpMatrix m_covariance;
  bool m_hasJackknifeStd;
  vpColVector m_jackknifeStd;
  std::vector<std::vector<std::pair<double, double> > > m_predicted, m_initialPredicted, m_measured;
  std::vector<std::vector<bool> > m_inlier;
};

#endif
