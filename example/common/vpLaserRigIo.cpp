/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpLaserRigIo.h"

#include "vpOutputFile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>

#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPoseVector.h>
#include <visp3/core/vpXmlParserCamera.h>

#include "vpCsvTools.h"

namespace
{
const char *const kGroundTruthHeader = "frame,image,altitude_m,roll_rad,pitch_rad,nx,ny,nz,d";

//! Next line that is neither blank nor a '#' comment; false at the end of the stream.
bool nextContentLine(std::istream &in, std::string &line, unsigned int &lineNumber)
{
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string::size_type first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') {
      return true;
    }
  }
  return false;
}

//! Parses exactly \e count finite numbers from \e line.
bool parseNumbers(const std::string &line, unsigned int count, double *values)
{
  std::istringstream ss(line);
  for (unsigned int i = 0; i < count; ++i) {
    if (!(ss >> values[i]) || !std::isfinite(values[i])) {
      return false;
    }
  }
  std::string rest;
  return !(ss >> rest);
}

//! The text of the next \e tag element of \e text at or after \e from, trimmed; \e from moves past its closing
//! tag. False when there is none.
bool nextElement(const std::string &text, const std::string &tag, std::string::size_type &from, std::string &value)
{
  const std::string open = "<" + tag + ">", close = "</" + tag + ">";
  const std::string::size_type start = text.find(open, from);
  if (start == std::string::npos)
    return false;
  const std::string::size_type end = text.find(close, start + open.size());
  if (end == std::string::npos)
    return false;
  value = text.substr(start + open.size(), end - start - open.size());
  const std::string::size_type first = value.find_first_not_of(" \t\r\n"), last = value.find_last_not_of(" \t\r\n");
  value = first == std::string::npos ? std::string() : value.substr(first, last - first + 1);
  from = end + close.size();
  return true;
}

/*!
  The first number of the camera \e name in the vpXmlParserCamera file's \e text that is not one (e.g. "800px",
  "abc", empty), as "tag 'value'"; empty when all are numbers. ViSP's parser reads such a value as 0 (or as its
  leading digits) without a word: a principal point or a distortion of 0 then gives poses off by metres.
*/
std::string firstValueNotANumber(const std::string &text, const std::string &name)
{
  std::string::size_type from = 0;
  std::string camera;
  while (nextElement(text, "camera", from, camera)) {
    std::string::size_type inCamera = 0;
    std::string cameraName;
    if (!nextElement(camera, "name", inCamera, cameraName) || cameraName != name)
      continue;
    for (const char *tag : {"image_width", "image_height", "px", "py", "u0", "v0", "kud", "kdu"}) {
      std::string::size_type at = 0;
      std::string value;
      while (nextElement(camera, tag, at, value)) {
        char *end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0' || !std::isfinite(number))
          return std::string(tag) + " '" + value + "'";
      }
    }
  }
  return std::string();
}

//! Sends std::cout to nowhere while it lives.
class CoutSilencer
{
public:
  CoutSilencer() : m_saved(std::cout.rdbuf(nullptr)) {}
  ~CoutSilencer() { std::cout.rdbuf(m_saved); }
  CoutSilencer(const CoutSilencer &) = delete;
  CoutSilencer &operator=(const CoutSilencer &) = delete;

private:
  std::streambuf *m_saved;
};

