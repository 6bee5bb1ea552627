/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// Tests of vpReadNumericCsv(): which lines are rows, their line numbers, and where reading fails.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <visp3/robust/vpNumericCsv.h>

namespace
{
//! Comma-separated numbers (the callers' rules are their own: this one is only for the test).
bool parseCommas(const std::string &line, std::vector<double> &values)
{
  values.clear();
  std::istringstream fields(line);
  std::string field;
  while (std::getline(fields, field, ',')) {
    size_t used = 0;
    try {
      values.push_back(std::stod(field, &used));
    } catch (const std::exception &) {
      return false;
    }
    if (used != field.size())
      return false;
  }
  return true;
}

struct Rows
{
  std::vector<size_t> lines;
  std::vector<std::vector<double> > values;
  size_t failLine = 0;
  std::string failure;
};

Rows read(const std::string &text, size_t columns)
{
  Rows r;
  std::istringstream in(text);
  try {
    vpReadNumericCsv(
        in, columns, "a, b", parseCommas,
        [&](size_t line, const std::vector<double> &v) {
          r.lines.push_back(line);
          r.values.push_back(v);
        },
        [&](size_t line, const std::string &what) {
          r.failLine = line;
          r.failure = what;
          throw std::runtime_error(what);
        });
  } catch (const std::runtime_error &) {
  }
  return r;
}
} // namespace

TEST(RobustNumericCsv, SkipsCommentsBlanksAndOneHeader)
{
  const Rows r = read("# comment\n\n  \r\nt,x\n1,2\n # another\n3,4.5\n", 2);
  ASSERT_EQ(r.lines, (std::vector<size_t>{5, 7}));
  EXPECT_EQ(r.values[1], (std::vector<double>{3.0, 4.5}));
  EXPECT_TRUE(r.failure.empty());
}

TEST(RobustNumericCsv, RowsWithoutHeader)
{
  const Rows r = read("1,2\n3,4\n", 2);
  EXPECT_EQ(r.lines, (std::vector<size_t>{1, 2}));
}

// Only the first non-comment line may be a header: a later text line is an error at its line.
TEST(RobustNumericCsv, FailsAtTheLineOfABadRow)
{
  Rows r = read("t,x\n1,2\nx,3\n5,6\n", 2);
  EXPECT_EQ(r.lines, (std::vector<size_t>{2}));
  EXPECT_EQ(r.failLine, 3u);
  EXPECT_EQ(r.failure, "a field is not a number: 'x,3'");

  r = read("1,2\n1,2,3\n", 2);
  EXPECT_EQ(r.failLine, 2u);
  EXPECT_EQ(r.failure, "expected 2 columns (a, b), got 3");
}

// The first line was a header whenever parse refused it: a data row with a typo ("0.0.1") or behind the UTF-8
// byte-order mark that spreadsheets write was dropped without a word, the file read from its second sample. A
// first line that starts with a number is a row; the mark is skipped.
TEST(RobustNumericCsv, AFirstRowThatIsNoHeaderIsReadOrRefused)
{
  Rows r = read("\xEF\xBB\xBF"
                "0,1\n2,3\n",
                2);
  EXPECT_EQ(r.lines, (std::vector<size_t>{1, 2}));
  EXPECT_EQ(r.values[0], (std::vector<double>{0.0, 1.0}));
  r = read("\xEF\xBB\xBF"
           "t,x\n2,3\n",
           2); // a header after the mark is still one
  EXPECT_EQ(r.lines, (std::vector<size_t>{2}));
  r = read("0.0.1,1\n2,3\n", 2);
  EXPECT_TRUE(r.lines.empty());
  EXPECT_EQ(r.failLine, 1u);
  EXPECT_EQ(r.failure, "a field is not a number: '0.0.1,1'");
  r = read("nan,1\n2,3\n", 2); // parseCommas takes nan: the caller's rules judge it, not the header test
  EXPECT_EQ(r.lines, (std::vector<size_t>{1, 2}));
}

// The parser both IMU readers share: an empty field is refused, not skipped (a reader that split on blanks too read
// "0,0,,0,0,0,9.8,25" as seven numbers, every column after the gap shifted); blanks around a field are allowed;
// nan and inf are numbers, left to the caller to judge.
TEST(RobustNumericCsv, ParseCsvNumbersKeepsTheColumns)
{
  std::vector<double> v;
  EXPECT_FALSE(vpParseCsvNumbers("0,0,,0,0,0,9.8,25", v));
  EXPECT_FALSE(vpParseCsvNumbers("1,2,", v));
  EXPECT_FALSE(vpParseCsvNumbers("1 2,3", v));
  EXPECT_FALSE(vpParseCsvNumbers("1,1e999", v)); // out of range
  ASSERT_TRUE(vpParseCsvNumbers(" 1.5 ,\t-2,3e2\r", v));
  EXPECT_EQ(v, (std::vector<double>{1.5, -2.0, 300.0}));
  ASSERT_TRUE(vpParseCsvNumbers("nan,inf", v));
  EXPECT_TRUE(std::isnan(v[0]) && std::isinf(v[1]));
}

// A fail callback that returns (does not throw) stops the reading: no row after the bad one.
TEST(RobustNumericCsv, StopsWhenFailReturns)
{
  std::istringstream in("1,2\n3\n4,5\n");
  std::vector<size_t> lines, failures;
  vpReadNumericCsv(
      in, 2, "a, b", parseCommas, [&](size_t line, const std::vector<double> &) { lines.push_back(line); },
      [&](size_t line, const std::string &) { failures.push_back(line); });
  EXPECT_EQ(lines, (std::vector<size_t>{1}));
  EXPECT_EQ(failures, (std::vector<size_t>{2}));
}
