/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_calibration_problem.h
  \brief Private: the bundle adjustment of vpLaserConicCalibration (paper Sec. 6, eq. 58-65): the cone
  parameters, one gamma per laser point, the Ceres problem of their grid residuals and the figures
  computed from it.
*/
#ifndef VP_LASER_CALIBRATION_PROBLEM_H
#define VP_LASER_CALIBRATION_PROBLEM_H

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <ceres/ceres.h>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/robust/vpRobustScale.h>

namespace vsp::laser_calibration
{
//! Parameter vector of the cone, in the order of the covariance matrix.
enum { kAlpha = 0, kBeta, kVx, kVy, kVz, kOpening, kNbConeParams };

//! The full opening angle stays within [kMinOpening, pi - kMinOpening] rad in the solver (its bounds), and a
//! given one must lie there too (an angle outside made Ceres fail on an infeasible start).
constexpr double kMinOpening = 1e-3;

//! Grid XY of the laser points of each view.
typedef std::vector<std::vector<std::pair<double, double> > > GridPoints;

typedef Eigen::Matrix<double, kNbConeParams, kNbConeParams> ConeMatrix;

/*!
  Two grid planes closer than this (angle of the normals, relative difference of the distances to the
  camera centre) count as one: the cone cut by one plane is a conic that several cones fit exactly
  (views of one plane, measured: 11-12 degrees and 18 cm from the truth with a normal RMS, even for
  planes 1 degree or 1 % apart), while planes 3 degrees or 3 % apart gave 0.1 degree and 1.6 mm at
  0.5 px of noise.
*/
constexpr double kSamePlaneAngleDeg = 2.0, kSamePlaneDistanceRatio = 0.02;

//! True when the grids of \e cMg lie in at least two planes (see kSamePlaneAngleDeg).
bool hasTwoGridPlanes(const std::vector<vpHomogeneousMatrix> &cMg);

//! Alpha, beta such that Rx(alpha) Ry(beta) (0, 0, 1) is the Z axis of cMl: (sin b, -sin a cos b, cos a cos b).
void axisAngles(const vpHomogeneousMatrix &cMl, double &alpha, double &beta);

//! The laser pose [Rx(alpha) Ry(beta) | apex].
vpHomogeneousMatrix laserPose(double alpha, double beta, const double apex[3]);

//! The cone parameters Ceres works on, and one gamma per point.
struct ConeState
{
  double angles[2];
  double apex[3];
  double opening;
  std::vector<std::vector<double> > gammas;
};

//! One residual block of the problem.
struct PointBlock
{
  ceres::ResidualBlockId id;
  const ceres::CostFunction *cost;
  double W[4]; //!< pixels per metre of grid displacement at the measured point (row-major 2x2)
  size_t view, index;
  bool inlier;
};

/*!
  The problem of compute(): one residual block per laser point (in view order), over the cone (axis
  angles, apex, opening angle) and the point's gamma. The stages of vpLaserConicCalibration::compute()
  are its fit*() calls, in order.
*/
class ConeProblem
{
public:
  /*!
    The cone at the initial guess (its axis and apex, the opening angle \e openingAngle) and, for each
    point, the gamma of the cone ray closest to it as seen from the apex.
  */
  ConeProblem(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured, const vpCameraParameters &cam,
              const vpHomogeneousMatrix &guess, double openingAngle, int maxIterations);
  ConeProblem(const ConeProblem &) = delete;
  ConeProblem &operator=(const ConeProblem &) = delete;

  //! Stage 1: only the gamma_i, so that every point starts on its closest ray of the guessed cone.
  bool fitGammas(std::string &error);
  //! Frees the axis, the apex and, when \e estimateAngle, the opening angle for the next stages.
  void releaseCone(bool estimateAngle);
  /*!
    Stage 2: everything under the robust \e loss whose scale (pixels) shrinks from the initial
    residuals to the noise level, 1.5 vpRobustMadScale() of the residual norms, times sqrt(N / (N - p)) for the
    p cone parameters fitted to N points (or \e userScale when > 0), by at most a factor of 4 per run; \e scale
    is the last one. Then the points farther than 3
    scales from the cone leave the problem (they keep their gamma).
  */
  bool fitRobust(vpRobustLoss loss, double userScale, double &scale, std::string &error);
  //! Stage 3: plain least squares on the inliers; its convergence is the calibration's.
  bool fitInliers(ceres::Solver::Summary &summary);

  //! Number of points still in the problem.
  unsigned int nbInliers() const;
  //! True when every cone parameter is finite.
  bool isFinite() const;
  //! RMS distance (metres) on the grid planes over all the points, or over the inliers only.
  double gridRms(bool inliersOnly);
  //! Predicted grid XY of every point, for figures.
  GridPoints predictedGridPoints(const GridPoints &measured);
  /*!
    Normal matrix of the 6 cone parameters with the gamma_i eliminated (Schur complement; each gamma_i
    touches only its own two residuals), summed over the inliers, and their residual sum of squares.
  */
  ConeMatrix reducedNormalMatrix(double &rss);
  //! For each view and point, true when the point is an inlier.
  std::vector<std::vector<bool> > inlierFlags(size_t nbViews) const;
  //! Mean distance from the initial apex to the grid points: the length that turns angles into metres.
  double meanDistance() const { return m_meanDistance; }
  //! The laser pose of the current cone.
  vpHomogeneousMatrix pose() const { return laserPose(m_s.angles[0], m_s.angles[1], m_s.apex); }
  //! The current full opening angle (rad).
  double openingAngle() const { return m_s.opening; }

private:
  void initialState(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured,
                    const vpHomogeneousMatrix &guess, double openingAngle);
  void addBlocks(const std::vector<vpHomogeneousMatrix> &cMg, const GridPoints &measured,
                 const vpCameraParameters &cam);
  bool solve();
  void residual(const PointBlock &b, double r[2], double *jacobians[4] = nullptr);
  void gridResidual(const PointBlock &b, double d[2]);
  //! Residual norms (pixels) of all the points, into m_norms.
  void evaluateNorms();

  ConeState m_s;
  double m_meanDistance;
  // The blocks' cost functions outlive their removal from the problem (outliers are still evaluated
  // for the figures), and one loss is shared by all the blocks: both are owned here.
  ceres::Problem m_problem;
  ceres::LossFunctionWrapper m_loss;
  std::vector<std::unique_ptr<ceres::CostFunction> > m_costs;
  std::vector<PointBlock> m_blocks;
  std::vector<double> m_norms;
  int m_freeConeParameters = 0; //!< the cone's parameters the fit estimates (releaseCone())
  ceres::Solver::Options m_options;
  ceres::Solver::Summary m_summary;
};
} // namespace vsp::laser_calibration

#endif