//! Reads the older text format (see vpLaserRigIo::readLaserCalibration()).
bool readLaserText(const std::string &file, std::istream &in, double &openingAngleRad, vpHomogeneousMatrix &cMl,
                   std::string &error)
{
  const std::string where = "laser calibration '" + file + "'";
  std::string line;
  unsigned int lineNumber = 0;

  if (!nextContentLine(in, line, lineNumber)) {
    error = where + ": empty file, expected 'opening_angle_deg <value>'";
    return false;
  }
  std::istringstream angleLine(line);
  std::string keyword;
  double angleDeg = 0.0;
  std::string rest;
  if (!(angleLine >> keyword) || keyword != "opening_angle_deg" || !(angleLine >> angleDeg) || (angleLine >> rest)) {
    error = where + " line " + std::to_string(lineNumber) + ": expected 'opening_angle_deg <value>'";
    return false;
  }
  if (!std::isfinite(angleDeg) || angleDeg <= 0.0 || angleDeg >= 180.0) {
    error = where + " line " + std::to_string(lineNumber) + ": opening angle must be in (0, 180) degrees";
    return false;
  }

  if (!nextContentLine(in, line, lineNumber)) {
    error = where + ": missing 'cMl' after the opening angle";
    return false;
  }
  std::istringstream cMlLine(line);
  if (!(cMlLine >> keyword) || keyword != "cMl" || (cMlLine >> rest)) {
    error = where + " line " + std::to_string(lineNumber) + ": expected the keyword 'cMl'";
    return false;
  }

  vpHomogeneousMatrix M;
  for (unsigned int r = 0; r < 4; ++r) {
    double row[4];
    if (!nextContentLine(in, line, lineNumber)) {
      error = where + ": cMl has " + std::to_string(r) + " rows, expected 4";
      return false;
    }
    if (!parseNumbers(line, 4, row)) {
      error = where + " line " + std::to_string(lineNumber) + ": expected 4 finite numbers";
      return false;
    }
    for (unsigned int c = 0; c < 4; ++c) {
      M[r][c] = row[c];
    }
  }
  if (std::fabs(M[3][0]) > 0.0 || std::fabs(M[3][1]) > 0.0 || std::fabs(M[3][2]) > 0.0 || M[3][3] != 1.0) {
    error = where + ": the last row of cMl must be '0 0 0 1'";
    return false;
  }
  const vpRotationMatrix R = M.getRotationMatrix();
  vpMatrix RtR = vpMatrix(R.t()) * vpMatrix(R);
  double orthogonalityError = 0.0;
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 3; ++c) {
      orthogonalityError = std::max(orthogonalityError, std::fabs(RtR[r][c] - (r == c ? 1.0 : 0.0)));
    }
  }
  if (orthogonalityError > 1e-6 || vpMatrix(R).det() < 0.0) {
    error = where + ": the 3x3 block of cMl is not a rotation matrix";
    return false;
  }
  if (nextContentLine(in, line, lineNumber)) {
    error = where + " line " + std::to_string(lineNumber) + ": unexpected content after cMl";
    return false;
  }

  openingAngleRad = vpMath::rad(angleDeg);
  cMl = M;
  return true;
}

//! Strict list of \e count finite numbers "[a, b, c]" (or a single number when count is 1).
bool parseYamlNumbers(std::string text, unsigned int count, double *values)
{
  text = vpCsvTools::trim(text);
  if (count > 1 || (!text.empty() && text[0] == '[')) {
    if (text.size() < 2 || text.front() != '[' || text.back() != ']')
      return false;
    text = text.substr(1, text.size() - 2);
  }
  const std::vector<std::string> fields = vpCsvTools::split(text);
  if (fields.size() != count)
    return false;
  for (unsigned int i = 0; i < count; ++i)
    if (!vpCsvTools::toDouble(vpCsvTools::trim(fields[i]), values[i]))
      return false;
  return true;
}

