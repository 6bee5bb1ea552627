/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_robust_fit.h
  \brief Private scale-adaptive final fit of the circular-laser estimators, after their RANSAC search:
  the trace collected at its own residual scale, the arc coverage test, the constrained (3-DOF plane)
  and free (5-DOF conic) fits with a robust loss, the choice between them, the calibration-health
  figure and the covariance of the estimate. Pure Eigen, normalized image coordinates.
*/
#ifndef VP_LASER_ROBUST_FIT_H
#define VP_LASER_ROBUST_FIT_H

#include <limits>
#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

#include "laser_estimators.h"

namespace vsp::laser_robust_fit
{
using vsp::laser_estimators::PointList;

//! Which fit gives the final plane.
enum class FinalFit {
  FREE,        //!< plane pair of the least-squares conic on the trace (5 DOF; PP-5, PLANE_PAIR)
  CONSTRAINED, //!< plane refined on the trace (3 DOF, the conic keeps its tangency to the epipolar lines)
  SELECT       //!< the constrained fit unless the data reject it against the free one (F-test at 1 %)
};

//! Settings of fit().
struct Settings
{
  double focal = 1.0;       //!< pixels per normalized unit: residuals are reported in pixels
  double threshold = 2.0;   //!< RANSAC threshold (pixels): the floor of the re-collection threshold
  double scaleFactor = 3.0; //!< re-collection threshold = max(threshold, scaleFactor * sigma)
  double minCoverage = 0.0; //!< smallest accepted arc coverage of the trace (rad, 0 disables the test)
  bool adaptive = true;     //!< false: keep the RANSAC inliers and a plain least-squares final fit
  bool covariance = false;  //!< compute the covariances
  //! Largest dilution of the altitude (see Result::altitudeDilution; 0 disables the test)
  double maxAltitudeDilution = 0.0;
  //! Largest standard deviation of the attitude (radians, see Result::attitudeDeviation; 0 disables the test)
  double maxAttitudeDeviation = 0.0;
  FinalFit finalFit = FinalFit::FREE;
};

/*!
  Smallest error (pixels) the attitude's deviation assumes of a trace point. The detector regularises its
  centres along the curve: on rendered frames they scatter by 0.003-0.03 px about the final fit while they lie
  0.05-0.4 px from the true line (second-pass RMS), and through JPEG the colour blocks move whole stretches of
  the ring the same way, which a first-order deviation (independent errors) does not see. A 1 mm baseline at
  1 m through JPEG 60 (10-15 deg off) read as 0.4 deg uncertain at the points' own scatter, 4.3 deg at 0.25 px,
  8.6 deg at 0.5 px; a 3 cm one 0.28 deg at 0.5 px. Exact points (scatter 0) would read as certain whatever the
  baseline.
*/
constexpr double kMinTraceError = 0.5;

//! Outcome of fit().
enum class Outcome { OK, SHORT_ARC, NOT_AN_ELLIPSE, NO_PLANE, WEAK_TRACE, NO_PARALLAX };

//! Result of fit().
struct Result
{
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero(); //!< image conic of the final plane or free fit
  std::vector<int> inliers;                        //!< the points of the trace
  double sigma = 0.0;                              //!< residual scale (pixels, MAD) of the free fit on the trace
  double rmsConstrained = 0.0;                     //!< RMS residual (pixels) of the constrained fit on the trace
  double rmsFree = 0.0;                            //!< RMS residual (pixels) of the free fit on the trace
  double coverage = 0.0;                           //!< angular coverage of the trace around the ellipse (rad)
  //! How many times the final plane's altitude is less certain from the trace than from as many points over its
  //! whole ring (measureTraceGeometry() in the .cpp), when the tests ran (see Settings::maxAltitudeDilution)
  double altitudeDilution = 0.0;
  //! First-order standard deviation (radians) of the final plane's attitude in its worst direction, from the
  //! trace at its residual scale, when the tests ran (see Settings::maxAttitudeDeviation)
  double attitudeDeviation = 0.0;
  //! attitudeDeviation as many points spread over the whole ring of the final plane would give (NaN when the
  //! tests did not run or most of that ring lies behind the camera)
  double wholeAttitudeDeviation = std::numeric_limits<double>::quiet_NaN();
  bool constrainedChosen = false;                            //!< the final plane is the constrained fit
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();      //!< of (altitude, roll, pitch)
  Eigen::Matrix4d planeCovariance = Eigen::Matrix4d::Zero(); //!< of (a, b, c, d)
};

/*!
  Final fit from a RANSAC consensus \e inliers (and, for a constrained start, \e startPlane; zero
  when the RANSAC model was a conic).
*/
Outcome fit(const PointList &points, const std::vector<int> &inliers, const vpLaserSolvers::LaserCone &cone,
            const Eigen::Vector4d &startPlane, const Settings &settings, Result &result);

//! Centre of the conic \e c (its symmetric part); false when it has none (a parabola or a degenerate conic) or
//! when it is not finite (a subnormal determinant).
bool ellipseCentre(const Eigen::Matrix3d &c, Eigen::Vector2d &centre);

//! Angular coverage (rad, in [0, 2 pi]) of the points around the centre of the ellipse \e c.
double arcCoverage(const PointList &points, const std::vector<int> &indices, const Eigen::Matrix3d &c);
} // namespace vsp::laser_robust_fit

#endif
