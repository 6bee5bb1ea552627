/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicFilter.h
  \brief IMU-rate altitude, vertical speed, roll and pitch fusing an IMU stream with the laser planes.
*/
#ifndef VP_LASER_CONIC_FILTER_H
#define VP_LASER_CONIC_FILTER_H

#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/laser_conic/vpLaserConicException.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

/*!
  \ingroup group_laser_conic
  \brief Extended Kalman filter of the altitude, vertical speed, roll and pitch over the ground plane,
  propagated by every IMU sample and updated by each frame's vpLaserConicPose estimate and covariance.

  State (10): altitude h of the camera centre over the ground (m), vertical speed dh/dt (m/s), roll and
  pitch (rad, vpLaserConicPose's convention: the downward ground normal in the camera frame is
  \f$ R_x(\mathrm{roll}) R_y(\mathrm{pitch}) (0,0,1)^T \f$), the gyro bias (rad/s) and the accelerometer
  bias (m/s²), both in the camera frame. Kinematics: \f$ \dot{\mathbf{g}} = \mathbf{g} \times
  (\boldsymbol{\omega} - \mathbf{b}_g) \f$, \f$ \ddot h = -\mathbf{g}^T (\mathbf{f} - \mathbf{b}_a) - g_0 \f$.
  The gyro bias about the ground normal, and the accelerometer bias across it while the vehicle stays
  level, are not observable: their covariances keep their priors plus their random walks, and they do
  not affect the outputs until the vehicle tilts.

  IMU stream: the conventions of vpImuGravity (and its CSV layout, see loadImuCsv()): gyro in rad/s and
  specific force (\f$ \mathbf{a} - \mathbf{g} \f$, 9.81 m/s² up at rest) in m/s², both in the IMU frame,
  mapped into the camera frame by setImuToCameraRotation(); the IMU is taken at the camera centre (the
  lever-arm accelerations are neglected). Each sample propagates the state from the previous one with the
  mean of the two readings.

  Frames: addFrame() takes a frame's (altitude, roll, pitch) and its 3x3 covariance at the frame's
  exposure time, which may be up to setMaxLatency() older than the last IMU sample: the filter keeps the
  states of its recent samples, updates at the exposure time and re-propagates the newer samples (exact,
  no approximation of the delay). Each update is gated by the squared Mahalanobis distance of its
  innovation (setGateProbability()): a frame inconsistent with the prediction is rejected with
  FRAME_REJECTED, never averaged in (until setInitialisationFrames() frames have been accepted, such a frame
  starts the state again from itself instead, FRAME_INITIALISED: the first frame may be the wrong one).
  Several frames between the same two IMU samples (a camera faster than the IMU) are each applied in turn.
  Rejected frames whose attitude agrees with the prediction and whose altitudes agree with each other but
  jump from the prediction by more than setMinStepHeight() (a box, a table edge: a change of ground)
  re-initialise the altitude after setStepFrames() of them
  (FRAME_GROUND_STEP); a long run of rejected frames declares a divergence (setMaxRejections()).
  addMissingFrame() records
  a frame without a plane: the prediction runs on with its growing covariance.

  \code
  vpLaserConicFilter filter;
  filter.setImuToCameraRotation(cRimu);
  for (each event in time order) {
    if (imu sample)  filter.addImu(t, gyro, acc);                       // 200 Hz
    if (frame ready) {                                                   // 30 Hz, ~30 ms late
      if (estimator.computePlane(points, vpLaserConicPose::GP3, plane))  // with setCovarianceComputation(true)
        filter.addFrame(exposureTime, estimator);
      else
        filter.addMissingFrame(exposureTime);
    }
    control(filter.getAltitude(), filter.getVerticalSpeed(), filter.getRoll(), filter.getPitch());
  }
  \endcode
*/
class VISP_EXPORT vpLaserConicFilter
{
public:
  //! State of the outputs (getStatus()).
  typedef enum {
    STATUS_INITIALISING, //!< no frame accepted yet, or fewer than setInitialisationFrames()
    STATUS_TRACKING,     //!< frames accepted recently
    STATUS_PREDICTING,   //!< no frame accepted for setPredictionTimeout(): IMU prediction only
    STATUS_GROUND_STEP,  //!< the altitude was re-initialised on a change of ground, not confirmed yet
    STATUS_DIVERGED      //!< setMaxRejections() frames rejected in a row: re-initialised by the next frame
  } vpFilterStatus;