//! Reads the YAML format: keys parsed here, the pose with vpPoseVector::loadYAML().
bool readLaserYaml(const std::string &file, std::istream &in, vpLaserCalibrationData &result, std::string &error)
{
  const std::string where = "laser calibration '" + file + "'";
  std::string line;
  unsigned int lineNumber = 0;
  bool hasAngle = false, inData = false;
  unsigned int nbStd = 0, nbDataRows = 0;
  std::string rows, cols;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string at = where + " line " + std::to_string(lineNumber);
    const std::string trimmed = vpCsvTools::trim(line);
    if (trimmed.empty() || trimmed[0] == '#')
      continue;
    if (inData) {
      // "- [value]": checked here because vpArray2D::loadYAML() reads the values with atof().
      double v = 0.0;
      if (trimmed.compare(0, 1, "-") != 0 || !parseYamlNumbers(trimmed.substr(1), 1, &v)) {
        error = at + ": expected a pose row '- [value]' with a finite number";
        return false;
      }
      ++nbDataRows;
      continue;
    }
    const std::string::size_type colon = trimmed.find(':');
    if (colon == std::string::npos) {
      error = at + ": expected 'key: value'";
      return false;
    }
    const std::string key = vpCsvTools::trim(trimmed.substr(0, colon));
    std::string value = trimmed.substr(colon + 1);
    const std::string::size_type comment = value.find('#');
    if (comment != std::string::npos)
      value = value.substr(0, comment);
    double v[3] = {0.0, 0.0, 0.0};
    if (key == "data") {
      inData = true;
    } else if (key == "rows" || key == "cols") {
      (key == "rows" ? rows : cols) = vpCsvTools::trim(value);
    } else if (key == "opening_angle_deg") {
      if (!parseYamlNumbers(value, 1, v) || v[0] <= 0.0 || v[0] >= 180.0) {
        error = at + ": opening_angle_deg must be a number in (0, 180)";
        return false;
      }
      result.openingAngle = vpMath::rad(v[0]);
      hasAngle = true;
    } else if (key == "std_dev_axis_deg" || key == "std_dev_apex_m" || key == "std_dev_opening_angle_deg") {
      const unsigned int n = key == "std_dev_axis_deg" ? 2 : (key == "std_dev_apex_m" ? 3 : 1);
      if (!parseYamlNumbers(value, n, v) || *std::min_element(v, v + n) < 0.0) {
        error = at + ": ";
        error += key;
        error += " expects ";
        error += n == 1 ? std::string("a number") : "a list of " + std::to_string(n) + " numbers";
        error += " >= 0";
        return false;
      }
      if (n == 2) {
        result.stdDeviations[0] = vpMath::rad(v[0]);
        result.stdDeviations[1] = vpMath::rad(v[1]);
      } else if (n == 3) {
        for (unsigned int k = 0; k < 3; ++k)
          result.stdDeviations[2 + k] = v[k];
      } else {
        result.stdDeviations[5] = vpMath::rad(v[0]);
      }
      ++nbStd;
    } else if (key == "rms_m") {
      if (!parseYamlNumbers(value, 1, v) || v[0] < 0.0) {
        error = at + ": rms_m must be a number >= 0";
        return false;
      }
      result.rms = v[0];
    } else if (key == "views") {
      if (!parseYamlNumbers(value, 1, v) || v[0] < 0.0 || v[0] != std::floor(v[0])) {
        error = at + ": views must be a whole number";
        return false;
      }
      result.nbViews = static_cast<unsigned int>(v[0]);
    } else {
      error = at + ": unknown key '";
      error += key;
      error += "'";
      return false;
    }
  }
  if (!hasAngle) {
    error = where + ": missing 'opening_angle_deg: <value>'";
    return false;
  }
  if (nbStd != 0 && nbStd != 3) {
    error = where + ": give all of std_dev_axis_deg, std_dev_apex_m and std_dev_opening_angle_deg, or none";
    return false;
  }
  result.hasStdDeviations = nbStd == 3;
  if (rows != "6" || cols != "1" || nbDataRows != 6) {
    error = where + ": the pose must be a vpPoseVector (rows: 6, cols: 1, 6 data rows)";
    return false;
  }
  vpPoseVector pose;
  if (!vpPoseVector::loadYAML(file, pose)) {
    error = where + ": vpPoseVector::loadYAML() cannot read the pose";
    return false;
  }
  result.cMl.buildFrom(pose);
  return true;
}
} // namespace

