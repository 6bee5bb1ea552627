/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/laser_conic/vpLaserConicGridCalibration.h>

#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpRotationVector.h>
#include <visp3/core/vpThetaUVector.h>

#include "laser_value_check.h"

vpLaserConicGridCalibration::vpLaserConicGridCalibration()
  : m_cam(), m_hasCam(false), m_squaresX(0), m_squaresY(0), m_squareSize(0.0), m_margin(0.5), m_maxReprojection(1.0),
    m_cornerClearance(8.0), m_laserClearancePoints(nullptr), m_detector(), m_calibration(), m_viewStatus(),
    m_gridPoses(), m_reprojection(), m_corners(), m_laserPoints(), m_viewImage()
{
}

void vpLaserConicGridCalibration::setCameraParameters(const vpCameraParameters &cam)
{
  m_calibration.setCameraParameters(cam); // validates
  m_cam = cam;
  m_hasCam = true;
}

void vpLaserConicGridCalibration::setChessboard(unsigned int squaresX, unsigned int squaresY, double squareSize)
{
  vsp::laser_value_check::require(squaresX >= 3 && squaresY >= 3 && std::isfinite(squareSize) && squareSize > 0.0,
                                  "vpLaserConicGridCalibration: the chessboard needs at least 3 x 3 squares of a "
                                  "positive, finite size");
  m_squaresX = squaresX;
  m_squaresY = squaresY;
  m_squareSize = squareSize;
}

void vpLaserConicGridCalibration::setGridMargin(double squares)
{
  vsp::laser_value_check::requireNonNegative(squares,
                                             "vpLaserConicGridCalibration: the grid margin must be finite and >= 0");
  m_margin = squares;
}

void vpLaserConicGridCalibration::setCornerClearance(double pixels)
{
  vsp::laser_value_check::requireNonNegative(pixels, "vpLaserConicGridCalibration: the corner clearance must be finite "
                                                     "and >= 0");
  m_cornerClearance = pixels;
}

void vpLaserConicGridCalibration::setMaxReprojectionError(double pixels)
{
  vsp::laser_value_check::requirePositive(pixels, "vpLaserConicGridCalibration: the largest reprojection error must be "
                                                  "positive");
  m_maxReprojection = pixels;
}

std::string vpLaserConicGridCalibration::getViewStatusMessage(vpGridViewStatus status)
{
  switch (status) {
  case VIEW_OK:
    return "view used";
  case VIEW_NO_GRID:
    return "chessboard not found";
  case VIEW_BAD_GRID_POSE:
    return "chessboard corners inconsistent with a planar grid (reprojection error too large)";
  case VIEW_FEW_LASER_POINTS:
    return "fewer than 5 laser points on the chessboard";
  case VIEW_FEW_GRID_CORNERS:
    return "chessboard found, but fewer than 6 corners clear of the laser trace (see setCornerClearance())";
  }
  return "unknown view status";
}

void vpLaserConicGridCalibration::checkReady(const vpImage<vpRGBa> &I) const
{
  if (!m_hasCam)
    throw vpLaserConicException(vpLaserConicException::badCameraError,
                                "vpLaserConicGridCalibration: call setCameraParameters() first");
  if (m_squaresX == 0)
    throw vpLaserConicException(vpLaserConicException::badValueError,
                                "vpLaserConicGridCalibration: call setChessboard() first");
  if (I.getWidth() == 0 || I.getHeight() == 0)
    throw vpLaserConicException(vpLaserConicException::badValueError, "vpLaserConicGridCalibration: empty image");
}

bool vpLaserConicGridCalibration::detectGrid(const vpImage<vpRGBa> &I, vpHomogeneousMatrix &cMg,
                                             std::vector<vpImagePoint> &corners, double &rmsPixels)
{
  return findGrid(I, cMg, corners, rmsPixels) == VIEW_OK;
}

