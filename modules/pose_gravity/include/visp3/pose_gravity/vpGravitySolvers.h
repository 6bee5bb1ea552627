/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpGravitySolvers.h
  \brief Pure Eigen solvers for absolute pose with known camera and object vertical directions
  (D'Alfonso, Garone, Muraca, Pugliese, MED 2013), free of ViSP types so that they can be
  benchmarked and reused without the vpPoseGravity facade.

  Conventions shared by every function here:
  - a pose is \f$ {}^c\mathbf{R}_o, {}^c\mathbf{t}_o \f$: a point \f$ \mathbf{X} \f$ of the object
    frame is \f$ \mathbf{R}\mathbf{X} + \mathbf{t} \f$ in the camera frame;
  - an image point is given by its normalized coordinates as the bearing
    \f$ \mathbf{x} = (x, y, 1)^T \f$ (any positive multiple is accepted);
  - \e gCam and \e gObj are the gravity direction measured in the camera and the object frames, of
    unit norm (the facade normalises them);
  - no function allocates on the heap; none throws: validation belongs to the facade.
*/
#ifndef VP_GRAVITY_SOLVERS_H
#define VP_GRAVITY_SOLVERS_H

#include <array>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>

namespace vpGravitySolvers
{
//! A camera pose: object-to-camera rotation and translation (cRo, cto).
struct Pose
{
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity(); //!< cRo
  Eigen::Vector3d t = Eigen::Vector3d::Zero();     //!< cto
};

//! Outcome of the two-point solver (Lemma 1 of the paper).
enum class P2PCase
{
  TwoSolutions,      //!< distinct image points: two candidate poses (one if the trigonometric equation has a double root).
  UniqueRotation,    //!< both image points on one ray not parallel to gravity: rotation unique, translation known only up to that ray.
  Undetermined,      //!< both image points on one ray parallel to gravity: infinitely many rotations and translations.
  NoSolution         //!< degenerate input (identical 3D points, non-finite data): nothing returned.
};

/*!
  Rotation \f$ {}^w\mathbf{R}_s \f$ that maps the unit vector \e g (gravity in a sensor frame s) onto
  \f$ \mathbf{e}_z \f$ of an "upright" frame w. It is smooth and well conditioned for every
  direction of \e g (two branches joined where both are exact, no singular direction).
*/
Eigen::Matrix3d uprightRotation(const Eigen::Vector3d &g);

/*!
  Minimal P2P with known vertical: rotation \f$ \mathbf{R} = {}^w\mathbf{R}_c^T \mathbf{R}_z(\alpha)\, {}^w\mathbf{R}_o \f$
  with one unknown angle, solved in closed form.

  \param gCam, gObj : unit gravity in camera and object frames.
  \param x : the two bearings (normalized image points, z > 0).
  \param X : the two object points.
  \param poses : receives the candidates, ordered by increasing yaw angle \f$ \alpha \in (-\pi, \pi] \f$.
  \param p2pCase : optional, receives the Lemma 1 case.
  \return number of poses written (0, 1 or 2). In the UniqueRotation case one pose is returned
  whose translation places object point 0 at unit depth along its ray.
*/
int p2p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[2],
        const Eigen::Vector3d X[2], std::array<Pose, 2> &poses, P2PCase *p2pCase = nullptr);

/*!
  P3P with known vertical (Sec. V): P2P on the pair of points farthest apart in the image (the
  other pairs if its image points coincide), then the candidate that reprojects the third point best.
  \return true when a pose was found.
*/
bool p3p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[3],
         const Eigen::Vector3d X[3], Pose &pose);

/*!
  Closed-form least squares on n >= 2 points: the algebraic residuals of all projection equations
  are linear in \f$ (\cos\alpha, \sin\alpha, \mathbf{t}) \f$; \f$ \mathbf{t} \f$ is eliminated and the
  remaining constrained problem on the unit circle is solved exactly through a quartic.
  \return true when a pose was found.
*/
bool leastSquares(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                  const Eigen::Vector3d *X, int n, Pose &pose);

/*!
  Translation of the pose given its rotation, linear least squares on n >= 2 points
  (the paper's eq. 14 generalised). \return false when the rays are all parallel.
*/
bool translationFromRotation(const Eigen::Matrix3d &R, const Eigen::Vector3d *x, const Eigen::Vector3d *X,
                             int n, Eigen::Vector3d &t);
} // namespace vpGravitySolvers

#endif
