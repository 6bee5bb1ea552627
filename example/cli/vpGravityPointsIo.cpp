/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpGravityPointsIo.h"

#include "vpOutputFile.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>

#include "vpCsvTools.h"

namespace
{
const char *const kPoseHeader = "frame,status,tx,ty,tz,tux,tuy,tuz";

//! True for lines that carry no data: blank or comment.
bool isSkippable(const std::string &line)
{
  const std::string t = vpCsvTools::trim(line);
  return t.empty() || t[0] == '#';
}

//! Parses fields[first .. first+count) as numbers named by \e names.
bool parseNumbers(const std::vector<std::string> &fields, size_t first, const std::vector<std::string> &names,
                  const std::string &where, std::vector<double> &values, std::string &error)
{
  values.assign(names.size(), 0.0);
  for (size_t i = 0; i < names.size(); ++i)
    if (!vpCsvTools::parseDouble(fields[first + i], values[i], where, names[i], error))
      return false;
  return true;
}

/*!
  Calls \e row(fields, where) for every data row of a CSV file (comments, blank lines and an optional
  first header line starting with "frame" skipped) until it returns false. \e what names the file in
  the message when it cannot be opened. \return false with \e error set on failure.
*/
template <typename RowFunction>
bool forEachRow(const std::string &file, const std::string &what, std::string &error, RowFunction row)
{
  std::ifstream in(file);
  if (!in) {
    error = file + ": cannot open the " + what + " file";
    return false;
  }
  std::string line;
  unsigned int lineNumber = 0;
  bool seenData = false;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (isSkippable(line))
      continue;
    const std::vector<std::string> fields = vpCsvTools::split(line);
    if (!seenData && fields[0] == "frame") { // optional header line
      seenData = true;
      continue;
    }
    seenData = true;
    if (!row(fields, vpCsvTools::location(file, lineNumber), lineNumber))
      return false;
  }
  return true;
}

bool parseGravityRow(const std::vector<std::string> &fields, const std::string &where, vpGravityFrame &frame,
                     std::string &error)
{
  if (fields.size() != 8) {
    error = where + ": a gravity row has 8 columns (frame,gravity,gcx,gcy,gcz,gox,goy,goz), found " +
            std::to_string(fields.size());
    return false;
  }
  if (frame.gCam.size() == 3) {
    error = where + ": second gravity row for frame " + std::to_string(frame.frame);
    return false;
  }
  std::vector<double> v;
  if (!parseNumbers(fields, 2, {"gcx", "gcy", "gcz", "gox", "goy", "goz"}, where, v, error))
    return false;
  frame.gCam = vpColVector({v[0], v[1], v[2]});
  frame.gObj = vpColVector({v[3], v[4], v[5]});
  return true;
}

bool parsePointRow(const std::vector<std::string> &fields, const std::string &where, vpGravityFrame &frame,
                   std::string &error)
{
  if (fields.size() != 7) {
    error = where + ": a point row has 7 columns (frame,point,oX,oY,oZ,x,y), found " + std::to_string(fields.size());
    return false;
  }
  std::vector<double> v;
  if (!parseNumbers(fields, 2, {"oX", "oY", "oZ", "x", "y"}, where, v, error))
    return false;
  vpPoint P(v[0], v[1], v[2]);
  P.set_x(v[3]);
  P.set_y(v[4]);
  frame.points.push_back(P);
  return true;
}
} // namespace

bool vpGravityPointsIo::readPoints(const std::string &file, std::vector<vpGravityFrame> &frames, std::string &error)
{
  return readPoints(file, frames, error, true);
}

bool vpGravityPointsIo::readPoints(const std::string &file, std::vector<vpGravityFrame> &frames, std::string &error,
                                   bool requireGravity)
{
  std::map<unsigned int, vpGravityFrame> byIndex;
  const bool read =
      forEachRow(file, "points", error,
                 [&](const std::vector<std::string> &fields, const std::string &where, unsigned int lineNumber) {
                   if (fields.size() < 2) {
                     error = where + ": expected 'frame,gravity,...' or 'frame,point,...', found 1 column";
                     return false;
                   }
                   unsigned int index = 0;
                   if (!vpCsvTools::parseIndex(fields[0], index, where, "frame", error))
                     return false;
                   vpGravityFrame &frame = byIndex[index];
                   if (frame.firstLine == 0) {
                     frame.frame = index;
                     frame.firstLine = lineNumber;
                   }
                   if (fields[1] == "gravity")
                     return parseGravityRow(fields, where, frame, error);
                   if (fields[1] == "point")
                     return parsePointRow(fields, where, frame, error);
                   error = where + ": column kind ('" + fields[1] + "') must be 'gravity' or 'point'";
                   return false;
                 });
  if (!read)
    return false;
  if (byIndex.empty()) {
    error = file + ": no data row (expected 'frame,gravity,...' and 'frame,point,...' rows)";
    return false;
  }
  std::vector<vpGravityFrame> result;
  for (const auto &entry : byIndex) {
    if (requireGravity && entry.second.gCam.size() != 3) {
      error = vpCsvTools::location(file, entry.second.firstLine) + ": frame " + std::to_string(entry.first) +
              " has no gravity row";
      return false;
    }
    result.push_back(entry.second);
  }
  frames = result;
  return true;
}

