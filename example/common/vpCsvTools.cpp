/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpCsvTools.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <visp3/core/vpIoTools.h>

namespace vpCsvTools
{
std::string trim(const std::string &s) { return vpIoTools::trim(s); }

std::vector<std::string> split(const std::string &line)
{
  // Not vpIoTools::splitChain(): it drops empty fields ("a,,b" gives two), which would shift every
  // column after a missing value instead of reporting that value.
  std::vector<std::string> fields;
  std::string::size_type start = 0;
  while (true) {
    const std::string::size_type comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos)
      break;
    start = comma + 1;
  }
  return fields;
}

bool toDouble(const std::string &text, double &value)
{
  // strtod skips leading blanks: refuse them here so that " 1" is as wrong as "1 ".
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
    return false;
  errno = 0;
  char *end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
    return false;
  value = v;
  return true;
}

bool toInteger(const std::string &text, long long &value)
{
  const std::string digits = (!text.empty() && text[0] == '-') ? text.substr(1) : text;
  // 18 digits always fit a long long: no overflow check needed.
  if (digits.empty() || digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos)
    return false;
  value = std::strtoll(text.c_str(), nullptr, 10);
  return true;
}

bool parseDouble(const std::string &field, double &value, const std::string &where, const std::string &column,
                 std::string &error)
{
  if (!toDouble(field, value)) {
    error = where + ": column " + column + " ('" + field + "') is not a finite number";
    return false;
  }
  return true;
}

bool parseIndex(const std::string &field, unsigned int &value, const std::string &where, const std::string &column,
                std::string &error)
{
  long long v = 0;
  if (field.empty() || field[0] == '-' || !toInteger(field, v) || v > 999999999) {
    error = where + ": column " + column + " ('" + field + "') is not a non-negative integer";
    return false;
  }
  value = static_cast<unsigned int>(v);
  return true;
}

std::string location(const std::string &file, unsigned int line)
{
  std::ostringstream os;
  os << file << ":" << line;
  return os.str();
}

bool samePath(const std::string &a, const std::string &b)
{
  std::error_code ec;
  if (!std::filesystem::exists(a, ec) || !std::filesystem::exists(b, ec))
    return false;
  return std::filesystem::equivalent(a, b, ec);
}

namespace
{
//! The weakly canonical form of \e path, empty when it cannot be made.
std::filesystem::path canonicalName(const std::string &path)
{
  std::error_code ec;
  const std::filesystem::path name = std::filesystem::weakly_canonical(path, ec);
  return ec ? std::filesystem::path() : name;
}

//! Whether \e b names the file \e a (of canonical name \e aName) does: by name first, as an output may not exist
//! yet while naming an input (or another output) the same way, else as the same existing file.
bool sameFile(const std::string &a, const std::filesystem::path &aName, const std::string &b)
{
  return (!aName.empty() && aName == canonicalName(b)) || samePath(a, b);
}
} // namespace

bool checkOutputIsNotInput(const std::string &output, const std::vector<std::string> &inputs, std::string &error)
{
  const std::filesystem::path out = canonicalName(output);
  for (const std::string &input : inputs) {
    if (sameFile(output, out, input)) {
      error = "refusing to overwrite input file '";
      error += input;
      error += "' with the output '";
      error += output;
      error += "'";
      return false;
    }
  }
  return true;
}

bool checkOutputs(const std::vector<std::string> &outputs, const std::vector<std::string> &inputs, std::string &error)
{
  std::vector<std::string> earlier;
  for (const std::string &output : outputs) {
    if (output.empty())
      continue;
    if (!checkOutputIsNotInput(output, inputs, error))
      return false;
    const std::filesystem::path name = canonicalName(output);
    for (const std::string &other : earlier)
      if (sameFile(output, name, other)) {
        error = "two outputs name the same file '" + output + "': choose one file for each";
        return false;
      }
    earlier.push_back(output);
  }
  return true;
}

std::string formatDouble(double value)
{
  if (std::isnan(value))
    return "nan";
  // Shortest of 15, 16 or 17 significant digits that reads back exactly.
  std::string text;
  for (int digits = 15; digits <= 17; ++digits) {
    std::ostringstream os;
    os.precision(digits);
    os << value;
    text = os.str();
    if (std::strtod(text.c_str(), nullptr) == value)
      break;
  }
  return text;
}
} // namespace vpCsvTools
