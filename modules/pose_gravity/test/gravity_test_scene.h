/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Simulated scenes for the pose_gravity tests: a random object seen by ViSP's pinhole camera
  (vpPoint::track), gravity measured by an IMU in each frame. The ground truth is the simulated
  pose itself. The test suites are named pose_gravity_* so that `ctest -R pose_gravity` selects them.
*/
#ifndef GRAVITY_TEST_SCENE_H
#define GRAVITY_TEST_SCENE_H

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpQuaternionVector.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/pose_gravity/vpGravitySolvers.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

namespace gravity_test
{
//! The repetitions of a statistical test: \e full, or \e reduced when the environment has
//! VSP_REDUCED_TRIALS=1 (the sanitizer stage of scripts/test.sh: the same code paths, fewer times; the
//! full counts run in the Release stage).
inline int trials(int full, int reduced)
{
  const char *env = std::getenv("VSP_REDUCED_TRIALS");
  return env != nullptr && std::string(env) == "1" ? reduced : full;
}

//! One simulated observation: ground-truth pose, points (oX.. and x, y set) and both gravities.
struct Scene
{
  vpHomogeneousMatrix cMo;
  std::vector<vpPoint> points;
  vpColVector gCam, gObj;
};

inline Eigen::Vector3d toEigen(const vpColVector &v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

inline vpColVector toVisp(const Eigen::Vector3d &v)
{
  vpColVector c(3);
  c[0] = v.x();
  c[1] = v.y();
  c[2] = v.z();
  return c;
}

inline Eigen::Matrix3d rotationOf(const vpHomogeneousMatrix &M)
{
  Eigen::Matrix3d R;
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c)
      R(r, c) = M[r][c];
  return R;
}

inline Eigen::Vector3d translationOf(const vpHomogeneousMatrix &M)
{
  return Eigen::Vector3d(M[0][3], M[1][3], M[2][3]);
}

//! Pose error: max of the rotation error (Frobenius / sqrt 2, ~ the angle in rad, accurate near 0)
//! and the translation error relative to the true distance.
inline double poseError(const Eigen::Matrix3d &R, const Eigen::Vector3d &t, const vpHomogeneousMatrix &truth)
{
  const double eR = (R - rotationOf(truth)).norm() / std::sqrt(2.0);
  const double eT = (t - translationOf(truth)).norm() / translationOf(truth).norm();
  return std::max(eR, eT);
}
inline double poseError(const vpGravitySolvers::Pose &p, const vpHomogeneousMatrix &truth)
{
  return poseError(p.R, p.t, truth);
}
inline double poseError(const vpHomogeneousMatrix &M, const vpHomogeneousMatrix &truth)
{
  return poseError(rotationOf(M), translationOf(M), truth);
}
//! Rotation error alone (rad) and translation error alone (relative).
inline double rotationError(const vpHomogeneousMatrix &M, const vpHomogeneousMatrix &truth)
{
  return (rotationOf(M) - rotationOf(truth)).norm() / std::sqrt(2.0);
}
inline double translationError(const vpHomogeneousMatrix &M, const vpHomogeneousMatrix &truth)
{
  return (translationOf(M) - translationOf(truth)).norm() / translationOf(truth).norm();
}

//! Rotation mapping unit vector a onto unit vector b, followed by a turn of angle beta about b.
inline vpRotationMatrix rotationMapping(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double beta)
{
  Eigen::Vector3d axis = a.cross(b);
  const double s = axis.norm(), c = a.dot(b);
  if (s < 1e-12) {
    // Parallel or antiparallel: any axis orthogonal to a.
    axis = (std::abs(a.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(a).normalized();
  } else {
    axis /= s;
  }
  const double angle = std::atan2(s, c);
  const vpRotationMatrix align(vpThetaUVector(angle * axis.x(), angle * axis.y(), angle * axis.z()));
  const vpRotationMatrix turn(vpThetaUVector(beta * b.x(), beta * b.y(), beta * b.z()));
  return turn * align;
}

//! Seeded generator of random scenes in front of the camera.
class SceneGenerator
{
public:
  explicit SceneGenerator(unsigned int seed) : m_rng(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(m_rng); }
  double gaussian(double sigma) { return std::normal_distribution<double>(0.0, sigma)(m_rng); }
  std::mt19937 &rng() { return m_rng; }

  Eigen::Vector3d unitVector()
  {
    Eigen::Vector3d v;
    do {
      v = Eigen::Vector3d(gaussian(1.0), gaussian(1.0), gaussian(1.0));
    } while (v.norm() < 1e-6);
    return v.normalized();
  }

  //! Uniformly distributed rotation.
  vpRotationMatrix rotation()
  {
    Eigen::Vector4d q;
    do {
      q = Eigen::Vector4d(gaussian(1.0), gaussian(1.0), gaussian(1.0), gaussian(1.0));
    } while (q.norm() < 1e-6);
    q.normalize();
    return vpRotationMatrix(vpQuaternionVector(q[0], q[1], q[2], q[3]));
  }

  //! n object points in a cube of side \e size around a random origin offset.
  std::vector<Eigen::Vector3d> objectPoints(int n, double size = 1.0)
  {
    const Eigen::Vector3d offset(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    std::vector<Eigen::Vector3d> X(n);
    for (Eigen::Vector3d &p : X)
      p = offset + size * Eigen::Vector3d(uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5));
    return X;
  }

  //! A pose with rotation cRo placing the object centroid 2 to 8 m in front of the camera, inside a
  //! 60 degree field of view, every point at least 0.5 m deep (retries the translation otherwise).
  vpHomogeneousMatrix poseLookingAt(const std::vector<Eigen::Vector3d> &X, const vpRotationMatrix &cRo)
  {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d &p : X)
      centroid += p / static_cast<double>(X.size());
    Eigen::Matrix3d R;
    for (unsigned int r = 0; r < 3; ++r)
      for (unsigned int c = 0; c < 3; ++c)
        R(r, c) = cRo[r][c];
    for (;;) {
      const double depth = uniform(2.0, 8.0);
      const Eigen::Vector3d target(uniform(-0.5, 0.5) * depth, uniform(-0.5, 0.5) * depth, depth);
      const Eigen::Vector3d t = target - R * centroid;
      bool inFront = true;
      for (const Eigen::Vector3d &p : X)
        inFront = inFront && (R * p + t).z() > 0.5;
      if (inFront)
        return vpHomogeneousMatrix(vpTranslationVector(t.x(), t.y(), t.z()), cRo);
    }
  }

  //! Random scene of n points, random gravity in the object frame, exact measurements.
  Scene scene(int n, double size = 1.0)
  {
    const std::vector<Eigen::Vector3d> X = objectPoints(n, size);
    Scene s;
    s.cMo = poseLookingAt(X, rotation());
    s.gObj = toVisp(unitVector());
    s.gCam = cameraGravity(s.cMo, s.gObj);
    s.points = project(X, s.cMo);
    return s;
  }

  static vpColVector cameraGravity(const vpHomogeneousMatrix &cMo, const vpColVector &gObj)
  {
    return toVisp(rotationOf(cMo) * toEigen(gObj));
  }

  //! vpPoints with object coordinates X and image coordinates from ViSP's projection through cMo.
  static std::vector<vpPoint> project(const std::vector<Eigen::Vector3d> &X, const vpHomogeneousMatrix &cMo)
  {
    std::vector<vpPoint> points;
    for (const Eigen::Vector3d &p : X) {
      vpPoint P(p.x(), p.y(), p.z());
      P.track(cMo);
      points.push_back(P);
    }
    return points;
  }

  //! Adds Gaussian noise of standard deviation sigma to the normalized image coordinates.
  void addImageNoise(std::vector<vpPoint> &points, double sigma)
  {
    for (vpPoint &P : points) {
      P.set_x(P.get_x() + gaussian(sigma));
      P.set_y(P.get_y() + gaussian(sigma));
    }
  }

  //! Gravity measurement: sigma on each component, then renormalised (the paper's IMU model).
  vpColVector noisyGravity(const vpColVector &g, double sigma)
  {
    const Eigen::Vector3d n = toEigen(g) + Eigen::Vector3d(gaussian(sigma), gaussian(sigma), gaussian(sigma));
    return toVisp(n.normalized());
  }

private:
  std::mt19937 m_rng;
};

//! Bearings (x, y, 1) and object points of vpPoints, for the pure solvers.
inline void toSolverInput(const std::vector<vpPoint> &points, std::vector<Eigen::Vector3d> &x,
                          std::vector<Eigen::Vector3d> &X)
{
  x.clear();
  X.clear();
  for (const vpPoint &P : points) {
    x.emplace_back(P.get_x(), P.get_y(), 1.0);
    X.emplace_back(P.get_oX(), P.get_oY(), P.get_oZ());
  }
}

/*!
  An estimator fed with the scene: both gravity directions and the points, each unless told otherwise
  (the validation tests leave one of them out on purpose).
*/
inline vpPoseGravity estimatorFor(const Scene &s, bool cameraGravity = true, bool objectGravity = true,
                                  bool points = true)
{
  vpPoseGravity pose;
  if (cameraGravity)
    pose.setCameraGravity(s.gCam);
  if (objectGravity)
    pose.setObjectGravity(s.gObj);
  if (points)
    pose.addPoints(s.points);
  return pose;
}

//! Median of a vector (copied).
inline double median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
} // namespace gravity_test

#endif
