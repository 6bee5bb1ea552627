/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/robust/vpNumericCsv.h>

#include <cerrno>
#include <cstdlib>

namespace
{
bool blankOrComment(const std::string &line)
{
  const size_t first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

// Whether the line starts with a number (nan and inf included): then it is a row, never a header, whatever parse
// says of it (a typo in the first sample was taken for a header and the sample dropped).
bool startsWithANumber(const std::string &line)
{
  const char *begin = line.c_str();
  char *end = nullptr;
  std::strtod(begin, &end);
  return end != begin;
}

// The line without a leading UTF-8 byte-order mark (spreadsheets write one; it made a first data row a header).
void dropByteOrderMark(std::string &line)
{
  if (line.compare(0, 3, "\xEF\xBB\xBF") == 0)
    line.erase(0, 3);
}
} // namespace

bool vpParseCsvNumbers(const std::string &line, std::vector<double> &values)
{
  values.clear();
  size_t start = 0;
  while (start <= line.size()) {
    size_t end = line.find(',', start);
    if (end == std::string::npos)
      end = line.size();
    const std::string field = line.substr(start, end - start);
    const char *begin = field.c_str();
    char *stop = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &stop);
    if (stop == begin || errno == ERANGE)
      return false;
    for (; *stop != '\0'; ++stop)
      if (*stop != ' ' && *stop != '\t' && *stop != '\r')
        return false;
    values.push_back(v);
    start = end + 1;
  }
  return true;
}

void vpReadNumericCsv(std::istream &in, size_t columns, const std::string &columnNames,
                      const std::function<bool(const std::string &, std::vector<double> &)> &parse,
                      const std::function<void(size_t, const std::vector<double> &)> &row,
                      const std::function<void(size_t, const std::string &)> &fail)
{
  std::string line;
  std::vector<double> values;
  size_t lineNo = 0;
  bool first = true;
  while (std::getline(in, line)) {
    if (++lineNo == 1)
      dropByteOrderMark(line);
    if (blankOrComment(line))
      continue;
    const bool numeric = parse(line, values);
    if (!numeric && first && !startsWithANumber(line)) { // a header line
      first = false;
      continue;
    }
    first = false;
    if (!numeric) {
      fail(lineNo, "a field is not a number: '" + line + "'");
      return;
    }
    if (values.size() != columns) {
      fail(lineNo, "expected " + std::to_string(columns) + " columns (" + columnNames + "), got " +
                       std::to_string(values.size()));
      return;
    }
    row(lineNo, values);
  }
}
