/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpImuGravity.h
  \brief From raw accelerometer readings to the gravity directions vpPoseGravity expects.
*/
#ifndef VP_IMU_GRAVITY_H
#define VP_IMU_GRAVITY_H

#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/pose_gravity/vpPoseGravityException.h>

/*!
  \ingroup group_pose_gravity
  \brief Gravity direction in a sensor frame from an IMU stream (or single readings).

  Physics: an accelerometer measures the specific force \f$ \mathbf{f} = \mathbf{a} - \mathbf{g} \f$
  in its own frame. At rest (\f$ \mathbf{a} = 0 \f$) it reads \f$ -\mathbf{g} \f$: a vector of norm
  about 9.81 m/s² pointing \b up. vpPoseGravity wants gravity pointing \b down in the frame of the
  sensor (camera or object), so the reading is negated and rotated by the IMU-to-sensor rotation
  \f$ {}^s\mathbf{R}_{imu} \f$: \f$ \mathbf{g}_s = -{}^s\mathbf{R}_{imu} \mathbf{f} / |\mathbf{f}| \f$.
  Under motion the reading is \f$ \mathbf{a} - \mathbf{g} \f$ and its direction is off by about
  \f$ |\mathbf{a}_\perp| / g \f$ rad; such readings are flagged when their norm differs from g by more
  than setNormTolerance() (an acceleration along gravity changes the norm, one across it tilts the
  direction and changes the norm at second order only, so the flag is necessary, not sufficient),
  or when the rotation rate exceeds setGyroTolerance().

  Timestamps: the stream is interpolated linearly at the requested times (e.g. the exposure times
  of the camera frames), after adding setTimeOffset() (IMU clock = sensor clock + offset).

  CSV stream (loadCsv()): one sample per line, `timestamp, wx, wy, wz, ax, ay, az` (gyro in rad/s,
  accelerometer in m/s², in the IMU frame): the layout of EuRoC `mav0/imu0/data.csv` and of Kalibr's
  `imu.csv`, timestamps in nanoseconds for both (loadCsv()'s default time scale 1e-9 gives seconds).
  Fields are separated by commas (an empty field is an error, not a skipped column). Lines starting with '#', a
  UTF-8 byte-order mark and a first line that does not start with a number (a header) are skipped.
  \code
  #timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]
  1403636579758555392,-0.0991,0.1473,0.0272,9.7318,0.2004,-1.2507
  \endcode

  \code
  vpImuGravity imu;
  imu.loadCsv("imu0/data.csv");                                  // EuRoC / Kalibr layout, ns
  imu.setImuToSensorRotation(vpImuGravity::loadRotation("cam_R_imu.txt"));
  vpColVector g_cam;
  bool moving = false;
  if (imu.gravityAt(frameTime, g_cam, moving) && !moving)
    pose.setCameraGravity(g_cam);                                 // down, camera frame
  \endcode
*/
class VISP_EXPORT vpImuGravity
{
public:
  //! Standard gravity, m/s².
  static constexpr double standardGravity() { return 9.80665; }

  //! An IMU stream without samples, identity IMU-to-sensor rotation, tolerances at their defaults.
  vpImuGravity();

  /*!
    Down gravity direction (unit) in the sensor frame from one accelerometer reading \e f (specific
    force, IMU frame, any unit): \f$ -{}^s\mathbf{R}_{imu} \mathbf{f} / |\mathbf{f}| \f$.
    \exception vpPoseGravityException::badGravityError on a zero, non-finite or non-3-vector reading,
    badParameterError when \e sRimu is not a rotation (see setImuToSensorRotation()).
  */
  static vpColVector gravityFromSpecificForce(const vpColVector &f, const vpRotationMatrix &sRimu = vpRotationMatrix());
  /*!
    True when the norm of the reading \e f (m/s²) is within \e tolerance of \e g: the IMU may be at
    rest (see the class description for what the test cannot see).
  */
  static bool isAtRest(const vpColVector &f, double tolerance = 0.5, double g = standardGravity());

