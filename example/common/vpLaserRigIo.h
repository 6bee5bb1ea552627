/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserRigIo.h
  \brief Reading and writing the files of a camera/circular-laser dataset (laser calibration, ground
  truth, camera intrinsics), shared by the laser example programs.

  A dataset directory (e.g. data/laser_sequence) holds:
  - \c camera.xml : intrinsics in vpXmlParserCamera format, camera name "Camera", perspective
    projection without distortion;
  - \c laser.txt : laser calibration, see readLaserCalibration();
  - \c groundtruth.csv : one row per frame, see readGroundTruth();
  - \c images/ : the colour images named in groundtruth.csv (paths relative to the directory).

  Every reader returns false with a one-line explanation in \e error instead of throwing, so that a
  program can print it and exit cleanly.

  \code
  vpLaserDataset dataset;
  std::string error;
  if (!vpLaserRigIo::readDataset("data/laser_sequence", dataset, error)) {
    std::cerr << error << std::endl;
    return EXIT_FAILURE;
  }
  for (const vpLaserGroundTruthFrame &frame : dataset.frames) {
    vpImage<vpRGBa> I;
    vpImageIo::read(I, dataset.imagePath(frame));
    // ... frame.altitude, frame.roll, frame.pitch, frame.plane are the ground truth
  }
  \endcode
*/
#ifndef VP_LASER_RIG_IO_H
#define VP_LASER_RIG_IO_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPlane.h>

/*!
  \brief Ground truth of one frame of a laser dataset (one row of groundtruth.csv).

  Angles follow vpLaserConicPose: with g the downward unit normal of the ground in the camera frame,
  g = Rx(roll) Ry(pitch) (0, 0, 1)^T. The plane has a unit normal pointing from the ground towards
  the camera, so its D coefficient is the altitude.
*/
struct vpLaserGroundTruthFrame
{
  unsigned int frame = 0; //!< frame index
  std::string image;      //!< image file, relative to the dataset directory
  double altitude = 0.0;  //!< altitude of the camera centre over the ground, metres
  double roll = 0.0;      //!< roll, radians
  double pitch = 0.0;     //!< pitch, radians
  vpPlane plane;          //!< ground plane in the camera frame (nx, ny, nz, d)
};

/*!
  \brief Everything a laser dataset directory holds except the images themselves.
*/
struct vpLaserDataset
{
  std::string directory;                        //!< the dataset directory
  vpCameraParameters cam;                       //!< intrinsics (no distortion)
  unsigned int width = 0;                       //!< image width, pixels
  unsigned int height = 0;                      //!< image height, pixels
  double openingAngle = 0.0;                    //!< full opening angle of the laser, radians
  vpHomogeneousMatrix cMl;                      //!< laser frame (apex, axis +Z) in the camera frame
  std::vector<vpLaserGroundTruthFrame> frames;  //!< ground truth, one entry per image

  //! Full path of the image of \e frame.
  std::string imagePath(const vpLaserGroundTruthFrame &frame) const { return directory + "/" + frame.image; }
};

/*!
  \brief Static readers and writers of the laser dataset files.
*/
class vpLaserRigIo
{
public:
  /*!
    Reads a laser calibration file:
    \verbatim
    # laser calibration: full opening angle and pose of the laser frame in the camera frame
    opening_angle_deg 34
    cMl
    r11 r12 r13 tx
    r21 r22 r23 ty
    r31 r32 r33 tz
    0 0 0 1
    \endverbatim
    Lines starting with '#' and blank lines are ignored. The rotation must be orthonormal (1e-6) and
    the translation in metres.
    \param file : path of the file.
    \param openingAngleRad : full opening angle, radians (in (0, pi)).
    \param cMl : pose of the laser frame in the camera frame.
    \param error : why reading failed (missing file, bad keyword, bad number, not a rotation...).
    \return true on success; the outputs are untouched on failure.
  */
  static bool readLaserCalibration(const std::string &file, double &openingAngleRad, vpHomogeneousMatrix &cMl,
                                   std::string &error);
  //! Writes a laser calibration file in the format of readLaserCalibration(). \return false with \e error when it cannot be written.
  static bool writeLaserCalibration(const std::string &file, double openingAngleRad, const vpHomogeneousMatrix &cMl,
                                    std::string &error);

  /*!
    Reads groundtruth.csv: a header line
    \verbatim
    frame,image,altitude_m,roll_rad,pitch_rad,nx,ny,nz,d
    \endverbatim
    then one row per frame with these nine fields.
    \return false with \e error on a missing file, a wrong header or a malformed row (its line is named).
  */
  static bool readGroundTruth(const std::string &file, std::vector<vpLaserGroundTruthFrame> &frames,
                              std::string &error);
  //! Writes groundtruth.csv in the format of readGroundTruth() (17 significant digits). \return false with \e error on failure.
  static bool writeGroundTruth(const std::string &file, const std::vector<vpLaserGroundTruthFrame> &frames,
                               std::string &error);

  /*!
    Reads the camera \e name from a vpXmlParserCamera file: the perspective projection with distortion
    (kud, kdu) when the file has it, else the one without; \e width and \e height are 0 when the file
    gives no image size.
    \return false with \e error (naming the file) when the file is missing or not a vpXmlParserCamera
    file, the camera is not in it, or its focal lengths are not positive.
  */
  static bool readCamera(const std::string &file, const std::string &name, vpCameraParameters &cam,
                         unsigned int &width, unsigned int &height, std::string &error);
  //! Writes the camera (its projection model, with distortion or not) as "Camera" in vpXmlParserCamera format.
  //! \return false with \e error on failure.
  static bool writeCamera(const std::string &file, const vpCameraParameters &cam, unsigned int width,
                          unsigned int height, std::string &error);

  /*!
    Reads camera.xml, laser.txt and groundtruth.csv of \e directory.
    \return false with \e error naming the file at fault.
  */
  static bool readDataset(const std::string &directory, vpLaserDataset &dataset, std::string &error);
};

#endif
