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

#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>

/*!
  \ingroup group_laser_conic
  \brief Estimates the pose of the laser cone relative to the camera from views of a planar grid.

  Each view gives the grid pose cMg (grid plane Z = 0, e.g. from vpPose on the grid corners) and
  the image points of the laser trace on the grid. The image points are back-projected onto the
  grid plane; the unknowns are the two angles (alpha about X, beta about Y) of the cone axis, the apex
  v and one angle gamma_i per point on the cone; the sum of squared XY distances on the grid plane is
  minimised with Ceres' Levenberg-Marquardt, first over the gamma_i alone, then over everything.
  The rotation about the cone axis is unobservable and returned as zero.

  Model (paper Sec. 6, eq. 58-65): the ray i of the cone has the direction
  \f$ \mathbf{D}'_i = R_x(\alpha) R_y(\beta) R_z(\gamma_i) (\sin\frac{A}{2}, 0, \cos\frac{A}{2})^T \f$ in the
  camera frame (A: full opening angle), from the apex \f$ \mathbf{v} \f$; mapped into the grid frame with
  \f$ {}^g\mathbf{M}_c = {}^c\mathbf{M}_g^{-1} \f$ and cut with the plane Z = 0 it predicts the grid XY of
  the point. The returned laser pose is \f$ {}^c\mathbf{M}_l = [R_x(\alpha) R_y(\beta) \mid \mathbf{v}] \f$.
  The cone axis is \f$ (\sin\beta, -\sin\alpha\cos\beta, \cos\alpha\cos\beta)^T \f$: the parameterisation
  is singular only for an axis perpendicular to the optical axis (beta = +-90 degrees).

  \code
  vpLaserConicCalibration calib;
  calib.setCameraParameters(cam);
  calib.setOpeningAngle(vpMath::rad(34));
  for (size_t j = 0; j < cMg.size(); ++j)
    calib.addView(cMg[j], laserPoints[j]);     // grid pose from vpPose, laser points from vpLaserConicDetector
  vpHomogeneousMatrix cMl(0.1, 0, 0, 0, 0, 0); // rough measurement, used as the initial guess
  double rms = calib.calibrate(cMl);           // metres
  \endcode
*/
class VISP_EXPORT vpLaserConicCalibration
{
public:
  //! Calibration with no camera, no opening angle, no initial guess and no view.
  vpLaserConicCalibration();

  /*!
    Camera intrinsics (used to back-project the laser points on the grids).
    \exception vpLaserConicException::badCameraError when a focal length is not positive or finite.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    Full opening angle of the laser (rad), known from the manufacturer.
    \exception vpLaserConicException::badLaserError when it is outside (0, pi).
  */
  void setOpeningAngle(double openingAngle);
  /*!
    Initial guess of the laser pose in the camera frame; only the direction of its Z axis (the cone
    axis) and its translation (the apex) matter. Without it, calibrate() uses its argument.
    \exception vpLaserConicException::badLaserError when the pose is not a finite rigid transformation.
  */
  void setInitialGuess(const vpHomogeneousMatrix &cMl);
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
    Runs the two-stage bundle adjustment: first the gamma_i alone (cone fixed at the initial guess),
    then all the parameters, both with Ceres' Levenberg-Marquardt.
    \param cMl : on input ignored unless no initial guess was set (then used as the guess); on output
    the calibrated laser pose (rotation Rx(alpha) Ry(beta), translation the apex).
    \return the RMS distance (metres) on the grid planes between measured and predicted points.
    \exception vpLaserConicException when the camera, opening angle or views are missing, the initial
    guess is not a finite rigid transformation, a laser point does not back-project in front of the camera
    on its grid plane, or the optimisation fails.
  */
  double calibrate(vpHomogeneousMatrix &cMl);

  //! RMS error (metres) of the initial cone (after the first stage, which fits only the gamma_i), available
  //! after calibrate().
  double getInitialRms() const { return m_initialRms; }
  //! Predicted trace points on each grid (grid coordinates X, Y) for the calibrated laser, for figures.
  std::vector<std::vector<std::pair<double, double> > > getPredictedGridPoints() const { return m_predicted; }
  //! Measured trace points on each grid (grid coordinates X, Y), for figures.
  std::vector<std::vector<std::pair<double, double> > > getMeasuredGridPoints() const { return m_measured; }

private:
  //! One view: grid pose and laser image points.
  struct View
  {
    vpHomogeneousMatrix cMg;
    std::vector<vpImagePoint> points;
  };
  vpCameraParameters m_cam;
  bool m_hasCam, m_hasGuess;
  double m_openingAngle;
  vpHomogeneousMatrix m_guess;
  std::vector<View> m_views;
  double m_initialRms;
  std::vector<std::vector<std::pair<double, double> > > m_predicted, m_measured;
};

#endif
