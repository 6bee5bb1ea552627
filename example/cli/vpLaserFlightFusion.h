/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file vpLaserFlightFusion.h
  \brief The IMU-rate output of vsp-laser-altimeter: its frames' planes fused with an IMU stream by
  vpLaserConicFilter, written as CSV.
*/
#ifndef VP_LASER_FLIGHT_FUSION_H
#define VP_LASER_FLIGHT_FUSION_H

#include <string>
#include <vector>

#include <visp3/core/vpMatrix.h>
#include <visp3/laser_conic/vpLaserConicFilter.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

class vpCommandLine;

/*!
  Options `--imu FILE --frame-times FILE --filtered FILE [--imu-rotation FILE] [--covariance-inflation K]`
  of vsp-laser-altimeter, and the fusion they ask for.

  - `--imu`: IMU CSV in vpImuGravity's layout (`timestamp_ns, wx, wy, wz, ax, ay, az`, EuRoC / Kalibr);
  - `--frame-times`: one exposure timestamp (ns, the IMU clock) per image, in the order of the images:
    lines `timestamp_ns` or `image,timestamp_ns`; '#' lines and a non-numeric header are skipped;
  - `--imu-rotation`: IMU-to-camera rotation (9 numbers, or a 4x4 matrix whose rotation is taken);
  - `--covariance-inflation`: variance scale of the per-frame covariance (default
    vpLaserConicPose::recommendedDetectorInflation()), which the filter fuses and vsp-laser-altimeter writes
    as each frame's standard deviations, with or without `--imu`;
  - `--filtered`: output, one row per IMU sample:
    `timestamp_ns,altitude_m,vertical_speed_mps,roll_rad,pitch_rad,sd_altitude_m,sd_vertical_speed_mps,sd_roll_rad,sd_pitch_rad,status`
    (status: vpLaserConicFilter::vpFilterStatus in words; NaN values before the first frame).
*/
class vpLaserFlightFusion
{
public:
  //! Declares the options on \e cli.
  void addOptions(vpCommandLine &cli);
  //! True when `--filtered` was given.
  bool enabled() const { return !m_output.empty(); }
  //! The input files its options name (`--imu`, `--frame-times`, `--imu-rotation`), those given.
  std::vector<std::string> inputs() const;
  //! The `--filtered` output (empty when not given).
  const std::string &output() const { return m_output; }
  /*!
    Checks the options and reads the IMU stream and the frame times (\e frames images).
    \return false with \e error naming the file and line otherwise.
  */
  bool prepare(size_t frames, std::string &error);
  //! Configures \e estimator for the fusion: covariance computed, inflated by the chosen scale.
  void configure(vpLaserConicPose &estimator) const;
  //! Records frame \e k: its last estimate when \e ok, a frame without a plane otherwise.
  void addFrame(size_t k, bool ok, const vpLaserConicPose &estimator);
  /*!
    Runs the filter over the IMU stream with the recorded frames and writes the CSV.
    \return false with \e error when the output cannot be written.
  */
  bool run(std::string &summary, std::string &error);

private:
  struct Frame
  {
    bool ok = false;
    double altitude = 0.0, roll = 0.0, pitch = 0.0;
    vpMatrix covariance;
  };
  bool readFrameTimes(size_t frames, std::string &error);

  std::string m_imuFile, m_timesFile, m_output, m_rotationFile;
  double m_inflation = vpLaserConicPose::recommendedDetectorInflation();
  std::vector<vpLaserConicFilter::vpImuSample> m_imu;
  std::vector<long long> m_frameTimes;
  std::vector<Frame> m_frames;
  vpRotationMatrix m_cRimu;
};

#endif
