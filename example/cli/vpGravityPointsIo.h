/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpGravityPointsIo.h
  \brief Reading and writing the per-frame 2D/3D points and gravity vectors of a gravity-aided
  pose sequence (the input of vsp-gravity-pose and of the demo), and the pose CSV files.

  Points file (CSV, '#' starts a comment line, blank lines are ignored, an optional header line
  starts with "frame,"). Every row starts with the frame index and a kind:
  \verbatim
  frame,gravity,gcx,gcy,gcz,gox,goy,goz     one per frame: gravity measured in the camera and in the object frame
  frame,point,oX,oY,oZ,x,y                  one per point: object coordinates (metres), normalized image coordinates
  \endverbatim
  Normalized coordinates are \f$ x = (u - u_0)/p_x \f$, \f$ y = (v - v_0)/p_y \f$ (see
  vpPixelMeterConversion); gravity vectors may have any positive norm. Rows of a frame may be in
  any order and frames need not be contiguous; frames are returned by increasing index.

  Pose file (CSV with header): \verbatim frame,status,tx,ty,tz,tux,tuy,tuz \endverbatim
  the pose cMo as translation (metres) and theta-u rotation vector (radians); status is "ok" or a
  word saying why there is no pose (then the numbers are "nan").
*/
#ifndef VP_GRAVITY_POINTS_IO_H
#define VP_GRAVITY_POINTS_IO_H

#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>

/*!
  \brief The measurements of one frame: both gravity vectors and the 2D/3D point correspondences.
*/
struct vpGravityFrame
{
  unsigned int frame = 0;      //!< frame index
  vpColVector gCam;            //!< gravity in the camera frame (3-vector)
  vpColVector gObj;            //!< gravity in the object frame (3-vector)
  std::vector<vpPoint> points; //!< points with oX, oY, oZ and x, y set
  unsigned int firstLine = 0;  //!< line of the file where the frame first appears (for messages)
};

/*!
  \brief One row of a pose file.
*/
struct vpPoseRow
{
  unsigned int frame = 0;    //!< frame index
  std::string status = "ok"; //!< "ok" or why there is no pose
  vpHomogeneousMatrix cMo;   //!< the pose when status is "ok"
};

/*!
  \brief Static readers and writers of the gravity-aided pose files (format in the file documentation).
*/
class vpGravityPointsIo
{
public:
  /*!
    Reads a points file.
    \return false with \e error naming the file and line on: missing file, unknown kind, wrong column
    count, a field that is not a number, a frame without or with two gravity rows, no frame at all.
  */
  static bool readPoints(const std::string &file, std::vector<vpGravityFrame> &frames, std::string &error);
  /*!
    The same; with \e requireGravity false a frame may have no gravity row (its gravity then comes
    from IMU streams, see vsp-gravity-pose --camera-imu), and gCam, gObj stay empty.
  */
  static bool readPoints(const std::string &file, std::vector<vpGravityFrame> &frames, std::string &error,
                         bool requireGravity);
  /*!
    Reads a frame times file: CSV rows \verbatim frame,timestamp \endverbatim (optional header line
    starting with "frame,", '#' comments), the exposure time of each frame in the unit of the IMU
    stream's timestamps.
    \return false with \e error naming the file and line on a malformed row or a repeated frame.
  */
  static bool readFrameTimes(const std::string &file, std::map<unsigned int, double> &times, std::string &error);
  //! Writes a points file (with a header line and a comment saying the format). \return false with \e error on failure.
  static bool writePoints(const std::string &file, const std::vector<vpGravityFrame> &frames, std::string &error);

  /*!
    Reads a pose file with the header "frame,status,tx,ty,tz,tux,tuy,tuz".
    \return false with \e error naming the file and line on a malformed row.
  */
  static bool readPoses(const std::string &file, std::vector<vpPoseRow> &poses, std::string &error);
  //! Writes a pose file. \return false with \e error on failure.
  static bool writePoses(const std::string &file, const std::vector<vpPoseRow> &poses, std::string &error);
};

#endif
