/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpFeatureLaserPlane.h
  \brief The ground plane seen by the circular laser as a visual feature for vpServo.
*/
#ifndef VP_FEATURE_LASER_PLANE_H
#define VP_FEATURE_LASER_PLANE_H

#include <visp3/core/vpPlane.h>
#include <visp3/visual_features/vpBasicFeature.h>

/*!
  \ingroup group_laser_conic
  \brief Ground-plane feature \f$ \mathbf{s} = (h, g_x, g_y) \f$: the altitude \f$ h \f$ of the camera
  centre over the plane and the first two coordinates of the plane's downward unit normal
  \f$ \mathbf{g} \f$ in the camera frame, as vpLaserConicPose or vpLaserConicFilter measure them.

  Interaction matrix (camera velocity \f$ (\mathbf{v}, \boldsymbol{\omega}) \f$ in the camera frame, as
  vpServo's): a world-fixed plane moves in the camera frame as \f$ \dot{\mathbf{g}} = \mathbf{g} \times
  \boldsymbol{\omega} \f$ and \f$ \dot h = -\mathbf{g}^T \mathbf{v} \f$, so
  \f[ L_h = \begin{pmatrix} -g_x & -g_y & -g_z & 0 & 0 & 0 \end{pmatrix}, \quad
      L_{g_x} = \begin{pmatrix} 0 & 0 & 0 & 0 & -g_z & g_y \end{pmatrix}, \quad
      L_{g_y} = \begin{pmatrix} 0 & 0 & 0 & g_z & 0 & -g_x \end{pmatrix}. \f]
  The three rows fix the altitude, the roll and the pitch (\f$ g_x = \sin \mathrm{pitch} \f$,
  \f$ g_y = -\sin \mathrm{roll} \cos \mathrm{pitch} \f$) of a camera that faces the ground (\f$ g_z > 0 \f$,
  roll and pitch within 90 degrees, as the laser's estimates are): the feature does not see the sign of
  \f$ g_z \f$, so a camera turned over (roll 180 degrees) has the feature of a level one, and at
  \f$ g_z = 0 \f$ the rows of \f$ g_x, g_y \f$ lose a rank. The horizontal translation and the yaw are left to
  other features, e.g. a vpFeaturePoint on a landing pad:

  \code
  vpFeatureLaserPlane s, sd;
  sd.buildFrom(0.3, 0.0, 0.0);                 // land at 30 cm, level
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.addFeature(s, sd);                      // altitude, roll, pitch
  task.addFeature(p, pd);                      // x, y of the pad
  // each iteration: s.buildFrom(filter.getAltitude(), filter.getRoll(), filter.getPitch());
  \endcode
*/
class VISP_EXPORT vpFeatureLaserPlane : public vpBasicFeature
{
public:
  //! Level ground at 1 m.
  vpFeatureLaserPlane();
  //! Default destructor.
  ~vpFeatureLaserPlane() override {}

  //! Resets to level ground at 1 m.
  void init() override;
  /*!
    From the altitude (m, > 0), roll and pitch (rad, vpLaserConicPose's convention, each within (-pi/2, pi/2):
    the ground in front of the camera).
    \exception vpLaserConicException::badValueError on a non-finite value, an altitude <= 0, or a roll or pitch
    outside (-pi/2, pi/2) (degrees passed as radians, say).
  */
  void buildFrom(double altitude, double roll, double pitch);
  /*!
    From a plane in the camera frame (any orientation of its normal, the camera off the plane).
    \exception vpLaserConicException::badValueError on a zero normal or a camera on the plane.
  */
  void buildFrom(const vpPlane &cPlane);

  //! Altitude h, m.
  double get_h() const { return s[0]; }
  //! x coordinate of the downward ground normal.
  double get_gx() const { return s[1]; }
  //! y coordinate of the downward ground normal.
  double get_gy() const { return s[2]; }
  //! z coordinate of the downward ground normal (positive when the camera looks at the ground).
  double get_gz() const { return m_gz; }

  //! Selects the altitude row.
  static unsigned int selectAltitude() { return FEATURE_LINE[0]; }
  //! Selects the g_x row (pitch).
  static unsigned int selectGx() { return FEATURE_LINE[1]; }
  //! Selects the g_y row (roll).
  static unsigned int selectGy() { return FEATURE_LINE[2]; }

  //! Interaction matrix of the selected rows (see the class description).
  vpMatrix interaction(unsigned int select = FEATURE_ALL) override;
  //! s - s* on the selected rows.
  vpColVector error(const vpBasicFeature &s_star, unsigned int select = FEATURE_ALL) override;
  //! Prints the selected rows.
  void print(unsigned int select = FEATURE_ALL) const override;
  //! A copy allocated with new.
  vpFeatureLaserPlane *duplicate() const override;
  //! Writes altitude, roll and pitch in the top-left corner of the image (the feature has no image position).
  void display(const vpCameraParameters &cam, const vpImage<unsigned char> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const override;
  //! display() on a colour image.
  void display(const vpCameraParameters &cam, const vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const override;

private:
  double m_gz;
  void set(double h, double gx, double gy, double gz);
};

#endif
