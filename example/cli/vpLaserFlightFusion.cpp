/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
#include "vpLaserFlightFusion.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vpOutputFile.h"

void vpLaserFlightFusion::addOptions(vpCommandLine &cli)
{
  cli.addString("--imu", m_imuFile, "FILE", "IMU CSV (timestamp_ns, wx, wy, wz, ax, ay, az; EuRoC / Kalibr layout)");
  cli.addString("--frame-times", m_timesFile, "FILE",
                "exposure timestamp (ns, IMU clock) of each image, in image order: 'timestamp' or 'image,timestamp'");
  cli.addString("--filtered", m_output, "FILE", "IMU-rate CSV of the filter fusing the IMU with the frames");
  cli.addString("--imu-rotation", m_rotationFile, "FILE", "IMU-to-camera rotation (9 numbers or a 4x4 matrix)");
  cli.addDouble("--covariance-inflation", m_inflation, "K",
                "variance scale of the per-frame covariance (default: the detector's measured scale)",
                vpCommandLine::POSITIVE);
}

namespace
{
//! Reads 9 (rotation) or 16 (homogeneous matrix) numbers; false with \e error otherwise.
bool readRotation(const std::string &file, vpRotationMatrix &R, std::string &error)
{
  std::ifstream in(file);
  if (!in) {
    error = file + ": cannot be read";
    return false;
  }
  std::vector<double> v;
  std::string line;
  while (std::getline(in, line)) {
    line = line.substr(0, line.find('#'));
    for (char &c : line)
      if (c == ',')
        c = ' ';
    std::istringstream words(line);
    std::string w;
    double x = 0.0;
    while (words >> w) {
      if (!vpCsvTools::toDouble(w, x)) {
        error = file + ": '" + w + "' is not a number";
        return false;
      }
      v.push_back(x);
    }
  }
  if (v.size() != 9 && v.size() != 16) {
    error = file + ": expected 9 or 16 numbers, got " + std::to_string(v.size());
    return false;
  }
  const unsigned int stride = v.size() == 9 ? 3 : 4;
  vpMatrix M(3, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      M[i][j] = v[i * stride + j];
  vpMatrix I3(3, 3);
  I3.eye();
  if ((M * M.t() - I3).frobeniusNorm() > 1e-3 || M.det() < 0.0) {
    error = file + ": not a rotation matrix";
    return false;
  }
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      R[i][j] = M[i][j];
  return true;
}
} // namespace

bool vpLaserFlightFusion::readFrameTimes(size_t frames, std::string &error)
{
  std::ifstream in(m_timesFile);
  if (!in) {
    error = m_timesFile + ": cannot be read";
    return false;
  }
  std::string line;
  unsigned int lineNo = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string trimmed = vpCsvTools::trim(line);
    if (trimmed.empty() || trimmed[0] == '#')
      continue;
    const std::vector<std::string> fields = vpCsvTools::split(trimmed);
    long long t = 0;
    const bool numeric = vpCsvTools::toInteger(fields.back(), t);
    if (!numeric && first) { // a header
      first = false;
      continue;
    }
    first = false;
    if (!numeric || fields.size() > 2) {
      error = vpCsvTools::location(m_timesFile, lineNo) + ": expected 'timestamp_ns' or 'image,timestamp_ns'";
      return false;
    }
    if (!m_frameTimes.empty() && t <= m_frameTimes.back()) {
      error = vpCsvTools::location(m_timesFile, lineNo) + ": timestamps not increasing";
      return false;
    }
    m_frameTimes.push_back(t);
  }
  if (m_frameTimes.size() != frames) {
    error = m_timesFile + ": " + std::to_string(m_frameTimes.size()) + " timestamps for " + std::to_string(frames) +
            " images";
    return false;
  }
  return true;
}

std::vector<std::string> vpLaserFlightFusion::inputs() const
{
  std::vector<std::string> files;
  for (const std::string &file : {m_imuFile, m_timesFile, m_rotationFile})
    if (!file.empty())
      files.push_back(file);
  return files;
}

