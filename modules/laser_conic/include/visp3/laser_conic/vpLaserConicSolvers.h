/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicSolvers.h
  \brief Pure Eigen core of the circular-laser attitude and altitude estimators (Boutteau, Sturm,
  Vasseur, Demonceaux, JMIV 2018), free of ViSP types and of the RANSAC loop.

  Conventions shared by every function here:
  - everything lives in the camera frame, in \b normalized image coordinates: the camera is
    \f$ P = [I\,|\,0] \f$ (pixels are mapped through \f$ K^{-1} \f$ by the facade);
  - the laser is a cone of half opening angle \f$ \theta \f$ whose apex is at \e apex and whose axis
    is the third column of \f$ {}^c\mathbf{R}_l \f$ (laser frame: apex at the origin, axis +Z);
  - a plane is \f$ \boldsymbol{\pi} = (\mathbf{n}, d) \f$ with \f$ \mathbf{n}^T\mathbf{X} + d = 0 \f$;
    a ground plane is returned with \f$ \|\mathbf{n}\| = 1 \f$ and \f$ d > 0 \f$, i.e. its normal
    points from the plane towards the camera and \f$ d \f$ is the altitude of the camera centre;
  - conics are symmetric 3x3 matrices c with \f$ \mathbf{x}^T c\, \mathbf{x} = 0 \f$;
  - no function allocates on the heap or throws: validation belongs to the facade.
*/
#ifndef VP_LASER_CONIC_SOLVERS_H
#define VP_LASER_CONIC_SOLVERS_H

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>