bool vpGravityPointsIo::writePoints(const std::string &file, const std::vector<vpGravityFrame> &frames,
                                    std::string &error)
{
  std::ofstream out(file);
  if (!out) {
    error = file + ": cannot be written";
    return false;
  }
  using vpCsvTools::formatDouble;
  out << "# gravity-aided pose input: per frame one gravity row (camera and object frames) and point rows\n"
      << "# (object coordinates in metres, normalized image coordinates x = (u-u0)/px, y = (v-v0)/py)\n"
      << "frame,kind,values...\n";
  for (const vpGravityFrame &f : frames) {
    out << f.frame << ",gravity";
    for (unsigned int i = 0; i < 3; ++i)
      out << "," << formatDouble(f.gCam[i]);
    for (unsigned int i = 0; i < 3; ++i)
      out << "," << formatDouble(f.gObj[i]);
    out << "\n";
    for (const vpPoint &P : f.points)
      out << f.frame << ",point," << formatDouble(P.get_oX()) << "," << formatDouble(P.get_oY()) << ","
          << formatDouble(P.get_oZ()) << "," << formatDouble(P.get_x()) << "," << formatDouble(P.get_y()) << "\n";
  }
  if (!out) {
    error = file + ": write error";
    return false;
  }
  return true;
}

bool vpGravityPointsIo::readPoses(const std::string &file, std::vector<vpPoseRow> &poses, std::string &error)
{
  std::ifstream in(file);
  if (!in) {
    error = file + ": cannot open the pose file";
    return false;
  }
  std::string line;
  unsigned int lineNumber = 0;
  bool headerSeen = false;
  std::vector<vpPoseRow> result;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (isSkippable(line))
      continue;
    const std::string where = vpCsvTools::location(file, lineNumber);
    if (!headerSeen) {
      if (vpCsvTools::trim(line) != kPoseHeader) {
        error = where + ": expected the header '" + kPoseHeader + "'";
        return false;
      }
      headerSeen = true;
      continue;
    }
    const std::vector<std::string> fields = vpCsvTools::split(line);
    if (fields.size() != 8) {
      error = where + ": a pose row has 8 columns (" + kPoseHeader + "), found " + std::to_string(fields.size());
      return false;
    }
    vpPoseRow row;
    if (!vpCsvTools::parseIndex(fields[0], row.frame, where, "frame", error))
      return false;
    row.status = fields[1];
    if (row.status == "ok") {
      std::vector<double> v;
      if (!parseNumbers(fields, 2, {"tx", "ty", "tz", "tux", "tuy", "tuz"}, where, v, error))
        return false;
      row.cMo.buildFrom(vpTranslationVector(v[0], v[1], v[2]), vpThetaUVector(v[3], v[4], v[5]));
    }
    result.push_back(row);
  }
  if (!headerSeen) {
    error = file + ": empty pose file (expected the header '" + std::string(kPoseHeader) + "')";
    return false;
  }
  poses = result;
  return true;
}

bool vpGravityPointsIo::writePoses(const std::string &file, const std::vector<vpPoseRow> &poses, std::string &error)
{
  // Written to a temporary file renamed when complete: a failed write leaves an existing file as it was.
  vpOutputFile outFile(file);
  if (!outFile.open(error))
    return false;
  std::ostream &out = outFile.stream();
  out << kPoseHeader << "\n";
  for (const vpPoseRow &row : poses) {
    out << row.frame << "," << row.status;
    if (row.status == "ok") {
      const vpTranslationVector t = row.cMo.getTranslationVector();
      const vpThetaUVector tu = row.cMo.getThetaUVector();
      for (unsigned int i = 0; i < 3; ++i)
        out << "," << vpCsvTools::formatDouble(t[i]);
      for (unsigned int i = 0; i < 3; ++i)
        out << "," << vpCsvTools::formatDouble(tu[i]);
    } else {
      out << ",nan,nan,nan,nan,nan,nan";
    }
    out << "\n";
  }
  return outFile.commit(error);
}

bool vpGravityPointsIo::readFrameTimes(const std::string &file, std::map<unsigned int, double> &times,
                                       std::string &error)
{
  times.clear();
  const bool read = forEachRow(file, "frame times", error,
                               [&](const std::vector<std::string> &fields, const std::string &where, unsigned int) {
                                 if (fields.size() != 2) {
                                   error = where + ": a frame time row has 2 columns (frame,timestamp), found " +
                                           std::to_string(fields.size());
                                   return false;
                                 }
                                 unsigned int index = 0;
                                 double t = 0.0;
                                 if (!vpCsvTools::parseIndex(fields[0], index, where, "frame", error) ||
                                     !vpCsvTools::parseDouble(fields[1], t, where, "timestamp", error))
                                   return false;
                                 if (!times.insert(std::make_pair(index, t)).second) {
                                   error = where + ": second time for frame " + std::to_string(index);
                                   return false;
                                 }
                                 return true;
                               });
  if (!read)
    return false;
  if (times.empty()) {
    error = file + ": no frame time (expected 'frame,timestamp' rows)";
    return false;
  }
  return true;
}