  //! Outcome of one addFrame() / addMissingFrame().
  typedef enum {
    FRAME_ACCEPTED,     //!< the frame updated the state
    FRAME_INITIALISED,  //!< the frame initialised (or re-initialised) the state
    FRAME_REJECTED,     //!< gated out: Mahalanobis distance above the gate (getLastMahalanobis())
    FRAME_GROUND_STEP,  //!< a change of ground: the altitude was re-initialised from the frame
    FRAME_MISSING,      //!< a frame without a plane (addMissingFrame())
    FRAME_TOO_OLD,      //!< older than setMaxLatency() or than the kept history
    FRAME_OUT_OF_ORDER, //!< older than a frame already used
    FRAME_AHEAD_OF_IMU, //!< after the last IMU sample: add the IMU samples first
    FRAME_BAD_INPUT     //!< a non-finite value, a time beyond 1e10 s, an altitude not positive, a roll or pitch
                        //!< outside (-pi/2, pi/2) (degrees given as radians, say), a covariance that is not
                        //!< symmetric positive definite, or a standard deviation outside [1e-12, 1e4] (m or rad)
  } vpFrameStatus;

  //! Outcome of one addImu().
  typedef enum {
    IMU_OK,             //!< the sample propagated the state
    IMU_NOT_INCREASING, //!< timestamp not at least a microsecond after the previous one (and not more than
                        //!< setMaxImuGap() before it): sample ignored
    IMU_GAP,            //!< more than setMaxImuGap() after the previous sample, or before it (the previous one
                        //!< stamped far ahead, or the clock reset): the filter restarts here
    IMU_NOT_FINITE,     //!< a non-finite value: sample ignored
    IMU_OUT_OF_RANGE    //!< a rate over 100 rad/s or a specific force over 10000 m/s² (beyond any IMU), or a time
                        //!< beyond 1e10 s (nanoseconds given as seconds?): sample ignored
  } vpImuStatus;

  //! The filter with the EuRoC ADIS16448 noise densities, a 0.1 s latency limit and a 99 % gate.
  vpLaserConicFilter();

  /*!
    IMU noise densities: gyro white noise (rad/s/sqrt(Hz)), gyro bias random walk (rad/s²/sqrt(Hz)),
    accelerometer white noise (m/s²/sqrt(Hz)) and bias random walk (m/s³/sqrt(Hz)); default those of
    the ADIS16448 of the EuRoC dataset: 1.7e-4, 1.9e-5, 2.0e-3, 3.0e-3.
    \exception vpLaserConicException::badValueError unless all are in (0, 1e3].
  */
  void setImuNoise(double gyro, double gyroBiasWalk, double acc, double accBiasWalk);
  /*!
    Initial standard deviations: vertical speed (m/s, default 0.5), gyro bias (rad/s, default 0.01),
    accelerometer bias (m/s², default 0.2). \exception vpLaserConicException::badValueError unless in (0, 1e3].
  */
  void setInitialUncertainty(double verticalSpeed, double gyroBias, double accBias);
  /*!
    IMU-to-camera rotation \f$ {}^c\mathbf{R}_{imu} \f$ (maps IMU vectors into the camera frame); default
    identity. \exception vpLaserConicException::badValueError unless orthogonal with determinant +1 (a mirrored
    axis, determinant -1, would turn the attitude against the gyros' rotation); the mounting set before is kept.
  */
  void setImuToCameraRotation(const vpRotationMatrix &cRimu);
  //! Gravity norm, m/s²; default 9.80665. \exception vpLaserConicException::badValueError unless in [0.1, 1e3].
  void setGravityNorm(double g);
  /*!
    Oldest frame accepted, in seconds before the last IMU sample (default 0.1), and the number of IMU
    samples kept to re-propagate (default 64: 63 intervals, enough for 0.1 s up to 630 Hz). Allocates the history
    (the only allocation: none per sample) and restarts the filter (the history and the state are forgotten).
    \exception vpLaserConicException::badValueError unless latency >= 0 and 2 <= samples <= 1e6 (over 16
    minutes at 1 kHz, about 1 GB: more would be a mistake, not a latency).
  */
  void setMaxLatency(double seconds, unsigned int samples = 64);
  /*!
    Longest IMU gap (s) propagated (default 0.05): a longer gap restarts the filter (IMU_GAP).
    \exception vpLaserConicException::badValueError unless in (0, 10].
  */
  void setMaxImuGap(double seconds);
  /*!
    Probability of the chi-square gate (3 degrees of freedom) on each frame's innovation, default
    0.99 (distance² 11.34): a consistent frame is rejected with probability 1 - p.
    \exception vpLaserConicException::badValueError outside (0, 1).
  */
  void setGateProbability(double p);
  //! Consistent rejected frames that declare a change of ground (default 2). Throws badValueError when 0.
  void setStepFrames(unsigned int frames);
  /*!
    Smallest change of ground height taken for a step (default 0.03 m); a candidate must also be off by
    twice the gate's distance in altitude alone, so that two tails of the noise in a row never make a step.
    \exception vpLaserConicException::badValueError unless finite and >= 0.
  */
  void setMinStepHeight(double metres);
  /*!
    Frames rejected in a row after which the filter is declared diverged (default 30: one second at 30 Hz)
    and re-initialised by the next frame whose roll and pitch agree with those the gyros carried on.
    Biased frames in a row are not a divergence: a box edge across the ring shifts part of the trace by a
    pixel or two, which GP-3 keeps as inliers, and for as long as the edge stays in the ring (2-3 s in the
    landing tutorial's descents) each plane is tilted between the box and the floor (10-20 degrees). Frames
    whose attitude disagrees with the prediction therefore count apart: five times as many of them in a
    row declare the divergence, and only then does such a frame re-initialise the filter (its own attitude
    is then in doubt).
  */
  void setMaxRejections(unsigned int frames);
  /*!
    Frames accepted before the status leaves STATUS_INITIALISING (default 3). Until then a frame the gate
    refuses re-initialises the state from itself (FRAME_INITIALISED), not FRAME_REJECTED.
  */
  void setInitialisationFrames(unsigned int frames);
  //! Time without an accepted frame after which the status is STATUS_PREDICTING, s (default 0.1).
  void setPredictionTimeout(double seconds);