bool vpLaserRigIo::readLaserCalibration(const std::string &file, vpLaserCalibrationData &calibration,
                                        std::string &error)
{
  std::ifstream in(file.c_str());
  if (!in) {
    error = "cannot open laser calibration file '" + file + "'";
    return false;
  }
  // The YAML format is the one with a "rows:" line (vpArray2D::saveYAML()).
  bool yaml = false;
  std::string line;
  while (!yaml && std::getline(in, line))
    yaml = line.compare(0, 5, "rows:") == 0;
  in.clear();
  in.seekg(0);
  vpLaserCalibrationData result;
  if (yaml ? !readLaserYaml(file, in, result, error) : !readLaserText(file, in, result.openingAngle, result.cMl, error))
    return false;
  calibration = result;
  return true;
}

bool vpLaserRigIo::readLaserCalibration(const std::string &file, double &openingAngleRad, vpHomogeneousMatrix &cMl,
                                        std::string &error)
{
  vpLaserCalibrationData calibration;
  if (!readLaserCalibration(file, calibration, error))
    return false;
  openingAngleRad = calibration.openingAngle;
  cMl = calibration.cMl;
  return true;
}

bool vpLaserRigIo::writeLaserCalibrationYaml(const std::string &file, const vpLaserCalibrationData &calibration,
                                             std::string &error)
{
  std::ostringstream header;
  header << std::setprecision(6);
  header << "# Laser calibration of a camera/circular-laser rig. The pose is cMl, the laser frame (apex at its\n"
         << "# origin, cone axis +Z) in the camera frame, a vpPoseVector [tx ty tz (m), theta u (rad)]:\n"
         << "# read it with vpPoseVector::loadYAML(). Standard deviations: axis angles alpha, beta of\n"
         << "# Rx(alpha) Ry(beta), apex, opening angle (0: not estimated).\n";
  header << std::setprecision(std::numeric_limits<double>::max_digits10);
  header << "opening_angle_deg: " << vpMath::deg(calibration.openingAngle);
  header << std::setprecision(6);
  if (calibration.hasStdDeviations) {
    const vpColVector &s = calibration.stdDeviations;
    header << "\nstd_dev_axis_deg: [" << vpMath::deg(s[0]) << ", " << vpMath::deg(s[1]) << "]";
    header << "\nstd_dev_apex_m: [" << s[2] << ", " << s[3] << ", " << s[4] << "]";
    header << "\nstd_dev_opening_angle_deg: " << vpMath::deg(s[5]);
  }
  if (calibration.rms >= 0.0)
    header << "\nrms_m: " << calibration.rms;
  if (calibration.nbViews > 0)
    header << "\nviews: " << calibration.nbViews;
  const vpPoseVector pose(calibration.cMl);
  // Through a temporary file: a failed write (disk full, missing folder) is an error and leaves an
  // existing file as it was.
  if (!vpOutputFile::writeThrough(
          file, [&](const std::string &scratch) { return vpPoseVector::saveYAML(scratch, pose, header.str().c_str()); },
          error)) {
    error = "cannot write laser calibration file: " + error;
    return false;
  }
  return true;
}

bool vpLaserRigIo::writeLaserCalibration(const std::string &file, double openingAngleRad,
                                         const vpHomogeneousMatrix &cMl, std::string &error)
{
  vpOutputFile outFile(file);
  if (!outFile.open(error)) {
    error = "cannot write laser calibration file: " + error;
    return false;
  }
  std::ostream &out = outFile.stream();
  out << "# laser calibration: full opening angle and pose of the laser frame in the camera frame\n";
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  out << "opening_angle_deg " << vpMath::deg(openingAngleRad) << "\n";
  out << "cMl\n";
  for (unsigned int r = 0; r < 4; ++r) {
    for (unsigned int c = 0; c < 4; ++c) {
      out << (c ? " " : "") << cMl[r][c] + 0.0; // + 0.0 prints -0 as 0
    }
    out << "\n";
  }
  return outFile.commit(error);
}

