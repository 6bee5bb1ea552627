/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Small geometric helpers shared by the gravity solvers (private to the module).

  Every solver works in two "upright" frames: w_c = wRc * camera and w_o = wRo * object, both with
  gravity along e_z (see uprightRotation()). They differ by a rotation Rz(alpha) about e_z, so that
  cRo = wRc^T * Rz(alpha) * wRo for the one unknown angle alpha.
*/
#ifndef VP_GRAVITY_GEOMETRY_H
#define VP_GRAVITY_GEOMETRY_H

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/robust/vpRobustScale.h>

namespace vpGravitySolvers
{
namespace detail
{
//! Rotation of angle alpha about e_z, given by its cosine and sine.
inline Eigen::Matrix3d rotationZ(double c, double s)
{
  Eigen::Matrix3d Rz;
  Rz << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return Rz;
}

//! cRo = wRc^T Rz(alpha) wRo.
inline Eigen::Matrix3d composeRotation(const Eigen::Matrix3d &wRc, double alpha, const Eigen::Matrix3d &wRo)
{
  return wRc.transpose() * rotationZ(std::cos(alpha), std::sin(alpha)) * wRo;
}

//! Wraps an angle into (-pi, pi].
inline double wrapAngle(double a)
{
  const double pi = 3.14159265358979323846;
  a = std::remainder(a, 2.0 * pi); // in [-pi, pi]
  return (a <= -pi) ? a + 2.0 * pi : a;
}

//! Squared reprojection error in normalized coordinates of X through the pose, against the bearing
//! x (any positive multiple of (x, y, 1)); infinity when X is not in front of the camera.
inline double reprojectionError2(const Pose &pose, const Eigen::Vector3d &x, const Eigen::Vector3d &X)
{
  const Eigen::Vector3d P = pose.R * X + pose.t;
  if (!(P.z() > 0.0) || !(x.z() > 0.0))
    return std::numeric_limits<double>::infinity();
  const double ex = P.x() / P.z() - x.x() / x.z();
  const double ey = P.y() / P.z() - x.y() / x.z();
  return ex * ex + ey * ey;
}

//! True when \e gCam and \e gObj are finite and of unit norm within 1e-6 (the solvers' contract: a vector of
//! another norm would make uprightRotation() a matrix that is not a rotation).
inline bool unitGravities(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj)
{
  return std::abs(gCam.squaredNorm() - 1.0) <= 2e-6 && std::abs(gObj.squaredNorm() - 1.0) <= 2e-6;
}

//! True when every coefficient of the vector is finite.
template <typename Derived> inline bool allFinite(const Eigen::MatrixBase<Derived> &v) { return v.allFinite(); }

//! Settings of refinePose().
struct RefineOptions
{
  double imageSigma = 1e-3;               //!< image noise, normalized coordinates (whitens the reprojection errors)
  double cameraGravitySigma = 0.0;        //!< noise of each component of the unit camera gravity (0: exact)
  double objectGravitySigma = 0.0;        //!< noise of each component of the unit object gravity (0: exact)
  vpRobustLoss loss = vpRobustLoss::NONE; //!< robust loss on each point's reprojection error
  double lossScale = 3e-3;                //!< scale of the loss, normalized coordinates
};

/*!
  Maximum-likelihood refinement of \e pose on n >= 2 points (implemented with Ceres in
  refine_gravity.cpp). Reprojection residuals in normalized coordinates divided by imageSigma.
  Both gravity sigmas 0: 4 DOF (yaw, t), both gravity vectors exact. Otherwise 6 DOF with the two
  gravity measurements as one prior of standard deviation sqrt(sigma_c^2 + sigma_o^2) per component.
  Returns false, pose unchanged, without a usable solution or when a point ends behind the camera. Its
  covariance is poseCovariance()'s, apart: a pose whose covariance is singular is still a pose.
*/
bool refinePose(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                const Eigen::Vector3d *X, int n, const RefineOptions &options, Pose &pose);

/*!
  Covariance of the pose estimated from n points at \e pose (first-order, Gauss-Newton: the inverse
  of J^T J of the whitened, robustified residuals of refinePose()). Order (t_x, t_y, t_z, theta_x,
  theta_y, theta_z): t in the unit of the object points, theta in rad, a rotation perturbation on the
  left in the camera frame, cRo = exp([theta]_x) cRo_hat. With exact gravity (both sigmas 0) the
  matrix has rank 4: its rotation block is var(yaw) gc gc^T. Returns false when J^T J is singular.
*/
bool poseCovariance(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                    const Eigen::Vector3d *X, int n, const RefineOptions &options, const Pose &pose,
                    Eigen::Matrix<double, 6, 6> &covariance);
} // namespace detail
} // namespace vpGravitySolvers

#endif
