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
    projection with or without distortion;
  - \c laser.yaml (or the older \c laser.txt) : laser calibration, see readLaserCalibration();
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
#include <visp3/core/vpColVector.h>
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
  std::string directory;                       //!< the dataset directory
  vpCameraParameters cam;                      //!< intrinsics (with distortion when camera.xml has it)
  unsigned int width = 0;                      //!< image width, pixels
  unsigned int height = 0;                     //!< image height, pixels
  double openingAngle = 0.0;                   //!< full opening angle of the laser, radians
  vpHomogeneousMatrix cMl;                     //!< laser frame (apex, axis +Z) in the camera frame
  std::vector<vpLaserGroundTruthFrame> frames; //!< ground truth, one entry per image

  //! Full path of the image of \e frame.
  std::string imagePath(const vpLaserGroundTruthFrame &frame) const { return directory + "/" + frame.image; }
};

/*!
  \brief A laser calibration as stored in a file: the cone and, when a calibration produced it, its
  uncertainty and residual.
*/
struct vpLaserCalibrationData
{
  double openingAngle = 0.0;     //!< full opening angle, radians
  vpHomogeneousMatrix cMl;       //!< laser frame (apex at the origin, cone axis +Z) in the camera frame
  bool hasStdDeviations = false; //!< true when the file gives the standard deviations below
  /*!
    Standard deviations in the order of vpLaserConicCalibration::getStdDeviations(): axis angles
    alpha, beta (rad), apex vx, vy, vz (m), opening angle (rad; 0 when it was not estimated).
  */
  vpColVector stdDeviations = vpColVector(6, 0.0);
  double rms = -1.0;        //!< RMS residual of the calibration on the grids, metres (-1: not given)
  unsigned int nbViews = 0; //!< grid views used (0: not given)
};

/*!
  \brief Static readers and writers of the laser dataset files.
*/
class vpLaserRigIo
{
public:
  /*!
    Reads a laser calibration file in either format:
    - the YAML format of writeLaserCalibrationYaml(): the pose cMl as a vpPoseVector saved with
      vpPoseVector::saveYAML() (rows: 6, cols: 1, data: tx, ty, tz in metres, then theta u in radians),
      preceded by the keys
      \verbatim
      opening_angle_deg: 34
      std_dev_axis_deg: [0.0032, 0.0033]         # alpha, beta (optional, with the three below)
      std_dev_apex_m: [4.4e-05, 4.5e-05, 1e-04]
      std_dev_opening_angle_deg: 0.0046          # 0 when the angle was not estimated
      rms_m: 0.000298                            # optional
      views: 9                                   # optional
      \endverbatim
      (the file is recognised by its "rows:" line);
    - the older text format (laser.txt):
      \verbatim
      # laser calibration: full opening angle and pose of the laser frame in the camera frame
      opening_angle_deg 34
      cMl
      r11 r12 r13 tx
      r21 r22 r23 ty
      r31 r32 r33 tz
      0 0 0 1
      \endverbatim
      Lines starting with '#' and blank lines are ignored. The rotation must be orthonormal (1e-6).
    \param file : path of the file.
    \param calibration : the calibration read; untouched on failure.
    \param error : why reading failed (missing file, bad keyword, bad number, not a rotation...).
    \return true on success.
  */
  static bool readLaserCalibration(const std::string &file, vpLaserCalibrationData &calibration, std::string &error);
  /*!
    Reads the opening angle (radians) and the pose cMl of a laser calibration file in either format (see
    the other overload). \return true on success; the outputs are untouched on failure.
  */
  static bool readLaserCalibration(const std::string &file, double &openingAngleRad, vpHomogeneousMatrix &cMl,
                                   std::string &error);
  /*!
    Writes a laser calibration in the YAML format read by readLaserCalibration(): the keys, then cMl
    written by vpPoseVector::saveYAML() (so vpPoseVector::loadYAML() reads the pose from it; ViSP writes it
    with 6 significant digits: a micrometre, a microradian). The standard deviations are written when
    \e calibration.hasStdDeviations. \return false with \e error when it cannot be written.
  */
  static bool writeLaserCalibrationYaml(const std::string &file, const vpLaserCalibrationData &calibration,
                                        std::string &error);
  //! Writes a laser calibration file in the older text format (17 significant digits). \return false with \e error when it cannot be written.
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
    file, the camera is not in it, one of its values (image size, px, py, u0, v0, kud, kdu) is not a number
    (ViSP's parser would read it as 0), or its focal lengths are not positive.
  */
  static bool readCamera(const std::string &file, const std::string &name, vpCameraParameters &cam, unsigned int &width,
                         unsigned int &height, std::string &error);
  //! Writes the camera (its projection model, with distortion or not) as "Camera" in vpXmlParserCamera format.
  //! \return false with \e error on failure.
  static bool writeCamera(const std::string &file, const vpCameraParameters &cam, unsigned int width,
                          unsigned int height, std::string &error);

  /*!
    Image files of a calibration or measurement session: the files of folder \e source with an image
    extension (.png .jpg .jpeg .ppm .pgm, any case) sorted by name when \e isList is false; otherwise the
    paths listed in the text file \e source, one a line ('#' comments and blank lines skipped), relative
    to the list's folder. \return false with \e error on a missing folder/list/image or an empty result.
  */
  static bool listImages(const std::string &source, bool isList, std::vector<std::string> &images, std::string &error);

  /*!
    Reads camera.xml, laser.yaml (laser.txt when there is no laser.yaml) and groundtruth.csv of \e directory.
    \return false with \e error naming the file at fault.
  */
  static bool readDataset(const std::string &directory, vpLaserDataset &dataset, std::string &error);
};

#endif
