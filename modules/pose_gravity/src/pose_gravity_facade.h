/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Helpers shared by the source files of the vpPoseGravity facade (private to the module): ViSP <->
  Eigen conversions, point collection, the duplicate search, the consistency check.
*/
#ifndef VP_POSE_GRAVITY_FACADE_H
#define VP_POSE_GRAVITY_FACADE_H

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/pose_gravity/vpGravitySolvers.h>

namespace vsp::pose_gravity_facade
{
//! Relative tolerance under which two object (or image) points are the same point.
constexpr double kDuplicateTolerance = 1e-12;

inline Eigen::Vector3d toEigen(const vpColVector &v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

//! Writes the pose into cMo in place (no temporary matrix: vpHomogeneousMatrix allocates).
void storePose(const vpGravitySolvers::Pose &pose, vpHomogeneousMatrix &cMo);
//! The pose of a homogeneous matrix.
vpGravitySolvers::Pose toPose(const vpHomogeneousMatrix &cMo);

//! Bearings (x, y, 1) and object points of the given points (all of them when \e index is null).
void collectPoints(const std::vector<vpPoint> &points, const std::vector<unsigned int> *index,
                   std::vector<Eigen::Vector3d> &x, std::vector<Eigen::Vector3d> &X);

/*!
  For each row of \e v (n points of dimension dim, row-major), the index of an earlier row equal to it
  within \e tolerance in every coordinate, or -1. O(n log n): coordinates are quantised into cells
  of side \e tolerance, the cells sorted, and only the 3^dim neighbouring cells of a point searched
  (up to 128 rows, the direct comparison of all pairs is faster).
  \e tolerance 0 means exact equality.
*/
void findDuplicates(const std::vector<double> &v, int dim, double tolerance, std::vector<int> &firstEqual);

//! Bearings and object points of the first \e count points.
void collectFirst(const std::vector<vpPoint> &points, size_t count, std::vector<Eigen::Vector3d> &x,
                  std::vector<Eigen::Vector3d> &X);

//! Largest absolute coordinate of the object points (the scale of kDuplicateTolerance).
double objectScale(const std::vector<vpPoint> &points, unsigned int count);

/*!
  True when exchanging the camera and object gravity \e gCam, \e gObj (unit vectors) changes the problem by
  more than their noise: they differ by more than 3 times the root sum of squares of their standard deviations
  and by at least 1 degree, what IMUs give the vertical to when none was stated (the default 0). An upright
  camera facing an upright target has them equal: their exchange is then no mistake that points could show.
*/
bool exchangeChangesTheProblem(const Eigen::Vector3d &gCam, const Eigen::Vector3d &gObj, double gCamStdDev,
                               double gObjStdDev);
} // namespace vsp::pose_gravity_facade

#endif