bool vpLaserFlightFusion::prepare(size_t frames, std::string &error)
{
  if (m_imuFile.empty() || m_timesFile.empty()) {
    error = "--filtered needs --imu and --frame-times";
    return false;
  }
  try {
    m_imu = vpLaserConicFilter::loadImuCsv(m_imuFile, 1e-9);
  } catch (const vpException &e) {
    error = e.getStringMessage();
    return false;
  }
  if (!m_rotationFile.empty() && !readRotation(m_rotationFile, m_cRimu, error))
    return false;
  m_frames.assign(frames, Frame());
  return readFrameTimes(frames, error) &&
         vpCsvTools::checkOutputIsNotInput(m_output, {m_imuFile, m_timesFile, m_rotationFile}, error) &&
         vpOutputFile::checkWritable(m_output, error);
}

void vpLaserFlightFusion::configure(vpLaserConicPose &estimator) const
{
  estimator.setCovarianceComputation(true);
  estimator.setCovarianceInflation(m_inflation);
}

void vpLaserFlightFusion::addFrame(size_t k, bool ok, const vpLaserConicPose &estimator)
{
  if (k >= m_frames.size())
    return;
  Frame &f = m_frames[k];
  f.ok = ok && estimator.getStatus() == vpLaserConicPose::STATUS_OK;
  if (f.ok) {
    f.altitude = estimator.getAltitude();
    f.roll = estimator.getRoll();
    f.pitch = estimator.getPitch();
    f.covariance = estimator.getCovarianceMatrix();
  }
}

bool vpLaserFlightFusion::run(std::string &summary, std::string &error)
{
  // Written to a temporary file renamed when complete, as the per-frame output.
  vpOutputFile outFile(m_output);
  if (!outFile.open(error))
    return false;
  std::ostream &out = outFile.stream();
  vpLaserConicFilter filter;
  filter.setImuToCameraRotation(m_cRimu);
  out << "timestamp_ns,altitude_m,vertical_speed_mps,roll_rad,pitch_rad,sd_altitude_m,sd_vertical_speed_mps,"
         "sd_roll_rad,sd_pitch_rad,status\n";
  // Offline every frame is known: each is added as soon as the IMU reaches its exposure time.
  size_t next = 0;
  int counts[9] = {0};
  for (const vpLaserConicFilter::vpImuSample &s : m_imu) {
    filter.addImu(s.t, s.gyro, s.acc);
    for (; next < m_frames.size() && m_frameTimes[next] * 1e-9 <= s.t; ++next) {
      const double t = m_frameTimes[next] * 1e-9;
      const Frame &f = m_frames[next];
      const vpLaserConicFilter::vpFrameStatus st = f.ok ? filter.addFrame(t, f.altitude, f.roll, f.pitch, f.covariance)
                                                        : filter.addMissingFrame(t);
      ++counts[st];
    }
    const vpColVector x = filter.getState();
    const vpMatrix P = filter.getCovarianceMatrix();
    out << static_cast<long long>(std::llround(s.t * 1e9));
    for (unsigned int i = 0; i < 4; ++i)
      out << "," << vpCsvTools::formatDouble(x[i]);
    for (unsigned int i = 0; i < 4; ++i)
      out << "," << vpCsvTools::formatDouble(std::sqrt(P[i][i]));
    const std::string status = vpLaserConicFilter::getStatusMessage(filter.getStatus());
    out << "," << status.substr(0, status.find(':')) << "\n"; // its first word: "tracking", ...
  }
  if (!outFile.commit(error))
    return false;
  std::ostringstream s;
  s << m_imu.size() << " IMU samples written to " << m_output << "; frames: " << counts[0] + counts[1] << " used, "
    << counts[2] << " rejected, " << counts[3] << " ground steps, " << counts[4] << " without plane, "
    << counts[5] + counts[6] + counts[7] + (m_frames.size() - next) << " outside the IMU stream, " << counts[8]
    << " without a usable covariance";
  summary = s.str();
  return true;
}
