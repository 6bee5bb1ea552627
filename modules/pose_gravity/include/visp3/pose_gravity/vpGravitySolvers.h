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
    unit norm (the facade normalises them; the solvers refuse a vector whose norm is more than 1e-6 off,
    with no pose);
  - no function allocates on the heap; none throws: validation belongs to the facade, degenerate input gives a false / zero return;
  - the rotation is parametrised as \f$ {}^c\mathbf{R}_o = {}^w\mathbf{R}_c^T \mathbf{R}_z(\alpha)\,
    {}^w\mathbf{R}_o \f$ with \f$ {}^w\mathbf{R}_c = \f$ uprightRotation(gCam) and
    \f$ {}^w\mathbf{R}_o = \f$ uprightRotation(gObj): the "yaw" \f$ \alpha \f$ is the only unknown
    angle. With the bearings \f$ \mathbf{f}_i = {}^w\mathbf{R}_c \mathbf{x}_i \f$ and
    \f$ \mathbf{Y}_i = {}^w\mathbf{R}_o \mathbf{X}_i \f$ every solver works on
    \f$ \mathbf{R}_z(\alpha)\mathbf{Y}_i + {}^w\mathbf{R}_c\mathbf{t} = \lambda_i \mathbf{f}_i \f$, free of the
    singular frames of the paper's closed forms (gravity along a Y axis).
*/
#ifndef VP_GRAVITY_SOLVERS_H
#define VP_GRAVITY_SOLVERS_H

#include <array>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>

//! Pure Eigen solvers for the pose with known camera and object vertical directions.
namespace vpGravitySolvers
{
//! A camera pose: object-to-camera rotation and translation (cRo, cto).
struct Pose
{
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity(); //!< cRo
  Eigen::Vector3d t = Eigen::Vector3d::Zero();     //!< cto
};

//! Outcome of the two-point solver (Lemma 1 of the paper).
enum class P2PCase {
  TwoSolutions, //!< distinct image points: the two roots of the yaw equation; one pose when it has a double root or when cheirality discards a root.
  UniqueRotation, //!< both image points on one ray not parallel to gravity: rotation unique, translation known only up to that ray.
  Undetermined, //!< the yaw is not observable from the pair: both image points on one ray parallel to gravity (Lemma 1), or a vertical object segment, or two horizontal rays; infinitely many poses.
  NoSolution //!< no admissible pose: identical object points, non-finite data, measurements inconsistent beyond noise, or both roots behind the camera.
};

/*!
  Rotation \f$ {}^w\mathbf{R}_s \f$ that maps the unit vector \e g (gravity in a sensor frame s) onto
  \f$ \mathbf{e}_z \f$ of an "upright" frame w (Sec. III: the paper's "fake NED" frame).

  Its rows are \f$ (\mathbf{b}_1, \mathbf{b}_2, \mathbf{g}) \f$, the basis completed as in Duff et al.,
  "Building an orthonormal basis, revisited" (JCGT 2017). It is exact and well conditioned for every
  direction of \e g: the only division is by \f$ 1 + |g_z| \ge 1 \f$. The horizontal axes switch
  branch with the sign of \f$ g_z \f$; that choice is arbitrary and absorbed by the yaw.
  \param g : unit vector (not normalised here).
*/
VISP_EXPORT Eigen::Matrix3d uprightRotation(const Eigen::Vector3d &g);

/*!
  Minimal P2P with known vertical: rotation \f$ \mathbf{R} = {}^w\mathbf{R}_c^T \mathbf{R}_z(\alpha)\, {}^w\mathbf{R}_o \f$
  with one unknown angle, solved in closed form.

  \param gCam, gObj : unit gravity in camera and object frames.
  \param x : the two bearings (normalized image points, z > 0).
  \param X : the two object points.
  \param poses : receives the candidates, ordered by increasing yaw angle \f$ \alpha \in (-\pi, \pi] \f$
  (see the file description for the definition of the yaw); entries beyond the returned count are
  unspecified.
  \param p2pCase : optional, receives the Lemma 1 case.
  \return number of poses written (0, 1 or 2).

  The yaw solves \f$ \mathbf{n} \cdot \mathbf{R}_z(\alpha)(\mathbf{Y}_A - \mathbf{Y}_B) = 0 \f$ with
  \f$ \mathbf{n} = \mathbf{f}_A \times \mathbf{f}_B \f$, i.e. \f$ a\cos\alpha + b\sin\alpha + c = 0 \f$
  (the paper's eq. 12), solved for \f$ (\cos\alpha, \sin\alpha) \f$ with one square root; the depths
  follow by linear least squares. When noise makes
  \f$ |c| \f$ exceed \f$ \sqrt{a^2+b^2} \f$ by less than 0.05 (unit vectors: about the angle by
  which the segment misses the plane of the rays), the double root is returned; beyond, NoSolution.
  Roots that put a point behind the camera are discarded (the paper counts both algebraic roots).

  Coincident image points (Lemma 1): for a ray not parallel to gravity one pose is returned
  (UniqueRotation) with the exact rotation and the translation that puts the nearer of the two
  points at unit depth (the translation is only known up to the ray). Which point is nearer follows
  from the vertical components of the segment and the ray; for a horizontal ray it is not observable
  and point 0 is taken as the nearer one. A ray parallel to gravity gives Undetermined.
*/
VISP_EXPORT int p2p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[2],
                    const Eigen::Vector3d X[2], std::array<Pose, 2> &poses, P2PCase *p2pCase = nullptr);