vpLaserConicGridCalibration::vpGridViewStatus vpLaserConicGridCalibration::findGrid(const vpImage<vpRGBa> &I,
                                                                                    vpHomogeneousMatrix &cMg,
                                                                                    std::vector<vpImagePoint> &corners,
                                                                                    double &rmsPixels)
{
  checkReady(I);
  // Green channel: the red stripe adds little to it (except where it saturates to white).
  cv::Mat green(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1);
  for (unsigned int r = 0; r < I.getHeight(); ++r)
    for (unsigned int c = 0; c < I.getWidth(); ++c)
      green.at<unsigned char>(static_cast<int>(r), static_cast<int>(c)) = I[r][c].G;
  const cv::Size pattern(static_cast<int>(m_squaresX) - 1, static_cast<int>(m_squaresY) - 1);
  // The default search first; the exhaustive one (several times slower: seconds per view) only for a view
  // where the default does not find the whole board. Both refine the corners alike (CALIB_CB_ACCURACY).
  std::vector<cv::Point2f> found;
  const int flags = cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY;
  auto wholeBoard = [&](int extraFlags) {
    return cv::findChessboardCornersSB(green, pattern, found, flags | extraFlags) &&
           found.size() == static_cast<size_t>(pattern.area());
  };
  if (!wholeBoard(0) && !wholeBoard(cv::CALIB_CB_EXHAUSTIVE))
    return VIEW_NO_GRID;

  // Undistorted normalized coordinates with ViSP's model, then a pinhole PnP with identity intrinsics.
  // Corners next to the laser trace are left out of the pose: a stripe crossing a corner, above all
  // with a white saturated core, moves it by pixels.
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> normalized;
  corners.clear();
  const double clearance2 = m_cornerClearance * m_cornerClearance;
  for (int l = 0; l < pattern.height; ++l)
    for (int k = 0; k < pattern.width; ++k) {
      const cv::Point2f &p = found[static_cast<size_t>(l) * pattern.width + k];
      corners.push_back(vpImagePoint(p.y, p.x));
      bool nearLaser = false;
      if (m_laserClearancePoints != nullptr)
        for (const vpImagePoint &q : *m_laserClearancePoints)
          if (vpImagePoint::sqrDistance(q, corners.back()) < clearance2) {
            nearLaser = true;
            break;
          }
      if (nearLaser)
        continue;
      double x = 0.0, y = 0.0;
      vpPixelMeterConversion::convertPoint(m_cam, static_cast<double>(p.x), static_cast<double>(p.y), x, y);
      normalized.push_back(cv::Point2d(x, y));
      object.push_back(cv::Point3d((k + 1) * m_squareSize, (l + 1) * m_squareSize, 0.0));
    }
  if (object.size() < 6)
    return VIEW_FEW_GRID_CORNERS; // the trace hides nearly the whole board
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F), noDistortion;
  cv::Mat rvec, tvec;
  if (!cv::solvePnP(object, normalized, K, noDistortion, rvec, tvec, false, cv::SOLVEPNP_IPPE))
    return VIEW_BAD_GRID_POSE;
  cv::solvePnPRefineLM(object, normalized, K, noDistortion, rvec, tvec);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, rvec, tvec, K, noDistortion, projected);
  double sum2 = 0.0;
  for (size_t i = 0; i < projected.size(); ++i) {
    const double du = (projected[i].x - normalized[i].x) * m_cam.get_px();
    const double dv = (projected[i].y - normalized[i].y) * m_cam.get_py();
    sum2 += du * du + dv * dv;
  }
  rmsPixels = std::sqrt(sum2 / static_cast<double>(projected.size()));
  cMg.buildFrom(vpTranslationVector(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)),
                vpThetaUVector(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2)));
  return VIEW_OK;
}

std::vector<vpImagePoint> vpLaserConicGridCalibration::pointsOnGrid(const vpHomogeneousMatrix &cMg,
                                                                    const std::vector<vpImagePoint> &laserPoints) const
{
  const vpHomogeneousMatrix gMc = cMg.inverse();
  const double lo = m_squareSize * (1.0 - m_margin);
  const double hiX = m_squareSize * (m_squaresX - 1.0 + m_margin), hiY = m_squareSize * (m_squaresY - 1.0 + m_margin);
  // The ray of pixel (x, y, 1) in the grid frame: origin gMc t, direction gRc (x, y, 1); it meets Z = 0 at
  // origin - (origin_z / direction_z) direction.
  std::vector<vpImagePoint> kept;
  for (const vpImagePoint &p : laserPoints) {
    double x = 0.0, y = 0.0;
    vpPixelMeterConversion::convertPoint(m_cam, p, x, y);
    double d[3];
    for (unsigned int i = 0; i < 3; ++i)
      d[i] = gMc[i][0] * x + gMc[i][1] * y + gMc[i][2];
    const double lambda = -gMc[2][3] / d[2];
    if (!(lambda > 0.0) || !std::isfinite(lambda))
      continue;
    const double X = gMc[0][3] + lambda * d[0], Y = gMc[1][3] + lambda * d[1];
    if (X >= lo && X <= hiX && Y >= lo && Y <= hiY)
      kept.push_back(p);
  }
  return kept;
}

vpLaserConicGridCalibration::vpGridViewStatus vpLaserConicGridCalibration::addImage(const vpImage<vpRGBa> &I)
{
  checkReady(I);
  vpHomogeneousMatrix cMg;
  std::vector<vpImagePoint> corners, onGrid;
  double rms = 0.0;
  vpGridViewStatus status = VIEW_OK;
  const std::vector<vpImagePoint> laserPoints = m_detector.detect(I);
  m_laserClearancePoints = &laserPoints;
  status = findGrid(I, cMg, corners, rms);
  m_laserClearancePoints = nullptr;
  if (status != VIEW_OK) {
    cMg = vpHomogeneousMatrix();
  } else if (!(rms <= m_maxReprojection)) {
    status = VIEW_BAD_GRID_POSE;
  } else {
    onGrid = pointsOnGrid(cMg, laserPoints);
    if (onGrid.size() < 5)
      status = VIEW_FEW_LASER_POINTS;
  }
  if (status == VIEW_OK) {
    m_calibration.addView(cMg, onGrid);
    m_viewImage.push_back(static_cast<unsigned int>(m_viewStatus.size()));
  }
  m_viewStatus.push_back(status);
  m_gridPoses.push_back(cMg);
  m_reprojection.push_back(rms);
  m_corners.push_back(corners);
  m_laserPoints.push_back(onGrid);
  return status;
}