  /*!
    Reads a 3x3 rotation from a text file: 9 numbers (row-major) or 16 (a 4x4 homogeneous matrix,
    as Kalibr's T_cam_imu; its rotation block is taken), separated by spaces, commas or new lines;
    a line starting with '#' is a comment. A matrix within 1e-3 of a rotation (a file's rounding) gives the
    rotation nearest to it (singular value decomposition), whatever its angle.
    \exception vpPoseGravityException::badFileError if unreadable, malformed or not a rotation.
  */
  static vpRotationMatrix loadRotation(const std::string &file);

  /*!
    IMU-to-sensor rotation \f$ {}^s\mathbf{R}_{imu} \f$ (maps IMU vectors into the sensor frame); default identity.
    \exception vpPoseGravityException::badParameterError when \e sRimu is not a rotation (R R^T off the identity
    by more than 1e-3, det < 0 or a coefficient not finite), as loadRotation() refuses it in a file.
  */
  void setImuToSensorRotation(const vpRotationMatrix &sRimu);
  //! Norm of gravity used by the motion flag, m/s²; default standardGravity(). Throws badParameterError unless > 0.
  void setGravityNorm(double g);
  //! Largest deviation of the reading's norm from the gravity norm at rest, m/s²; default 0.5. Throws badParameterError unless > 0.
  void setNormTolerance(double tolerance);
  //! Largest rotation rate at rest, rad/s; default infinity (not checked). Throws badParameterError unless > 0.
  void setGyroTolerance(double tolerance);
  //! Half-width (s) of the window around a requested time whose samples are all checked for motion; default 0 (the two bracketing samples).
  void setMotionWindow(double halfWidth);
  //! Offset such that IMU time = requested time + offset (s); default 0. Throws badParameterError unless finite.
  void setTimeOffset(double offset);

  /*!
    Appends a sample: time (s, strictly increasing), gyro (rad/s) and accelerometer (m/s²), IMU frame.
    \exception vpPoseGravityException::badParameterError on non-finite values, wrong sizes or a time
    not after the previous one.
  */
  void addSample(double t, const vpColVector &gyro, const vpColVector &acc);
  /*!
    Reads a CSV stream (format in the class description) and appends its samples; \e timeScale
    converts its timestamps to seconds (1e-9 for EuRoC / Kalibr nanoseconds, 1 for seconds).
    \exception vpPoseGravityException::badFileError naming the file and line on a read error, a
    wrong column count, a field that is not a number or timestamps not increasing; the stream is then
    left as it was before the call (none of the file's rows kept).
  */
  void loadCsv(const std::string &file, double timeScale = 1e-9);
  //! Removes all samples.
  void clear() { m_samples.clear(); }
  //! Number of samples.
  size_t size() const { return m_samples.size(); }

  /*!
    Down gravity (unit) in the sensor frame at time \e t: the specific force interpolated linearly
    between the two samples around t + offset, negated and rotated into the sensor frame.
    \param t : time (s) in the sensor's clock.
    \param g : receives the gravity direction.
    \param moving : receives true when a sample used (or in the motion window) fails the rest test.
    \return false, \e g untouched, when t + offset is outside the stream or the interpolated reading is zero.
  */
  bool gravityAt(double t, vpColVector &g, bool &moving) const;

private:
  struct Sample
  {
    double t;
    double w[3];
    double a[3];
  };
  bool atRest(const Sample &s) const;
  //! gravityFromSpecificForce() for a rotation already checked (the stream's, checked when set).
  static vpColVector downGravity(const vpColVector &f, const vpRotationMatrix &sRimu);
  //! The rows of an IMU CSV stream appended (loadCsv(), which restores the stream when this throws).
  void readCsvRows(std::istream &in, const std::string &file, double timeScale);

  std::vector<Sample> m_samples;
  vpRotationMatrix m_sRimu;
  double m_gravityNorm, m_normTolerance, m_gyroTolerance, m_motionWindow, m_timeOffset;
};

#endif
