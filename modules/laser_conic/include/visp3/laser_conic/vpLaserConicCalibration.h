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
*/
class VISP_EXPORT vpLaserConicCalibration
{
public:
  vpLaserConicCalibration();

  //! Camera intrinsics.
  void setCameraParameters(const vpCameraParameters &cam);
  //! Full opening angle of the laser (rad), known from the manufacturer.
  void setOpeningAngle(double openingAngle);
  //! Initial guess of the laser pose in the camera frame (default: identity rotation, apex at the camera centre is refused, so set it).
  void setInitialGuess(const vpHomogeneousMatrix &cMl);
  //! Adds one view: grid pose in the camera frame and the laser points seen on the grid (pixels).
  void addView(const vpHomogeneousMatrix &cMg, const std::vector<vpImagePoint> &laserPoints);
  //! Removes all views.
  void clearViews();
  //! Number of views added.
  unsigned int getNbViews() const { return static_cast<unsigned int>(m_views.size()); }

  /*!
    Runs the two-stage bundle adjustment. \param cMl : on input ignored unless no initial guess was
    set (then used as the guess); on output the calibrated laser pose.
    \return the RMS distance (metres) on the grid planes between measured and predicted points.
    \exception vpException when the camera, opening angle, or views are missing or a view has fewer
    than 5 points, or the optimisation fails.
  */
  double calibrate(vpHomogeneousMatrix &cMl);

  //! RMS error (metres) of the initial guess, available after calibrate().
  double getInitialRms() const { return m_initialRms; }
  //! Predicted trace points on each grid (grid coordinates X, Y) for the calibrated laser, for figures.
  std::vector<std::vector<std::pair<double, double> > > getPredictedGridPoints() const { return m_predicted; }
  //! Measured trace points on each grid (grid coordinates X, Y), for figures.
  std::vector<std::vector<std::pair<double, double> > > getMeasuredGridPoints() const { return m_measured; }

private:
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
