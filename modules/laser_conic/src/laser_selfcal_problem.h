/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_selfcal_problem.h
  \brief Private: the joint least-squares problem of the self-calibration from ground frames (one
  plane per frame, the laser shared), its Jacobians, the laser information of a frame (plane
  eliminated) and the Ceres solve.

  Parameters (all in the camera frame):
  - the laser block L = (alpha, beta, u, v, s, A): cone axis Rx(alpha) Ry(beta) e_z (the convention of
    vpLaserConicCalibration), apex s * normalize(a0 + u e1 + v e2) with a0 the reference apex direction
    and (e1, e2) an orthonormal basis of its orthogonal plane, A the full opening angle;
  - one plane block P = (roll, pitch, h) per frame: n = -Rx(roll) Ry(pitch) e_z, d = h
    (vpLaserSolvers::planeFromAltitudeRollPitch()).
  A residual is the Sampson distance (pixels: normalized units times the mean focal length) of a trace
  point to the image conic the plane and the laser predict, times the square root of its weight.
*/
#ifndef VP_LASER_SELFCAL_PROBLEM_H
#define VP_LASER_SELFCAL_PROBLEM_H

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace vpLaserSelfCal
{
//! Number of laser parameters (alpha, beta, u, v, s, A).
constexpr int kLaserSize = 6;
//! Number of plane parameters (roll, pitch, h).
constexpr int kPlaneSize = 3;
typedef Eigen::Matrix<double, kLaserSize, 1> LaserVector;
typedef Eigen::Matrix<double, kLaserSize, kLaserSize> LaserMatrix;

//! The reference apex direction and its orthogonal basis, fixed for one solve.
struct ApexChart
{
  Eigen::Vector3d a0 = Eigen::Vector3d::UnitX(), e1 = Eigen::Vector3d::UnitY(), e2 = Eigen::Vector3d::UnitZ();
  //! Chart centred on the direction of \e apex (non-zero).
  static ApexChart around(const Eigen::Vector3d &apex);
};

//! One frame of the problem: its normalized points, their weights and its plane.
struct Frame
{
  std::vector<Eigen::Vector2d> points;                //!< normalized (undistorted) coordinates
  std::vector<double> weights;                        //!< IRLS weights, 0 for a rejected point
  Eigen::Vector3d plane = Eigen::Vector3d(0, 0, 1.0); //!< (roll, pitch, h)
  bool fixedAltitude = false;                         //!< h held (a known altitude)
};

//! Laser parameters of a cone (full opening angle) in a chart.
LaserVector laserParameters(const vpLaserSolvers::LaserCone &cone, const ApexChart &chart);
//! The cone of laser parameters.
vpLaserSolvers::LaserCone laserCone(const LaserVector &L, const ApexChart &chart);
//! (roll, pitch, h) of a ground plane (unit normal towards the camera, d > 0).
Eigen::Vector3d planeParameters(const Eigen::Vector4d &plane);
//! The ground plane (n, d) of plane parameters.
Eigen::Vector4d planeOf(const Eigen::Vector3d &P);

/*!
  Signed residuals (pixels, unweighted) of the points of a frame for the plane parameters \e plane and, when \e jacobianPlane and
  \e jacobianLaser are not null, their derivatives (n x 3 and n x 6, row-major flat arrays).
  \return false when the predicted conic has no gradient at a point (residual then 0).
*/
bool frameResiduals(const Frame &frame, const Eigen::Vector3d &plane, const LaserVector &L, const ApexChart &chart,
                    double focal, double *residuals, double *jacobianPlane, double *jacobianLaser);

/*!
  Information (6x6, pixels^-2 once divided by the noise variance) that the weighted points of a frame give
  on the laser parameters with the frame's plane eliminated (Schur complement), at the current estimate,
  from at most \e maxPoints points spread along the frame (scaled to all the points).
*/
LaserMatrix frameLaserInformation(const Frame &frame, const LaserVector &L, const ApexChart &chart, double focal,
                                  size_t maxPoints);

//! Settings of one joint solve.
struct SolveSettings
{
  double focal = 1.0;                                             //!< mean focal length, pixels (residual units)
  bool free[kLaserSize] = {true, true, true, true, false, false}; //!< laser parameters estimated
  int maxIterations = 100;                                        //!< Levenberg-Marquardt iterations
};

//! Outcome of one joint solve.
struct SolveResult
{
  bool converged = false; //!< Ceres reported convergence (not the iteration limit, not a failure)
  bool failed = false;    //!< Ceres failed (an evaluation of the residuals failed), rather than stopping at the limit
  bool finite = false;    //!< every parameter finite
  int iterations = 0;     //!< iterations run
  std::string message;    //!< Ceres' message
};

/*!
  Joint Levenberg-Marquardt over the planes of \e frames and the free entries of \e L (the planes are
  eliminated, DENSE_SCHUR), with the weights of the frames. \e L and the frames' planes are updated.
*/
SolveResult solveJoint(std::vector<Frame> &frames, LaserVector &L, const ApexChart &chart,
                       const SolveSettings &settings);
} // namespace vpLaserSelfCal

#endif
