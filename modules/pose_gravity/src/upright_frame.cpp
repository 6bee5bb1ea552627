/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Section III of D'Alfonso et al.: an "upright" frame w whose vertical axis is gravity.

  The paper completes gravity into a frame with a fixed helper axis (its eq. 2), which is singular
  when gravity lies on the sensor's Y axis. Here the basis is completed with the construction of
  Duff et al., "Building an orthonormal basis, revisited" (JCGT 2017): its only division is by
  1 + |g_z| >= 1, so it is exact and well conditioned for every unit direction.
*/
#include "gravity_pair_solver.h"

namespace vpGravitySolvers
{
Eigen::Matrix3d uprightRotation(const Eigen::Vector3d &g)
{
  Eigen::Vector3d b1, b2;
  detail::uprightAxes(g, b1, b2);
  // Rows (b1, b2, g): an orthonormal, right-handed basis (b1 x b2 = g), so the matrix is a
  // rotation and it maps g onto e_z.
  Eigen::Matrix3d wRs;
  wRs.row(0) = b1.transpose();
  wRs.row(1) = b2.transpose();
  wRs.row(2) = g.transpose();
  return wRs;
}
} // namespace vpGravitySolvers
