/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_estimators.h
  \brief Private adapters of the circular-laser minimal solvers to vpRansacLoop(): one small
  estimator per method, all scoring the Sampson distance of an image point to a conic (normalized
  image coordinates), so that the RANSAC threshold has the same meaning for every method.
*/
#ifndef VP_LASER_ESTIMATORS_H
#define VP_LASER_ESTIMATORS_H

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicSolvers.h>
#include <visp3/robust/vpRansac.h>

#include "laser_geometry.h"
#include "laser_kernels.h"

namespace vsp::laser_estimators
{
typedef std::vector<Eigen::Vector2d, Eigen::aligned_allocator<Eigen::Vector2d> > PointList;

//! Least-squares conic through the listed points, kept only if it is an ellipse.
inline bool fitEllipseOn(const PointList &points, const std::vector<int> &indices, Eigen::Matrix3d &c)
{
  PointList subset;
  subset.reserve(indices.size());
  for (int i : indices)
    subset.push_back(points[i]);
  return vpLaserSolvers::fitConic(subset.data(), static_cast<int>(subset.size()), c) && vpLaserSolvers::isEllipse(c);
}

//! Common part of the conic-model estimators: the data and the residual.
class ConicModelData
{
public:
  typedef Eigen::Matrix3d Model;
  explicit ConicModelData(const PointList &points) : m_points(points) {}
  int size() const { return static_cast<int>(m_points.size()); }
  double residual(const Model &c, int i) const { return vpLaserSolvers::sampsonDistance(c, m_points[i]); }
  //! Local optimisation: least-squares ellipse on the inliers.
  bool refine(const std::vector<int> &inliers, Model &c) const
  {
    return inliers.size() >= 5 && fitEllipseOn(m_points, inliers, c);
  }
  //! Final refit: the same least-squares ellipse.
  bool refineFinal(const std::vector<int> &inliers, Model &c) const { return refine(inliers, c); }

protected:
  const PointList &m_points;
};

//! PP-5: the conic through 5 points (Sec. 5.1).
class Pp5Estimator : public ConicModelData
{
public:
  static constexpr int kSampleSize = 5;
  static constexpr int kMaxModels = 1;
  explicit Pp5Estimator(const PointList &points) : ConicModelData(points) {}
  int solveMinimal(const int *sample, Model *models) const
  {
    Eigen::Vector2d p[5];
    for (int k = 0; k < 5; ++k)
      p[k] = m_points[sample[k]];
    return vpLaserSolvers::fitConic(p, 5, models[0]) && vpLaserSolvers::isEllipse(models[0]) ? 1 : 0;
  }
};

//! PP-3: the conics through 3 points tangent to the two epipolar lines (Sec. 5.2).
class Pp3Estimator : public ConicModelData
{
public:
  static constexpr int kSampleSize = 3;
  static constexpr int kMaxModels = 4;
  Pp3Estimator(const PointList &points, const vpLaserSolvers::EpipolarTangents &tangents)
    : ConicModelData(points), m_tangents(tangents)
  {
  }
  int solveMinimal(const int *sample, Model *models) const
  {
    const Eigen::Vector2d p[3] = {m_points[sample[0]], m_points[sample[1]], m_points[sample[2]]};
    return vpLaserSolvers::pp3Conics(p, m_tangents, models);
  }

private:
  vpLaserSolvers::EpipolarTangents m_tangents;
};

//! A ground-plane hypothesis with the image conic it predicts (cached for scoring).
struct PlaneModel
{
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  Eigen::Matrix3d conic = Eigen::Matrix3d::Zero();
};

/*!
  GP-3: ground planes through 3 ray/cone intersections (Sec. 5.3). The points are also kept as two
  contiguous coordinate arrays so that scoring a hypothesis is one tight loop of a few flops per
  point (squared Sampson distance, no square root, no call per point).
*/
class Gp3Estimator
{
public:
  typedef PlaneModel Model;
  static constexpr int kSampleSize = 3;
  static constexpr int kMaxModels = 8;
  /*!
    Inliers the local optimisation inside the RANSAC loop refines on at most (evenly spread over the
    consensus set): the loop only needs a better hypothesis to rank, the final refit uses them all.
  */
  static constexpr int kLocalPoints = 64;
  //! Iterations of the plane refinement inside the RANSAC loop (one pass over the points each).
  static constexpr int kLocalIterations = 3;

  /*!
    GP-3's settings of the RANSAC loop (the others come from the caller): a plane refinement is cheap
    and a refined plane often gathers inliers its start missed (three local rounds); most hypotheses of
    a contaminated trace (one outlier among the three points) predict a conic far from the trace, so a
    few data of a random subset suffice to drop them (pretest on 64 points); later best models a few
    inliers better than the refitted consensus are not refitted again (gain 2 %).
  */
  static void tuneRansac(vpRansacOptions &options)
  {
    options.localRounds = 3;
    options.pretestSize = 64;
    options.localOptimisationGain = 0.02;
  }

