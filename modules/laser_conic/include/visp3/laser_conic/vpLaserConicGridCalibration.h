/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicGridCalibration.h
  \brief Laser/camera calibration from colour images of a chessboard crossed by the laser trace.
*/
#ifndef VP_LASER_CONIC_GRID_CALIBRATION_H
#define VP_LASER_CONIC_GRID_CALIBRATION_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicCalibration.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicException.h>

/*!
  \ingroup group_laser_conic
  \brief From colour images of a planar chessboard with the laser trace on it to the laser calibration.

  For each image addImage():
  -# finds the inner corners of the chessboard with OpenCV's cv::findChessboardCornersSB() on the green
     channel (the red laser barely lights it, so the stripe crossing a black square does not shift the
     corners): its default search first, the exhaustive one (several times slower) when that does not
     find the whole board;
  -# detects the laser trace with getDetector() and leaves out the corners closer than setCornerClearance()
     to it (a stripe across a corner moves it);
  -# converts the other corners to normalized coordinates with vpPixelMeterConversion (the camera's ViSP distortion
     model, \f$ k_{du} \f$) and computes the grid pose cMg with cv::solvePnP() (IPPE, identity intrinsics,
     no distortion) refined by Levenberg-Marquardt; a view whose corner reprojection RMS exceeds
     setMaxReprojectionError() is refused;
  -# keeps the laser points whose back-projection on the grid plane lies on the board: within setGridMargin() squares of the rectangle of the inner corners (points
     on the background or the table would be outliers);
  -# adds the view (cMg, points) to getCalibration().

  Then getCalibration().compute(cMl) estimates the laser (see vpLaserConicCalibration: robust loss,
  opening angle, observability check, standard deviations).

  Grid frame: the board has \e squaresX by \e squaresY squares of side s; its inner corners are the grid
  points (k s, l s, 0), k = 1..squaresX-1, l = 1..squaresY-1 (as vpLaserConicSimulator::setGroundChessboard()).
  The detector may number the corners from either end of the board: the grid frame is then rotated in its
  plane, which changes cMg but not the plane, and so not the calibration.

  \code
  vpLaserConicGridCalibration grid;
  grid.setCameraParameters(cam);                 // from the camera XML, with distortion
  grid.setChessboard(9, 7, 0.03);                // squares, square side in metres
  grid.getCalibration().setOpeningAngle(vpMath::rad(34));
  grid.getCalibration().setOpeningAngleEstimation(true);
  for (const vpImage<vpRGBa> &I : images)
    if (grid.addImage(I) != vpLaserConicGridCalibration::VIEW_OK)
      std::cerr << vpLaserConicGridCalibration::getViewStatusMessage(grid.getViewStatus().back()) << std::endl;
  vpHomogeneousMatrix cMl(0.1, 0, 0, 0, 0, 0);   // rough guess
  if (grid.getCalibration().compute(cMl)) { ... }
  \endcode
*/
class VISP_EXPORT vpLaserConicGridCalibration
{
public:
  //! Outcome of addImage() for one image.
  typedef enum {
    VIEW_OK,               //!< grid found, pose computed, laser points added to the calibration
    VIEW_NO_GRID,          //!< the chessboard was not found
    VIEW_BAD_GRID_POSE,    //!< the corner reprojection error exceeds setMaxReprojectionError()
    VIEW_FEW_LASER_POINTS, //!< fewer than 5 laser points on the board
    //! the chessboard was found, but fewer than 6 of its corners lie farther than setCornerClearance() from the
    //! laser trace: too few for its pose (a trace over most of the board, or a clearance too wide)
    VIEW_FEW_GRID_CORNERS
  } vpGridViewStatus;

  //! No camera, no chessboard; margin 0.5 square, reprojection error limit 1 px, corner clearance 8 px,
  //! default detector.
  vpLaserConicGridCalibration();

  /*!
    Camera intrinsics (also given to getCalibration()); the distortion of perspectiveProjWithDistortion
    is used through vpPixelMeterConversion.
    \exception vpLaserConicException::badCameraError as vpLaserConicPose::setCameraParameters(): on
    non-finite parameters (distortion coefficients included), non-positive focal lengths or a projection model
    other than the two perspective ones.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    The chessboard: \e squaresX by \e squaresY squares (both >= 3) of side \e squareSize metres.
    \exception vpLaserConicException::badValueError otherwise.
  */
  void setChessboard(unsigned int squaresX, unsigned int squaresY, double squareSize);
  /*!
    Laser points are kept when their grid coordinates are within \e squares squares of the rectangle of
    the inner corners (default 0.5; the board itself extends 1 square beyond it).
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setGridMargin(double squares);
  /*!
    In addImage(), corners closer than \e pixels to a detected laser point are left out of the grid pose
    (default 8): the stripe crossing a corner moves it by up to 2 px (measured on rendered boards with a
    saturated stripe), far more than the 0.05 px the pose needs.
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setCornerClearance(double pixels);
  /*!
    Largest RMS reprojection error of the corners (pixels, normalized residual times px) for a view to
    be used (default 1).
    \exception vpLaserConicException::badValueError when not positive.
  */
  void setMaxReprojectionError(double pixels);

