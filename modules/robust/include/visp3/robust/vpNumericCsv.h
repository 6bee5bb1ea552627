/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpNumericCsv.h
  \brief The row loop of the numeric CSV files both modules read (the IMU streams of
  vpImuGravity::loadCsv() and vpLaserConicFilter::loadImuCsv()): comments, blank lines and one header
  line skipped, a fixed number of columns, every error located by its line.

  It lives in the robust module because both modules depend on it and neither on the other; each
  caller keeps its own field rule (which separators, which numbers) and its own exception.
*/
#ifndef VP_NUMERIC_CSV_H
#define VP_NUMERIC_CSV_H

#include <cstddef>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include <visp3/core/vpConfig.h>

/*!
  Splits a CSV line into numbers: fields separated by commas, each a number (strtod's syntax, nan and inf
  included: the caller judges the values) with optional blanks around it. False when a field is empty or not a
  number: an empty field is not skipped, so that the columns after it do not shift.
*/
VISP_EXPORT bool vpParseCsvNumbers(const std::string &line, std::vector<double> &values);

/*!
  Reads the data rows of a numeric CSV stream (an opened file), in order.

  Blank lines and lines whose first non-blank character is `#` are skipped, and a UTF-8 byte-order mark before
  the first line. The first other line is a header when \e parse refuses it and it does not start with a number
  (a first data row with a typo is an error, not a header); every line after it must be accepted by \e parse
  and hold \e columns numbers.

  \param in : the stream, read to its end (the caller opens the file and reports when it cannot).
  \param columns : the number of values of every data row.
  \param columnNames : the columns in words, for the error message (e.g. "timestamp, wx, wy, wz, ax, ay, az").
  \param parse : splits a line into numbers; returns false when a field is not a number.
  \param row : called with the line number (from 1) and the numbers of each data row.
  \param fail : called with the line number and the reason when a field is not a number or a row has
  another number of columns; it is expected to throw the caller's exception, and reading stops there
  when it does not.
*/
VISP_EXPORT void vpReadNumericCsv(std::istream &in, size_t columns, const std::string &columnNames,
                                  const std::function<bool(const std::string &, std::vector<double> &)> &parse,
                                  const std::function<void(size_t, const std::vector<double> &)> &row,
                                  const std::function<void(size_t, const std::string &)> &fail);

#endif
