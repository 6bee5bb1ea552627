/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpCsvTools.h
  \brief Small helpers shared by the example programs: strict number conversion, CSV field parsing
  with messages that name the file and line, and the "never overwrite an input" check.
*/
#ifndef VP_CSV_TOOLS_H
#define VP_CSV_TOOLS_H

#include <string>
#include <vector>

namespace vpCsvTools
{
//! Splits one CSV line on commas (no quoting: the project's files never need it); fields are trimmed
//! (vpIoTools::trim()), empty fields are kept in their place.
std::vector<std::string> split(const std::string &line);

//! Removes leading and trailing blanks (vpIoTools::trim(): spaces, tabs, carriage returns, new lines).
std::string trim(const std::string &s);

//! Converts the whole of \e text to a finite double (no blank, no trailing character). \return false otherwise.
bool toDouble(const std::string &text, double &value);

//! Converts the whole of \e text (an optional '-' and 1 to 18 digits) to an integer. \return false otherwise.
bool toInteger(const std::string &text, long long &value);

/*!
  Parses a finite double from the whole of \e field (no trailing characters).
  \return false with \e error ("<where>: column <column> ('<field>') is not a number") otherwise.
*/
bool parseDouble(const std::string &field, double &value, const std::string &where, const std::string &column,
                 std::string &error);

/*!
  Parses a non-negative integer from the whole of \e field.
  \return false with \e error naming \e where and \e column otherwise.
*/
bool parseIndex(const std::string &field, unsigned int &value, const std::string &where, const std::string &column,
                std::string &error);

//! "<file>:<line>" for messages.
std::string location(const std::string &file, unsigned int line);

//! True when both paths name the same existing file or directory (symbolic links resolved).
bool samePath(const std::string &a, const std::string &b);

/*!
  Refuses an output path that names one of the inputs.
  \return false with \e error ("refusing to overwrite input file ...") when \e output is one of \e inputs.
*/
bool checkOutputIsNotInput(const std::string &output, const std::vector<std::string> &inputs, std::string &error);

/*!
  Refuses outputs (the empty ones left out) of which one names an input, or two name the same file.
  \return false with \e error naming them.
*/
bool checkOutputs(const std::vector<std::string> &outputs, const std::vector<std::string> &inputs, std::string &error);

//! Shortest decimal text (15 to 17 significant digits) that reads back as exactly \e value; "nan" for NaN.
std::string formatDouble(double value);
} // namespace vpCsvTools

#endif