//! Which point pair P3P solves (see p3p()).
enum class P3PPairRule {
  BestThirdPoint, //!< all three pairs solved; the pose whose third point reprojects best (default).
  WidestPair      //!< the paper's rule: the pair farthest apart in the image, the others only if it has no solution.
};

/*!
  P3P with known vertical (Sec. V): P2P on one pair of the three points, then the candidate that
  reprojects the third point best.

  Pair choice (\e rule):
  - P3PPairRule::BestThirdPoint (default): each of the three pairs is solved and the pose whose third
    point has the smallest reprojection error is returned. Pairs that barely observe the yaw (a nearly
    vertical object segment, or two rays in a nearly vertical plane: the normalized coefficient
    \f$ \sqrt{a^2+b^2} / (|\mathbf{n}||\mathbf{d}|) \f$ of the yaw equation below 0.05) are used only
    when no other pair gives a pose; a pair with no yaw information at all never gives one. A double
    root (noise pushing the yaw equation past tangency) thus wins only when it explains the third point
    better than the other pairs' roots.
  - P3PPairRule::WidestPair: the paper's rule, the pair farthest apart in the image first; the other
    pairs, in decreasing image distance, only when it gives no pose.

  The returned pose is not checked against a tolerance here: vpPoseGravity does that (see
  vpPoseGravity::setConsistencyThreshold()).
  \param gCam, gObj : unit gravity in camera and object frames.
  \param x : the three bearings; \param X : the three object points (not collinear).
  \param pose : receives the pose when found.
  \param rule : pair choice.
  \return true when a pose was found.
*/
VISP_EXPORT bool p3p(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d x[3],
                     const Eigen::Vector3d X[3], Pose &pose, P3PPairRule rule = P3PPairRule::BestThirdPoint);

/*!
  Least squares on n >= 3 points, closed form at each step: the best minimum of the algebraic cost,
  reweighted towards the maximum-likelihood one.

  The algebraic residuals \f$ w_i (x_i P_z - P_x) \f$, \f$ w_i (y_i P_z - P_y) \f$ of all points
  (\f$ \mathbf{P} = \mathbf{R}\mathbf{X}_i + \mathbf{t} \f$) are linear in
  \f$ (\cos\alpha, \sin\alpha, \mathbf{t}, 1) \f$; \f$ \mathbf{t} \f$ is eliminated (Schur
  complement) and the remaining quadratic form is minimised on the unit circle exactly: its
  stationary points are the roots of a quartic in \f$ \tan(\phi/2) \f$ (vpPolynomialRoots()), polished
  by Newton steps. Only its minima (positive second derivative, at most two) are candidates, ranked by
  the sum of squared reprojection errors of their poses (infinite with a point behind the camera):
  the algebraic cost itself favours poses squeezed towards the camera, so that with an outlier its
  lowest minimum can be a pose with points behind it. Without any minimum in front of the camera the
  lowest algebraic minimum is returned (vpPoseGravity then reports it).

  Since \f$ x_i P_z - P_x = P_z\,(x_i - P_x/P_z) \f$, unit weights weight each point's squared
  reprojection error by its squared depth: far points dominate. Each reweighting pass sets
  \f$ w_i = \bar z / z_i \f$ from the depths \f$ z_i \f$ of the current estimate and solves again, so
  that the cost approaches the sum of squared reprojection errors (the maximum-likelihood cost for
  isotropic image noise). A pass is kept only if it lowers the sum of squared reprojection errors;
  passes stop at the first that does not, after one that lowers it by less than 0.1 %, or when a
  depth is not positive.
  \param gCam, gObj : unit gravity in camera and object frames.
  \param x, X : n bearings and object points.
  \param n : number of points (>= 2; 2 points leave the yaw ambiguous, use p2p()).
  \param pose : receives the pose.
  \param reweightingPasses : number of inverse-depth reweighting passes (0: the plain algebraic cost).
  \return false when all rays are parallel, when the yaw is not observable (all points on one
  vertical line) or data are not finite.
*/
VISP_EXPORT bool leastSquares(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, const Eigen::Vector3d *x,
                              const Eigen::Vector3d *X, int n, Pose &pose, int reweightingPasses = 2);

/*!
  Translation of the pose given its rotation: linear least squares on n >= 2 points of the
  distance of each transformed point \f$ \mathbf{R}\mathbf{X}_i + \mathbf{t} \f$ to its ray (the paper's
  eq. 14 generalised to all points and all equations).
  \param R : cRo. \param x, X : n bearings and object points. \param n : number of points.
  \param t : receives cto.
  \return false when the rays are all parallel (translation unobservable along them).
*/
VISP_EXPORT bool translationFromRotation(const Eigen::Matrix3d &R, const Eigen::Vector3d *x, const Eigen::Vector3d *X,
                                         int n, Eigen::Vector3d &t);
} // namespace vpGravitySolvers

#endif