  //! Estimator over normalized image points (kept by reference) for the given laser cone.
  Gp3Estimator(const PointList &points, const vpLaserSolvers::LaserCone &cone)
    : m_points(points), m_x(points.size()), m_y(points.size()), m_cone(cone),
      m_form(vpLaserSolvers::detail::laserConeForm(cone)), m_subset()
  {
    for (size_t i = 0; i < points.size(); ++i) {
      m_x[i] = points[i](0);
      m_y[i] = points[i](1);
    }
    m_subset.reserve(points.size());
  }
  //! Number of points.
  int size() const { return static_cast<int>(m_points.size()); }
  //! The GP-3 planes of three points (gp3Planes()), each with its predicted image conic.
  int solveMinimal(const int *sample, Model *models) const
  {
    const Eigen::Vector2d p[3] = {m_points[sample[0]], m_points[sample[1]], m_points[sample[2]]};
    Eigen::Vector4d planes[8];
    const int n = vpLaserSolvers::gp3Planes(p, m_cone, planes);
    for (int k = 0; k < n; ++k)
      models[k] = modelOf(planes[k]);
    return n;
  }
  //! Distance of the point to the image of the trace the plane predicts.
  double residual(const Model &m, int i) const
  {
    return std::sqrt(vpLaserSolvers::detail::ConicCoefficients(m.conic).squaredSampson(m_x[i], m_y[i]));
  }
  /*!
    Inliers among [begin, end), their truncated squared distances added to \e cost and their indices
    written to \e inliers when not null (see vpRansacLoop()): scoreConicChunk() on chunks of 64
    points (no division for the inlier test, no square root, no branch per point; NaN, i.e. no
    gradient, is never an inlier).
  */
  int scoreRange(const Model &m, int begin, int end, double thr2, double &cost, int *inliers) const
  {
    const vpLaserSolvers::detail::ConicCoefficients c(m.conic);
    constexpr int kChunk = 64;
    int local[kChunk];
    int count = 0;
    for (int first = begin; first < end; first += kChunk) {
      const int size = std::min(end - first, kChunk);
      count += vpLaserSolvers::detail::scoreConicChunk(c, m_x.data() + first, m_y.data() + first, first, size, thr2,
                                                       cost, inliers ? inliers + count : local);
    }
    return count;
  }
  //! Inliers among the listed points (the preemptive test of vpRansacLoop()): the test of scoreRange().
  int countInliers(const Model &m, const int *indices, int count, double thr2) const
  {
    const vpLaserSolvers::detail::ConicCoefficients c(m.conic);
    const double thr2Times4 = 4.0 * thr2;
    int inliers = 0;
    for (int k = 0; k < count; ++k) {
      const size_t i = static_cast<size_t>(indices[k]);
      double v0, v1;
      const double algebraic = c.apply(m_x[i], m_y[i], v0, v1);
      inliers += algebraic * algebraic < thr2Times4 * (v0 * v0 + v1 * v1) ? 1 : 0; // NaN is never an inlier
    }
    return inliers;
  }
  //! Local optimisation: geometric refinement of the plane (refinePlane) on a subset of the inliers.
  bool refine(const std::vector<int> &inliers, Model &m) const
  {
    return refineOn(inliers, kLocalPoints, kLocalIterations, m);
  }
  //! Final refit: the same refinement on every inlier, run to convergence.
  bool refineFinal(const std::vector<int> &inliers, Model &m) const
  {
    return refineOn(inliers, static_cast<int>(inliers.size()), 20, m);
  }

private:
  Model modelOf(const Eigen::Vector4d &plane) const
  {
    Model m;
    m.plane = plane;
    const Eigen::Matrix3d c = vpLaserSolvers::detail::traceConic(plane, m_cone.apex, m_form);
    const double norm = c.norm();
    m.conic = norm > 0.0 ? Eigen::Matrix3d(c / norm) : c;
    return m;
  }
  //! refinePlane() on at most \e cap inliers taken at a regular stride (all when cap >= their number).
  bool refineOn(const std::vector<int> &inliers, int cap, int iterations, Model &m) const
  {
    const int count = static_cast<int>(inliers.size());
    if (count < 3 || cap < 3)
      return false;
    const int used = std::min(count, cap);
    m_subset.clear();
    for (int k = 0; k < used; ++k)
      m_subset.push_back(m_points[inliers[static_cast<size_t>(k) * count / used]]);
    Eigen::Vector4d plane = m.plane;
    if (!vpLaserSolvers::refinePlane(m_subset.data(), used, m_cone, plane, iterations))
      return false;
    m = modelOf(plane);
    return true;
  }

  const PointList &m_points;
  std::vector<double> m_x, m_y; //!< coordinates of the points, contiguous for the scoring loop
  vpLaserSolvers::LaserCone m_cone;
  Eigen::Matrix3d m_form;     //!< 3x3 form of the laser cone
  mutable PointList m_subset; //!< points handed to the refinement (capacity reserved once)
};
} // namespace vsp::laser_estimators

#endif
