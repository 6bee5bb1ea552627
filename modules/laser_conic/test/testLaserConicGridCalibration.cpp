/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpLaserConicGridCalibration on chessboards rendered by vpLaserConicSimulator (distorted lens,
// saturating stripe): grid pose against the rendering's, corners with and without the laser, the board
// area filter, the view statuses and the input checks. The whole chain (images -> calibration within
// 1 mm / 0.1 deg) is the ctest case cli_laser_calibrate_accuracy.
#include <visp3/laser_conic/vpLaserConicGridCalibration.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>

#include "laser_test_utils.h"

namespace
{
const unsigned int kWidth = 1280, kHeight = 960, kSquaresX = 12, kSquaresY = 9;
const double kSquare = 0.05;

vpCameraParameters distortedCamera()
{
  return vpLaserConicSimulator::fitInverseDistortion(vpCameraParameters(1000.0, 1000.0, 643.0, 478.0, 0.0, 0.04),
                                                     kWidth, kHeight);
}

// The board centre at distance d in front of the camera, tilted by (rx, ry) degrees and spun by rz.
vpHomogeneousMatrix boardPose(double d, double rx, double ry, double rz)
{
  const vpHomogeneousMatrix centre(0.5 * kSquaresX * kSquare, 0.5 * kSquaresY * kSquare, 0, 0, 0, 0);
  return vpHomogeneousMatrix(0.05, 0.0, d, vpMath::rad(rx), vpMath::rad(ry), vpMath::rad(rz)) * centre.inverse();
}

vpImage<vpRGBa> renderBoard(const vpCameraParameters &cam, const vpHomogeneousMatrix &cMg, bool laserOn,
                            bool chessboard = true)
{
  vpLaserConicSimulator sim;
  sim.setCamera(cam, kWidth, kHeight);
  sim.setLaser(vpMath::rad(34.0), vpHomogeneousMatrix(0.10, 0.02, -0.01, vpMath::rad(3.0), vpMath::rad(-5.0), 0.0));
  if (chessboard)
    sim.setGroundChessboard(kSquaresX, kSquaresY, kSquare);
  sim.setGroundPose(cMg);
  sim.setSeed(4);
  vpLaserConicSimulator::vpRenderSettings settings;
  settings.laserOn = laserOn;
  settings.laserPower = 400.0;
  settings.whiteCore = 0.6;
  vpImage<vpRGBa> I;
  sim.render(I, settings);
  return I;
}

vpLaserConicGridCalibration makeGrid(const vpCameraParameters &cam)
{
  vpLaserConicGridCalibration grid;
  grid.setCameraParameters(cam);
  grid.setChessboard(kSquaresX, kSquaresY, kSquare);
  return grid;
}

// Angle (deg) between the grid planes' normals and difference (mm) of their distances to the camera centre.
void planeErrors(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &angleDeg, double &distanceMm)
{
  const double dot = a[0][2] * b[0][2] + a[1][2] * b[1][2] + a[2][2] * b[2][2];
  angleDeg = vpMath::deg(std::acos(std::min(1.0, std::fabs(dot))));
  const double da = a[0][2] * a[0][3] + a[1][2] * a[1][3] + a[2][2] * a[2][3];
  const double db = b[0][2] * b[0][3] + b[1][2] * b[1][3] + b[2][2] * b[2][3];
  distanceMm = 1000.0 * std::fabs(std::fabs(da) - std::fabs(db));
}
} // namespace

TEST(LaserConicGridCalibration, GridPoseMatchesTheRenderingWithTheCornersUnderTheLaserLeftOut)
{
  const vpCameraParameters cam = distortedCamera();
  vpLaserConicGridCalibration grid = makeGrid(cam), noClearance = makeGrid(cam);
  noClearance.setCornerClearance(0.0);
  const std::vector<vpHomogeneousMatrix> poses = {boardPose(0.6, 18, 0, -15), boardPose(0.8, 0, -18, 5),
                                                  boardPose(1.0, -12, 10, 20)};
  // The first board only under the sanitizers (OpenCV's corner search, not instrumented, is most of the time).
  for (const vpHomogeneousMatrix &truth : laser_test::trialsOf(poses, 1)) {
    const vpImage<vpRGBa> I = renderBoard(cam, truth, true);
    ASSERT_EQ(grid.addImage(I), vpLaserConicGridCalibration::VIEW_OK);
    ASSERT_EQ(noClearance.addImage(I), vpLaserConicGridCalibration::VIEW_OK);
    vpHomogeneousMatrix cMgNoLaser;
    std::vector<vpImagePoint> cornersNoLaser;
    double rmsNoLaser = 0.0;
    ASSERT_TRUE(grid.detectGrid(renderBoard(cam, truth, false), cMgNoLaser, cornersNoLaser, rmsNoLaser));
    const std::vector<vpImagePoint> &corners = grid.getCorners().back();
    ASSERT_EQ(corners.size(), static_cast<size_t>((kSquaresX - 1) * (kSquaresY - 1)));
    ASSERT_EQ(corners.size(), cornersNoLaser.size());
    double maxShift = 0.0;
    for (size_t i = 0; i < corners.size(); ++i)
      maxShift = std::max(maxShift, vpImagePoint::distance(corners[i], cornersNoLaser[i]));
    double angle = 0.0, distance = 0.0, angleAll = 0.0, distanceAll = 0.0, angleNoLaser = 0.0, distanceNoLaser = 0.0;
    planeErrors(grid.getGridPoses().back(), truth, angle, distance);
    planeErrors(noClearance.getGridPoses().back(), truth, angleAll, distanceAll);
    planeErrors(cMgNoLaser, truth, angleNoLaser, distanceNoLaser);
    std::cout << "grid " << truth[2][3] << " m: plane " << angle << " deg, " << distance
              << " mm off (all corners: " << angleAll << " deg, " << distanceAll << " mm; no laser: " << angleNoLaser
              << " deg, " << distanceNoLaser << " mm), corner RMS " << grid.getReprojectionErrors().back()
              << " px, largest corner shift by the laser " << maxShift << " px" << std::endl;
    EXPECT_GT(maxShift, 0.5); // the stripe does move the corners it crosses
    EXPECT_LT(angle, 0.1);
    EXPECT_LT(distance, 0.5);
    EXPECT_LT(grid.getReprojectionErrors().back(), 1.0);
  }
}

TEST(LaserConicGridCalibration, KeepsOnlyTheLaserPointsOnTheBoard)
{
  // Exact projections (no distortion) of grid points on a lattice around the board.
  const vpCameraParameters cam(1000.0, 1000.0, 640.0, 480.0);
  vpLaserConicGridCalibration grid = makeGrid(cam);
  grid.setGridMargin(0.5);
  const vpHomogeneousMatrix cMg = boardPose(0.9, 10, -8, 0);
  std::vector<vpImagePoint> points;
  unsigned int expected = 0;
  for (double X = -0.1; X <= 0.7; X += 0.0123)
    for (double Y = -0.1; Y <= 0.55; Y += 0.0123) {
      double P[3];
      for (unsigned int i = 0; i < 3; ++i)
        P[i] = cMg[i][0] * X + cMg[i][1] * Y + cMg[i][3];
      vpImagePoint ip;
      vpMeterPixelConversion::convertPoint(cam, P[0] / P[2], P[1] / P[2], ip);
      points.push_back(ip);
      const double lo = 0.5 * kSquare, hiX = (kSquaresX - 0.5) * kSquare, hiY = (kSquaresY - 0.5) * kSquare;
      expected += (X >= lo && X <= hiX && Y >= lo && Y <= hiY) ? 1u : 0u;
    }
  const std::vector<vpImagePoint> kept = grid.pointsOnGrid(cMg, points);
  EXPECT_EQ(kept.size(), expected);
  EXPECT_GT(expected, 100u);
  EXPECT_LT(expected, points.size() - 100);
}

TEST(LaserConicGridCalibration, ReportsEachImage)
{
  const vpCameraParameters cam = distortedCamera();
  vpLaserConicGridCalibration grid = makeGrid(cam);
  const vpHomogeneousMatrix cMg = boardPose(0.8, 10, 5, 0);
  EXPECT_EQ(grid.addImage(renderBoard(cam, cMg, true)), vpLaserConicGridCalibration::VIEW_OK);
  EXPECT_EQ(grid.addImage(renderBoard(cam, cMg, true, false)), vpLaserConicGridCalibration::VIEW_NO_GRID);
  EXPECT_EQ(grid.addImage(renderBoard(cam, cMg, false)), vpLaserConicGridCalibration::VIEW_FEW_LASER_POINTS);
  grid.setMaxReprojectionError(1e-3);
  EXPECT_EQ(grid.addImage(renderBoard(cam, cMg, true)), vpLaserConicGridCalibration::VIEW_BAD_GRID_POSE);
  // Found, but every corner within the clearance of the trace: not "chessboard not found".
  grid.setCornerClearance(5000.0);
  EXPECT_EQ(grid.addImage(renderBoard(cam, cMg, true)), vpLaserConicGridCalibration::VIEW_FEW_GRID_CORNERS);
  EXPECT_EQ(grid.getCorners().back().size(), (kSquaresX - 1u) * (kSquaresY - 1u));
  ASSERT_EQ(grid.getViewStatus().size(), 5u);
  EXPECT_EQ(grid.getCalibration().getNbViews(), 1u); // only the first image was usable
  ASSERT_EQ(grid.getViewImageIndex().size(), 1u);
  EXPECT_EQ(grid.getViewImageIndex()[0], 0u);
  EXPECT_GT(grid.getLaserPoints()[0].size(), 300u);
  EXPECT_FALSE(vpLaserConicGridCalibration::getViewStatusMessage(vpLaserConicGridCalibration::VIEW_NO_GRID).empty());
}

TEST(LaserConicGridCalibration, BadInputThrows)
{
  vpLaserConicGridCalibration grid;
  const vpImage<vpRGBa> I(10, 10);
  EXPECT_THROW(grid.addImage(I), vpLaserConicException); // no camera
  EXPECT_THROW(grid.setCameraParameters(vpCameraParameters(-1.0, 1000, 640, 480)), vpLaserConicException);
  grid.setCameraParameters(vpCameraParameters(1000, 1000, 640, 480));
  EXPECT_THROW(grid.addImage(I), vpLaserConicException); // no chessboard
  EXPECT_THROW(grid.setChessboard(2, 9, 0.05), vpLaserConicException);
  EXPECT_THROW(grid.setChessboard(12, 9, -0.05), vpLaserConicException);
  EXPECT_THROW(grid.setChessboard(12, 9, std::numeric_limits<double>::quiet_NaN()), vpLaserConicException);
  grid.setChessboard(12, 9, 0.05);
  EXPECT_THROW(grid.addImage(vpImage<vpRGBa>()), vpLaserConicException);
  EXPECT_THROW(grid.setGridMargin(-1.0), vpLaserConicException);
  EXPECT_THROW(grid.setMaxReprojectionError(0.0), vpLaserConicException);
  EXPECT_EQ(grid.addImage(I), vpLaserConicGridCalibration::VIEW_NO_GRID); // tiny blank image: no board, no crash
}
