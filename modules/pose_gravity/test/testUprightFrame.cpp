/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
// uprightRotation(): a rotation taking gravity onto e_z, exact for every direction (Sec. III).
#include <vector>

#include <gtest/gtest.h>

#include <visp3/pose_gravity/vpGravitySolvers.h>

#include "gravity_test_scene.h"

namespace
{
void expectUpright(const Eigen::Vector3d &g)
{
  const Eigen::Matrix3d R = vpGravitySolvers::uprightRotation(g);
  // Only rounding separates these from exact: a few ulps of 1.
  EXPECT_LT((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-14) << "g = " << g.transpose();
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14) << "g = " << g.transpose();
  EXPECT_LT((R * g - Eigen::Vector3d::UnitZ()).norm(), 1e-14) << "g = " << g.transpose();
}
} // namespace

TEST(PoseGravityUprightFrame, AxesAndTheirNeighbourhoods)
{
  // The paper's frame is singular for g on the Y axis; the directions where a branch switches
  // (g_z = 0) and the exact axes are the delicate ones.
  std::vector<Eigen::Vector3d> directions;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[axis] = sign;
      directions.push_back(e);
      for (double eps : {1e-300, 1e-16, 1e-9, 1e-4})
        for (int other = 0; other < 3; ++other)
          if (other != axis)
            for (double s2 : {-1.0, 1.0}) {
              Eigen::Vector3d v = e;
              v[other] = s2 * eps;
              directions.push_back(v.normalized());
            }
    }
  directions.push_back(Eigen::Vector3d(1.0, 1.0, -0.0).normalized());
  directions.push_back(Eigen::Vector3d(1.0, -1.0, 0.0).normalized());
  for (const Eigen::Vector3d &g : directions)
    expectUpright(g);
}

TEST(PoseGravityUprightFrame, RandomDirections)
{
  gravity_test::SceneGenerator gen(7);
  for (int k = 0; k < 100000; ++k)
    expectUpright(gen.unitVector());
}
