/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  vpImuGravity: accelerometer readings (specific force, pointing up at rest) -> down gravity
  direction in a sensor frame, interpolation of an IMU stream at given times, motion flag.
*/
#include <visp3/pose_gravity/vpImuGravity.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <Eigen/SVD>

#include <visp3/core/vpMatrix.h>
#include <visp3/robust/vpNumericCsv.h>

namespace
{
void badParameter(const std::string &what)
{
  throw vpPoseGravityException(vpPoseGravityException::badParameterError, "vpImuGravity::" + what);
}

void badFile(const std::string &file, size_t line, const std::string &what)
{
  std::ostringstream msg;
  msg << "vpImuGravity: " << file;
  if (line > 0)
    msg << ":" << line;
  msg << ": " << what;
  throw vpPoseGravityException(vpPoseGravityException::badFileError, msg.str());
}

// Splits a line of a rotation file on commas, spaces and tabs into numbers; false if a field is not a number.
bool parseNumbers(const std::string &line, std::vector<double> &values)
{
  values.clear();
  std::string token;
  std::string cleaned = line;
  std::replace(cleaned.begin(), cleaned.end(), ',', ' ');
  std::replace(cleaned.begin(), cleaned.end(), '\t', ' ');
  std::replace(cleaned.begin(), cleaned.end(), '\r', ' ');
  std::istringstream words(cleaned);
  while (words >> token) {
    char *end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE)
      return false;
    values.push_back(v);
  }
  return true;
}

// True when the 3x3 block of \e M is finite, R R^T within 1e-3 of the identity (Frobenius) and det R > 0: a
// rotation up to the rounding of a file or of a composition.
bool isRotation(const vpArray2D<double> &M)
{
  vpMatrix R(3, 3);
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c) {
      if (!std::isfinite(M[r][c]))
        return false;
      R[r][c] = M[r][c];
    }
  return (R * R.t() - vpMatrix(vpRotationMatrix())).frobeniusNorm() <= 1e-3 && R.det() > 0.0;
}

bool blankOrComment(const std::string &line)
{
  const size_t first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}
} // namespace

vpImuGravity::vpImuGravity()
  : m_samples(), m_sRimu(), m_gravityNorm(standardGravity()), m_normTolerance(0.5),
    m_gyroTolerance(std::numeric_limits<double>::infinity()), m_motionWindow(0.0), m_timeOffset(0.0)
{
}

vpColVector vpImuGravity::gravityFromSpecificForce(const vpColVector &f, const vpRotationMatrix &sRimu)
{
  if (!isRotation(sRimu))
    badParameter("gravityFromSpecificForce: sRimu is not a rotation (R R^T != I, det < 0 or not finite)");
  return downGravity(f, sRimu);
}

vpColVector vpImuGravity::downGravity(const vpColVector &f, const vpRotationMatrix &sRimu)
{
  if (f.size() != 3 || !std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
    throw vpPoseGravityException(vpPoseGravityException::badGravityError,
                                 "vpImuGravity::gravityFromSpecificForce: the reading must be a finite 3-vector");
  const vpColVector s = sRimu * f;
  const double norm = std::sqrt(s.sumSquare());
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw vpPoseGravityException(vpPoseGravityException::badGravityError,
                                 "vpImuGravity::gravityFromSpecificForce: zero reading (free fall?) has no direction");
  return -s / norm; // specific force points up at rest: gravity is its opposite
}

bool vpImuGravity::isAtRest(const vpColVector &f, double tolerance, double g)
{
  if (f.size() != 3)
    return false;
  const double norm = std::sqrt(f.sumSquare());
  return std::isfinite(norm) && std::abs(norm - g) <= tolerance;
}

vpRotationMatrix vpImuGravity::loadRotation(const std::string &file)
{
  std::ifstream in(file.c_str());
  if (!in)
    badFile(file, 0, "cannot open the rotation file");
  std::vector<double> all, values;
  std::string line;
  size_t lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    if (blankOrComment(line))
      continue;
    std::string content = line;
    // Kalibr's YAML rows "- [a, b, c, d]": drop the list marker and the brackets.
    const size_t first = content.find_first_not_of(" \t");
    if (first != std::string::npos && content.compare(first, 2, "- ") == 0)
      content[first] = ' ';
    std::replace(content.begin(), content.end(), '[', ' ');
    std::replace(content.begin(), content.end(), ']', ' ');
    if (!parseNumbers(content, values))
      badFile(file, lineNo, "not a list of numbers: '" + line + "'");
    all.insert(all.end(), values.begin(), values.end());
  }
  if (all.size() != 9 && all.size() != 16)
    badFile(file, 0,
            "expected 9 numbers (3x3 rotation) or 16 (4x4 homogeneous matrix), got " + std::to_string(all.size()));
  const size_t stride = (all.size() == 16) ? 4 : 3;
  vpMatrix M(3, 3);
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c) {
      M[r][c] = all[r * stride + c];
      if (!std::isfinite(M[r][c]))
        badFile(file, 0, "non-finite rotation coefficient");
    }
  if (!isRotation(M))
    badFile(file, 0, "the matrix is not a rotation (R R^T != I or det < 0)");
  // The rotation nearest to the file's matrix, U V^T of its singular value decomposition (det +1: isRotation()).
  // Through the theta-u vector, whose axis near a half turn comes from the antisymmetric part (of size sin
  // theta), a file rounded to 4 decimals loaded 7.9e-3 rad off at 3.129 rad (gravity 0.45 degree off).
  Eigen::Matrix3d A;
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c)
      A(r, c) = M[r][c];
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d nearest = svd.matrixU() * svd.matrixV().transpose();
  vpRotationMatrix R;
  for (unsigned int r = 0; r < 3; ++r)
    for (unsigned int c = 0; c < 3; ++c)
      R[r][c] = nearest(r, c);
  return R;
}