bool vpLaserRigIo::readGroundTruth(const std::string &file, std::vector<vpLaserGroundTruthFrame> &frames,
                                   std::string &error)
{
  std::ifstream in(file.c_str());
  if (!in) {
    error = "cannot open ground truth file '" + file + "'";
    return false;
  }
  std::string line;
  if (!std::getline(in, line) || vpCsvTools::trim(line) != kGroundTruthHeader) {
    error = "ground truth '" + file + "': first line must be '" + std::string(kGroundTruthHeader) + "'";
    return false;
  }
  std::vector<vpLaserGroundTruthFrame> result;
  unsigned int lineNumber = 1;
  while (std::getline(in, line)) {
    ++lineNumber;
    line = vpCsvTools::trim(line);
    if (line.empty()) {
      continue;
    }
    const std::string where = "ground truth '" + file + "' line " + std::to_string(lineNumber);
    const std::vector<std::string> fields = vpCsvTools::split(line);
    if (fields.size() != 9) {
      error = where + ": expected 9 comma-separated fields, got " + std::to_string(fields.size());
      return false;
    }
    double values[9];
    for (unsigned int i = 0; i < 9; ++i) {
      if (i != 1 && !vpCsvTools::toDouble(fields[i], values[i])) {
        error = where + ": field " + std::to_string(i + 1) + " ('" + fields[i] + "') is not a finite number";
        return false;
      }
    }
    if (values[0] < 0.0 || values[0] != std::floor(values[0])) {
      error = where + ": the frame index must be a non-negative integer";
      return false;
    }
    if (fields[1].empty()) {
      error = where + ": empty image name";
      return false;
    }
    const double normalNorm = std::sqrt(values[5] * values[5] + values[6] * values[6] + values[7] * values[7]);
    if (std::fabs(normalNorm - 1.0) > 1e-6) {
      error = where + ": the plane normal (nx, ny, nz) is not a unit vector";
      return false;
    }
    vpLaserGroundTruthFrame frame;
    frame.frame = static_cast<unsigned int>(values[0]);
    frame.image = fields[1];
    frame.altitude = values[2];
    frame.roll = values[3];
    frame.pitch = values[4];
    frame.plane = vpPlane(values[5], values[6], values[7], values[8]);
    result.push_back(frame);
  }
  if (result.empty()) {
    error = "ground truth '" + file + "': no frame";
    return false;
  }
  frames.swap(result);
  return true;
}

bool vpLaserRigIo::writeGroundTruth(const std::string &file, const std::vector<vpLaserGroundTruthFrame> &frames,
                                    std::string &error)
{
  std::ofstream out(file.c_str());
  if (!out) {
    error = "cannot write ground truth file '" + file + "'";
    return false;
  }
  out << kGroundTruthHeader << "\n";
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (const vpLaserGroundTruthFrame &f : frames) {
    out << f.frame << "," << f.image << "," << f.altitude << "," << f.roll << "," << f.pitch << "," << f.plane.getA()
        << "," << f.plane.getB() << "," << f.plane.getC() << "," << f.plane.getD() << "\n";
  }
  if (!out) {
    error = "error while writing '" + file + "'";
    return false;
  }
  return true;
}

