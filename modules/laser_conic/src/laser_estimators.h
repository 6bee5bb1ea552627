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

#include <vector>

#include <Eigen/Core>

#include <visp3/laser_conic/vpLaserConicSolvers.h>

namespace vpLaserEstimators
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

//! GP-3: ground planes through 3 ray/cone intersections (Sec. 5.3).
class Gp3Estimator
{
public:
  typedef PlaneModel Model;
  static constexpr int kSampleSize = 3;
  static constexpr int kMaxModels = 8;
  Gp3Estimator(const PointList &points, const vpLaserSolvers::LaserCone &cone) : m_points(points), m_cone(cone) {}
  int size() const { return static_cast<int>(m_points.size()); }
  int solveMinimal(const int *sample, Model *models) const
  {
    const Eigen::Vector2d p[3] = {m_points[sample[0]], m_points[sample[1]], m_points[sample[2]]};
    Eigen::Vector4d planes[8];
    const int n = vpLaserSolvers::gp3Planes(p, m_cone, planes);
    for (int k = 0; k < n; ++k) {
      models[k].plane = planes[k];
      models[k].conic = vpLaserSolvers::conicFromPlane(planes[k], m_cone);
    }
    return n;
  }
  //! Distance of the point to the image of the trace the plane predicts.
  double residual(const Model &m, int i) const { return vpLaserSolvers::sampsonDistance(m.conic, m_points[i]); }
  /*!
    Local optimisation: geometric refinement of the plane on the inliers (refinePlane), started from
    the hypothesis and from the plane pair of their least-squares ellipse; the better one is kept.
  */
  bool refine(const std::vector<int> &inliers, Model &m) const
  {
    if (inliers.size() < 3)
      return false;
    PointList subset;
    subset.reserve(inliers.size());
    for (int i : inliers)
      subset.push_back(m_points[i]);
    const int n = static_cast<int>(subset.size());
    Eigen::Vector4d starts[2] = {m.plane, Eigen::Vector4d::Zero()};
    int nstarts = 1;
    Eigen::Matrix3d c;
    if (n >= 5 && fitEllipseOn(m_points, inliers, c) && vpLaserSolvers::planePair(c, m_cone, starts[1]))
      nstarts = 2;
    bool refined = false;
    double bestCost = 0.0;
    for (int k = 0; k < nstarts; ++k) {
      Model candidate;
      candidate.plane = starts[k];
      if (!vpLaserSolvers::refinePlane(subset.data(), n, m_cone, candidate.plane))
        continue;
      candidate.conic = vpLaserSolvers::conicFromPlane(candidate.plane, m_cone);
      double cost = 0.0;
      for (int i : inliers) {
        const double r = residual(candidate, i);
        cost += r * r;
      }
      if (!refined || cost < bestCost) {
        m = candidate;
        bestCost = cost;
        refined = true;
      }
    }
    return refined;
  }

private:
  const PointList &m_points;
  vpLaserSolvers::LaserCone m_cone;
};
} // namespace vpLaserEstimators

#endif