void vpImuGravity::setImuToSensorRotation(const vpRotationMatrix &sRimu)
{
  if (!isRotation(sRimu))
    badParameter("setImuToSensorRotation: not a rotation (R R^T != I, det < 0 or not finite)");
  m_sRimu = sRimu;
}

void vpImuGravity::setTimeOffset(double offset)
{
  if (!std::isfinite(offset))
    badParameter("setTimeOffset: the offset must be finite");
  m_timeOffset = offset;
}

void vpImuGravity::setGravityNorm(double g)
{
  if (!(g > 0.0) || !std::isfinite(g))
    badParameter("setGravityNorm: must be finite and > 0");
  m_gravityNorm = g;
}

void vpImuGravity::setNormTolerance(double tolerance)
{
  if (!(tolerance > 0.0))
    badParameter("setNormTolerance: must be > 0");
  m_normTolerance = tolerance;
}

void vpImuGravity::setGyroTolerance(double tolerance)
{
  if (!(tolerance > 0.0))
    badParameter("setGyroTolerance: must be > 0");
  m_gyroTolerance = tolerance;
}

void vpImuGravity::setMotionWindow(double halfWidth)
{
  if (!(halfWidth >= 0.0) || !std::isfinite(halfWidth))
    badParameter("setMotionWindow: must be finite and >= 0");
  m_motionWindow = halfWidth;
}

void vpImuGravity::addSample(double t, const vpColVector &gyro, const vpColVector &acc)
{
  if (gyro.size() != 3 || acc.size() != 3)
    badParameter("addSample: gyro and accelerometer must be 3-vectors");
  Sample s;
  s.t = t;
  bool finite = std::isfinite(t);
  for (unsigned int i = 0; i < 3; ++i) {
    s.w[i] = gyro[i];
    s.a[i] = acc[i];
    finite = finite && std::isfinite(gyro[i]) && std::isfinite(acc[i]);
  }
  if (!finite)
    badParameter("addSample: non-finite time or reading");
  if (!m_samples.empty() && !(t > m_samples.back().t))
    badParameter("addSample: times must be strictly increasing");
  m_samples.push_back(s);
}

void vpImuGravity::loadCsv(const std::string &file, double timeScale)
{
  if (!(timeScale > 0.0) || !std::isfinite(timeScale))
    badParameter("loadCsv: the time scale must be finite and > 0");
  std::ifstream in(file.c_str());
  if (!in)
    badFile(file, 0, "cannot open the IMU file");
  // A file refused part way leaves the stream as it was (the rows before the bad one are dropped again).
  const size_t before = m_samples.size();
  try {
    readCsvRows(in, file, timeScale);
  } catch (...) {
    m_samples.resize(before);
    throw;
  }
  if (m_samples.empty())
    badFile(file, 0, "no IMU sample");
}

void vpImuGravity::readCsvRows(std::istream &in, const std::string &file, double timeScale)
{
  vpColVector w(3), a(3);
  vpReadNumericCsv(
      in, 7, "timestamp, wx, wy, wz, ax, ay, az", vpParseCsvNumbers,
      [&](size_t lineNo, const std::vector<double> &values) {
        for (unsigned int i = 0; i < 3; ++i) {
          w[i] = values[1 + i];
          a[i] = values[4 + i];
        }
        try {
          addSample(values[0] * timeScale, w, a);
        } catch (const vpPoseGravityException &e) {
          badFile(file, lineNo, e.getStringMessage());
        }
      },
      [&](size_t lineNo, const std::string &what) { badFile(file, lineNo, what); });
}

bool vpImuGravity::atRest(const Sample &s) const
{
  const double an = std::sqrt(s.a[0] * s.a[0] + s.a[1] * s.a[1] + s.a[2] * s.a[2]);
  const double wn = std::sqrt(s.w[0] * s.w[0] + s.w[1] * s.w[1] + s.w[2] * s.w[2]);
  return std::abs(an - m_gravityNorm) <= m_normTolerance && wn <= m_gyroTolerance;
}

bool vpImuGravity::gravityAt(double t, vpColVector &g, bool &moving) const
{
  const double ti = t + m_timeOffset;
  if (m_samples.empty() || !std::isfinite(ti) || ti < m_samples.front().t || ti > m_samples.back().t)
    return false;
  auto after = std::lower_bound(m_samples.begin(), m_samples.end(), ti,
                                [](const Sample &s, double value) { return s.t < value; });
  auto before = (after == m_samples.begin()) ? after : after - 1;
  if (after->t == ti)
    before = after;
  const double span = after->t - before->t;
  const double u = (span > 0.0) ? (ti - before->t) / span : 0.0;
  vpColVector f(3);
  for (unsigned int i = 0; i < 3; ++i)
    f[i] = (1.0 - u) * before->a[i] + u * after->a[i];
  if (!(std::sqrt(f.sumSquare()) > 0.0))
    return false;
  g = downGravity(f, m_sRimu); // the rotation was checked when it was set
  moving = !atRest(*before) || !atRest(*after);
  // Every sample of the motion window too.
  auto lo = std::lower_bound(m_samples.begin(), m_samples.end(), ti - m_motionWindow,
                             [](const Sample &s, double value) { return s.t < value; });
  for (auto it = lo; it != m_samples.end() && it->t <= ti + m_motionWindow && !moving; ++it)
    moving = !atRest(*it);
  return true;
}