  //! The laser trace detector (configure it before addImage()).
  vpLaserConicDetector &getDetector() { return m_detector; }
  //! The calibration the views are added to (set the opening angle, the options, then compute()).
  vpLaserConicCalibration &getCalibration() { return m_calibration; }
  //! \overload
  const vpLaserConicCalibration &getCalibration() const { return m_calibration; }

  /*!
    Processes one image (see the class description); the view is added to getCalibration() only when
    VIEW_OK is returned. Every call appends one entry to the per-image results below.
    \exception vpLaserConicException when the camera or the chessboard is unset, or the image is empty.
  */
  vpGridViewStatus addImage(const vpImage<vpRGBa> &I);
  /*!
    Detects the chessboard and computes its pose from all its corners, without touching the calibration
    (addImage() leaves out the corners near the laser trace).
    \param I : colour image.
    \param cMg : grid pose (grid frame of the class description).
    \param corners : the inner corners found (pixels), row after row.
    \param rmsPixels : RMS reprojection error of the corners used.
    \return false when the chessboard is not found or no pose comes from its corners.
    \exception vpLaserConicException when the camera or the chessboard is unset, or the image is empty.
  */
  bool detectGrid(const vpImage<vpRGBa> &I, vpHomogeneousMatrix &cMg, std::vector<vpImagePoint> &corners,
                  double &rmsPixels);
  /*!
    The points of \e laserPoints whose back-projection on the grid plane of \e cMg lies within the board area
    (see setGridMargin()).
  */
  std::vector<vpImagePoint> pointsOnGrid(const vpHomogeneousMatrix &cMg,
                                         const std::vector<vpImagePoint> &laserPoints) const;

  //! One-line explanation of a view status.
  static std::string getViewStatusMessage(vpGridViewStatus status);
  //! Status of each image given to addImage(), in order.
  const std::vector<vpGridViewStatus> &getViewStatus() const { return m_viewStatus; }
  //! Grid pose of each image (identity when the grid was not found).
  const std::vector<vpHomogeneousMatrix> &getGridPoses() const { return m_gridPoses; }
  //! Corner reprojection RMS (pixels) of each image (0 when the grid was not found).
  const std::vector<double> &getReprojectionErrors() const { return m_reprojection; }
  //! Inner corners (pixels) found in each image.
  const std::vector<std::vector<vpImagePoint> > &getCorners() const { return m_corners; }
  //! Laser points kept on the board in each image.
  const std::vector<std::vector<vpImagePoint> > &getLaserPoints() const { return m_laserPoints; }
  //! Index in the images given to addImage() of each view of getCalibration().
  const std::vector<unsigned int> &getViewImageIndex() const { return m_viewImage; }

private:
  void checkReady(const vpImage<vpRGBa> &I) const;
  // detectGrid() with why it failed: VIEW_NO_GRID, VIEW_FEW_GRID_CORNERS (with the corners found) or
  // VIEW_BAD_GRID_POSE (no pose from them); VIEW_OK with the pose.
  vpGridViewStatus findGrid(const vpImage<vpRGBa> &I, vpHomogeneousMatrix &cMg, std::vector<vpImagePoint> &corners,
                            double &rmsPixels);

  vpCameraParameters m_cam;
  bool m_hasCam;
  unsigned int m_squaresX, m_squaresY;
  double m_squareSize, m_margin, m_maxReprojection, m_cornerClearance;
  //! Laser points of the image addImage() is processing (corners near them are left out), else null.
  const std::vector<vpImagePoint> *m_laserClearancePoints;
  vpLaserConicDetector m_detector;
  vpLaserConicCalibration m_calibration;
  std::vector<vpGridViewStatus> m_viewStatus;
  std::vector<vpHomogeneousMatrix> m_gridPoses;
  std::vector<double> m_reprojection;
  std::vector<std::vector<vpImagePoint> > m_corners, m_laserPoints;
  std::vector<unsigned int> m_viewImage;
};

#endif
