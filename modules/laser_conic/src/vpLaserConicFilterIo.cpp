/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// vpLaserConicFilter: status messages and the IMU CSV reader (vpImuGravity's layout; the row loop is the robust
// module's vpReadNumericCsv(), so that the laser module does not depend on the gravity module).
#include <visp3/laser_conic/vpLaserConicFilter.h>
#include <visp3/robust/vpNumericCsv.h>

#include <cmath>
#include <fstream>

namespace
{
void badFile(const std::string &file, size_t line, const std::string &what)
{
  std::string where = file;
  if (line > 0)
    where += ":" + std::to_string(line);
  throw vpLaserConicException(vpLaserConicException::badValueError,
                              "vpLaserConicFilter::loadImuCsv: " + where + ": " + what);
}

} // namespace

std::vector<vpLaserConicFilter::vpImuSample> vpLaserConicFilter::loadImuCsv(const std::string &file, double timeScale)
{
  if (!(timeScale > 0.0) || !std::isfinite(timeScale))
    badFile(file, 0, "the time scale must be finite and > 0");
  std::ifstream in(file.c_str());
  if (!in)
    badFile(file, 0, "cannot open the IMU file");
  std::vector<vpImuSample> samples;
  vpReadNumericCsv(
      in, 7, "timestamp, wx, wy, wz, ax, ay, az", vpParseCsvNumbers,
      [&](size_t lineNo, const std::vector<double> &values) {
        for (double v : values)
          if (!std::isfinite(v))
            badFile(file, lineNo, "non-finite time or reading");
        vpImuSample s;
        s.t = values[0] * timeScale;
        for (int i = 0; i < 3; ++i) {
          s.gyro[i] = values[1 + i];
          s.acc[i] = values[4 + i];
        }
        samples.push_back(s);
      },
      [&](size_t lineNo, const std::string &what) { badFile(file, lineNo, what); });
  if (samples.empty())
    badFile(file, 0, "no IMU sample");
  return samples;
}

std::string vpLaserConicFilter::getStatusMessage(vpFilterStatus status)
{
  switch (status) {
  case STATUS_INITIALISING:
    return "initialising: waiting for the first frames";
  case STATUS_TRACKING:
    return "tracking: frames accepted recently";
  case STATUS_PREDICTING:
    return "predicting: no frame accepted recently, IMU prediction only";
  case STATUS_GROUND_STEP:
    return "ground step: the altitude was re-initialised on a change of ground";
  case STATUS_DIVERGED:
    return "diverged: frames rejected in a row, the next frame re-initialises the filter";
  }
  return "unknown status";
}

std::string vpLaserConicFilter::getFrameStatusMessage(vpFrameStatus status)
{
  switch (status) {
  case FRAME_ACCEPTED:
    return "frame accepted";
  case FRAME_INITIALISED:
    return "frame initialised the state";
  case FRAME_REJECTED:
    return "frame rejected: its plane is inconsistent with the prediction (Mahalanobis gate)";
  case FRAME_GROUND_STEP:
    return "ground step: the altitude was re-initialised from the frame";
  case FRAME_MISSING:
    return "frame without a plane: prediction only";
  case FRAME_TOO_OLD:
    return "frame too old: older than the latency limit or the kept IMU history";
  case FRAME_OUT_OF_ORDER:
    return "frame out of order: older than a frame already used";
  case FRAME_AHEAD_OF_IMU:
    return "frame after the last IMU sample: add the IMU samples up to its time first";
  case FRAME_BAD_INPUT:
    return "bad frame: non-finite value, time beyond 1e10 s, non-positive altitude, roll or pitch outside (-pi/2, "
           "pi/2) (degrees given as radians?), covariance not symmetric positive definite or a standard deviation "
           "outside [1e-12, 1e4]";
  }
  return "unknown frame status";
}

std::string vpLaserConicFilter::getImuStatusMessage(vpImuStatus status)
{
  switch (status) {
  case IMU_OK:
    return "IMU sample used";
  case IMU_NOT_INCREASING:
    return "IMU timestamp not at least a microsecond after the previous one: sample ignored";
  case IMU_GAP:
    return "IMU timestamp more than the largest gap after the previous one, or before it (a stamp far ahead, a clock "
           "reset): the filter restarts";
  case IMU_NOT_FINITE:
    return "IMU sample with a non-finite value: ignored";
  case IMU_OUT_OF_RANGE:
    return "IMU sample beyond any IMU's range (over 100 rad/s or 10000 m/s^2), or a time beyond 1e10 s (nanoseconds "
           "given as seconds?): ignored";
  }
  return "unknown IMU status";
}