bool vpLaserRigIo::readCamera(const std::string &file, const std::string &name, vpCameraParameters &cam,
                              unsigned int &width, unsigned int &height, std::string &error)
{
  if (!vpIoTools::checkFilename(file)) {
    error = file + ": camera file not found";
    return false;
  }
  vpXmlParserCamera parser;
  vpCameraParameters parsed;
  int status = vpXmlParserCamera::SEQUENCE_ERROR;
  std::string parseError;
  {
    // vpXmlParserCamera reports the camera it found on std::cout: keep that out of the programs' output.
    const CoutSilencer silence;
    try {
      // The model with distortion when the file has it (kud, kdu), else the one without.
      status = parser.parse(parsed, file, name, vpCameraParameters::perspectiveProjWithDistortion);
      if (status != vpXmlParserCamera::SEQUENCE_OK)
        status = parser.parse(parsed, file, name, vpCameraParameters::perspectiveProjWithoutDistortion);
    } catch (const vpException &e) {
      parseError = e.getStringMessage();
    }
  }
  if (!parseError.empty()) {
    error = file + ": not a vpXmlParserCamera file (" + parseError + ")";
    return false;
  }
  if (status != vpXmlParserCamera::SEQUENCE_OK) {
    error = file + ": no camera named '" + name + "' with a perspective model (vpXmlParserCamera format)";
    return false;
  }
  std::ifstream in(file.c_str());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string notANumber = firstValueNotANumber(text, name);
  if (!notANumber.empty()) {
    error = file + ": camera '" + name + "': " + notANumber + " is not a number";
    return false;
  }
  if (!std::isfinite(parsed.get_kud()) || !std::isfinite(parsed.get_kdu())) {
    error = file + ": distortion coefficients kud, kdu must be finite";
    return false;
  }
  if (!(parsed.get_px() > 0.0) || !(parsed.get_py() > 0.0)) {
    error = file + ": focal lengths px, py must be positive";
    return false;
  }
  cam = parsed;
  width = parser.getWidth();
  height = parser.getHeight();
  return true;
}

bool vpLaserRigIo::writeCamera(const std::string &file, const vpCameraParameters &cam, unsigned int width,
                               unsigned int height, std::string &error)
{
  // vpXmlParserCamera::save() adds to an existing file and refuses a duplicate name: start afresh.
  std::remove(file.c_str());
  vpXmlParserCamera parser;
  if (parser.save(cam, file, "Camera", width, height) != vpXmlParserCamera::SEQUENCE_OK) {
    error = "cannot write camera file '" + file + "'";
    return false;
  }
  return true;
}

bool vpLaserRigIo::readDataset(const std::string &directory, vpLaserDataset &dataset, std::string &error)
{
  vpLaserDataset result;
  result.directory = directory;
  if (!vpIoTools::checkDirectory(directory)) {
    error = "dataset directory '" + directory + "' does not exist";
    return false;
  }
  if (!readCamera(directory + "/camera.xml", "Camera", result.cam, result.width, result.height, error) ||
      !readLaserCalibration(directory +
                                (vpIoTools::checkFilename(directory + "/laser.yaml") ? "/laser.yaml" : "/laser.txt"),
                            result.openingAngle, result.cMl, error) ||
      !readGroundTruth(directory + "/groundtruth.csv", result.frames, error)) {
    return false;
  }
  if (result.width == 0 || result.height == 0) {
    error = directory + "/camera.xml: image_width and image_height are missing";
    return false;
  }
  dataset = result;
  return true;
}

bool vpLaserRigIo::listImages(const std::string &source, bool isList, std::vector<std::string> &images,
                              std::string &error)
{
  namespace fs = std::filesystem;
  std::vector<std::string> found;
  if (!isList) {
    if (!fs::is_directory(source)) {
      error = source + ": image folder not found";
      return false;
    }
    for (const fs::directory_entry &entry : fs::directory_iterator(source)) {
      std::string ext = entry.path().extension().string();
      for (char &c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const bool image = ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm" || ext == ".pgm";
      if (image && entry.is_regular_file())
        found.push_back(entry.path().string());
    }
    std::sort(found.begin(), found.end());
  } else {
    std::ifstream in(source.c_str());
    if (!in) {
      error = source + ": cannot open the image list";
      return false;
    }
    std::string line;
    for (unsigned int n = 1; std::getline(in, line); ++n) {
      const std::string name = vpCsvTools::trim(line);
      if (name.empty() || name[0] == '#')
        continue;
      const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : fs::path(source).parent_path() / name;
      if (!fs::is_regular_file(path)) {
        error = vpCsvTools::location(source, n) + ": image '" + path.string() + "' not found";
        return false;
      }
      found.push_back(path.string());
    }
  }
  if (found.empty()) {
    error = source + (isList ? ": the list names no image" : ": no image (.png .jpg .jpeg .ppm .pgm) in this folder");
    return false;
  }
  images.swap(found);
  return true;
}