  //! Forgets the state, the history and the frames; keeps the settings.
  void reset();

  /*!
    Adds an IMU sample (time in s, gyro in rad/s, specific force in m/s², IMU frame) and propagates
    the state to it. No allocation.
  */
  vpImuStatus addImu(double t, const double gyro[3], const double acc[3]);
  //! addImu() with ViSP vectors. \exception vpLaserConicException::badValueError unless both have 3 rows.
  vpImuStatus addImu(double t, const vpColVector &gyro, const vpColVector &acc);
  /*!
    Adds a frame's estimate at its exposure time \e t (s, the IMU clock): altitude (m), roll, pitch
    (rad) and their 3x3 covariance (vpLaserConicPose::getCovarianceMatrix()).
  */
  vpFrameStatus addFrame(double t, double altitude, double roll, double pitch, const vpMatrix &covariance);
  /*!
    addFrame() with the last estimate of \e estimator (computed with setCovarianceComputation(true)); a
    failed estimate is a frame without a plane (addMissingFrame()).
    \exception vpLaserConicException::notComputedError when a successful estimate has no covariance.
  */
  vpFrameStatus addFrame(double t, const vpLaserConicPose &estimator);
  //! Records a frame at time \e t without a plane (no trace, no consensus): the prediction runs on.
  vpFrameStatus addMissingFrame(double t);

  //! True once a frame initialised the state (the getters below are then meaningful).
  bool isInitialised() const;
  //! Time of the last IMU sample (s): the time of the outputs.
  double getTime() const;
  //! Altitude of the camera centre over the ground plane at getTime(), m.
  double getAltitude() const;
  //! Vertical speed dh/dt at getTime(), m/s (positive when climbing).
  double getVerticalSpeed() const;
  //! Roll at getTime(), rad.
  double getRoll() const;
  //! Pitch at getTime(), rad.
  double getPitch() const;
  //! Covariance (4x4) of (altitude, vertical speed, roll, pitch) at getTime().
  vpMatrix getCovarianceMatrix() const;
  //! The whole state (10: altitude, vertical speed, roll, pitch, gyro bias xyz, accelerometer bias xyz).
  vpColVector getState() const;
  //! Covariance (10x10) of getState().
  vpMatrix getStateCovarianceMatrix() const;
  //! Status of the outputs at getTime().
  vpFilterStatus getStatus() const;
  //! Outcome of the last frame.
  vpFrameStatus getLastFrameStatus() const;
  //! Squared Mahalanobis distance of the last frame's innovation (NaN when it was not gated).
  double getLastMahalanobis() const;
  //! Gate on the squared Mahalanobis distance (chi-square quantile of setGateProbability()).
  double getGateThreshold() const;
  //! Number of ground steps detected since the last reset().
  unsigned int getGroundStepCount() const;

  //! What a status means, in words.
  static std::string getStatusMessage(vpFilterStatus status);
  //! What a frame status means, in words.
  static std::string getFrameStatusMessage(vpFrameStatus status);
  //! What an IMU status means, in words.
  static std::string getImuStatusMessage(vpImuStatus status);

  //! One IMU sample as read from a CSV stream (IMU frame).
  struct vpImuSample
  {
    double t;       //!< seconds
    double gyro[3]; //!< rad/s
    double acc[3];  //!< specific force, m/s²
  };
  /*!
    Reads an IMU CSV stream in vpImuGravity's layout, `timestamp, wx, wy, wz, ax, ay, az` (EuRoC
    `imu0/data.csv`, Kalibr), timestamps times \e timeScale in seconds (1e-9: nanoseconds). '#' lines
    and a non-numeric first line are skipped.
    \exception vpLaserConicException::badValueError naming the file and line on an unreadable file, a
    wrong column count or a field that is not a number.
  */
  static std::vector<vpImuSample> loadImuCsv(const std::string &file, double timeScale = 1e-9);

  //! Releases the history.
  ~vpLaserConicFilter();
  vpLaserConicFilter(const vpLaserConicFilter &) = delete;
  vpLaserConicFilter &operator=(const vpLaserConicFilter &) = delete;

private:
  struct Impl; // the Eigen state and the history (laser_filter_model.h), kept out of the public header
  std::unique_ptr<Impl> m_impl;
};

#endif
