/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpCsvTools.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace vpCsvTools
{
std::string trim(const std::string &s)
{
  const char *blanks = " \t\r\n";
  const std::string::size_type first = s.find_first_not_of(blanks);
  if (first == std::string::npos)
    return std::string();
  const std::string::size_type last = s.find_last_not_of(blanks);
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string &line)
{
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

bool parseDouble(const std::string &field, double &value, const std::string &where, const std::string &column,
                 std::string &error)
{
  errno = 0;
  char *end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (field.empty() || end != field.c_str() + field.size() || errno == ERANGE || !std::isfinite(v)) {
    error = where + ": column " + column + " ('" + field + "') is not a finite number";
    return false;
  }
  value = v;
  return true;
}

bool parseIndex(const std::string &field, unsigned int &value, const std::string &where, const std::string &column,
                std::string &error)
{
  const bool digitsOnly = !field.empty() && field.size() <= 9 && field.find_first_not_of("0123456789") == std::string::npos;
  if (!digitsOnly) {
    error = where + ": column " + column + " ('" + field + "') is not a non-negative integer";
    return false;
  }
  value = static_cast<unsigned int>(std::strtoul(field.c_str(), nullptr, 10));
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

bool checkOutputIsNotInput(const std::string &output, const std::vector<std::string> &inputs, std::string &error)
{
  for (const std::string &input : inputs) {
    // Lexical comparison first: the output may not exist yet while naming the input the same way.
    std::error_code ec1, ec2;
    const std::filesystem::path out = std::filesystem::weakly_canonical(output, ec1);
    const std::filesystem::path in = std::filesystem::weakly_canonical(input, ec2);
    const bool sameName = !ec1 && !ec2 && out == in;
    if (sameName || samePath(output, input)) {
      error = "refusing to overwrite input file '" + input + "' with the output '" + output + "'";
      return false;
    }
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