//! Pure Eigen solvers of the laser_conic module: cones, conic fit, plane pair, PP-3, GP-3.
namespace vpLaserSolvers
{
//! The laser cone in the camera frame.
struct LaserCone
{
  Eigen::Matrix3d cRl = Eigen::Matrix3d::Identity(); //!< orientation of the laser frame (axis = third column)
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();    //!< cone apex (laser centre) in the camera frame
  double halfAngle = 0.0;                            //!< half opening angle theta, in (0, pi/2)
};

//! Cone quadric D (4x4, paper eq. 8-9) of the laser in the camera frame.
VISP_EXPORT Eigen::Matrix4d laserConeQuadric(const LaserCone &cone);

//! Cone quadric C = P^T c P (eq. 10) spanned by the camera centre and an image conic (normalized coordinates).
VISP_EXPORT Eigen::Matrix4d cameraConeQuadric(const Eigen::Matrix3d &c);

/*!
  Plane-pair solution (Sec. 4): finds the double root of det(C + x D), splits the rank-2 member
  into its two planes and keeps the one with both optical centres on the same side.
  \return true and the ground plane (unit normal towards the camera, d > 0) on success.
*/
VISP_EXPORT bool planePair(const Eigen::Matrix3d &c, const LaserCone &cone, Eigen::Vector4d &plane);

/*!
  Conic through n >= 5 points (least squares, DLT on Hartley-normalised coordinates, eq. 29-31).
  With exactly 5 points it is the minimal interpolating conic. \return false when degenerate (with 5
  points also when two of them are closer than 1e-6 of the sample's extent).
*/
VISP_EXPORT bool fitConic(const Eigen::Vector2d *points, int n, Eigen::Matrix3d &c);

//! The camera-image epipole and the two epipolar lines tangent to every image of the laser trace (Sec. 5.2).
struct EpipolarTangents
{
  Eigen::Vector3d epipole = Eigen::Vector3d::Zero(); //!< image of the laser centre (homogeneous)
  Eigen::Vector3d u = Eigen::Vector3d::Zero();       //!< first tangent line (homogeneous)
  Eigen::Vector3d v = Eigen::Vector3d::Zero();       //!< second tangent line (homogeneous)
};

//! Computes the epipolar tangents of the laser cone. \return false if the camera centre lies inside the cone or on its apex.
VISP_EXPORT bool epipolarTangents(const LaserCone &cone, EpipolarTangents &tangents);

/*!
  PP-3 minimal solver (Sec. 5.2): conics through 3 points tangent to the two epipolar lines, via
  the canonical homography and the quartic (eq. 53). Only ellipses are returned. A sample with two
  points closer than 1e-4 of its extent gives none (the conic would be decided by rounding).
  \return number of conics written (0 to 4).
*/
VISP_EXPORT int pp3Conics(const Eigen::Vector2d points[3], const EpipolarTangents &tangents, Eigen::Matrix3d conics[4]);

/*!
  GP-3 minimal solver (Sec. 5.3): intersects the three rays with the laser cone (eq. 57) and forms
  the planes through one intersection per ray, keeping those with both optical centres on the same
  side. \return number of planes written (0 to 8), each normalised as a ground plane; 0 when two of
  the points are closer than 1e-6 of the sample's extent.
*/
VISP_EXPORT int gp3Planes(const Eigen::Vector2d points[3], const LaserCone &cone, Eigen::Vector4d planes[8]);

/*!
  Geometric refinement of a ground plane (d > 0) on image points (normalized coordinates) believed
  to lie on the trace: Levenberg-Marquardt over the 3 degrees of freedom of the plane (normal on the
  sphere, altitude) minimising the squared Sampson distances of the points to conicFromPlane().
  Unlike a free conic fit, every iterate satisfies the epipolar constraints of the rig.
  \return false (plane untouched) on invalid input; otherwise the plane is the refined one (never worse).
*/
VISP_EXPORT bool refinePlane(const Eigen::Vector2d *points, int n, const LaserCone &cone, Eigen::Vector4d &plane,
                             int iterations = 20);

/*!
  refinePlane() minimising the weighted sum of squared Sampson distances (weights >= 0, one per point;
  nullptr for unit weights): the step of an iteratively reweighted least-squares (IRLS) refit. False (plane
  untouched) also when a weight is negative or not finite, or fewer than 3 are positive.
*/
VISP_EXPORT bool refinePlaneWeighted(const Eigen::Vector2d *points, const double *weights, int n, const LaserCone &cone,
                                     Eigen::Vector4d &plane, int iterations = 20);

/*!
  Plane of a ground attitude: altitude h (d), roll and pitch as in altitudeRollPitch() (its inverse):
  n = -R_x(roll) R_y(pitch) e_z.
*/
VISP_EXPORT Eigen::Vector4d planeFromAltitudeRollPitch(double altitude, double roll, double pitch);

//! Image conic (normalized coordinates) of the trace of the laser cone on a ground plane.
VISP_EXPORT Eigen::Matrix3d conicFromPlane(const Eigen::Vector4d &plane, const LaserCone &cone);

//! First-order geometric (Sampson) distance of an image point to a conic, in the units of the point.
VISP_EXPORT double sampsonDistance(const Eigen::Matrix3d &c, const Eigen::Vector2d &p);

/*!
  True when the conic is a real, non-degenerate ellipse (upper-left 2x2 block definite, and real points), in
  any coordinates: normalized, or pixels with the ellipse anywhere in a large image (the test is relative to
  the quadratic part).
*/
VISP_EXPORT bool isEllipse(const Eigen::Matrix3d &c);

/*!
  Altitude, roll and pitch of the camera from a ground plane (unit normal towards the camera).
  With \f$ \mathbf{g} = -\mathbf{n} \f$ the downward direction in the camera frame, the attitude is
  \f$ \mathbf{g} = R_x(\mathrm{roll})\, R_y(\mathrm{pitch})\, \mathbf{e}_z \f$: roll about the camera
  x axis, pitch about the camera y axis, both zero when the optical axis is perpendicular to the
  ground. roll = atan2(-g_y, g_z), pitch = asin(g_x).
*/
VISP_EXPORT void altitudeRollPitch(const Eigen::Vector4d &plane, double &altitude, double &roll, double &pitch);
} // namespace vpLaserSolvers

#endif
