/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file demoCommon.h
  \brief Pieces shared by the two halves of the main demo (laser sequence, gravity-aided pose
  sequence): options, error statistics, the summary table, the accuracy bounds of --check and the
  progress line.
*/
#ifndef VSP_DEMO_COMMON_H
#define VSP_DEMO_COMMON_H

#include <iosfwd>
#include <string>
#include <vector>

//! Options of the demo.
struct vpDemoOptions
{
  std::string dataDir;        //!< folder holding laser_hard/ and gravity_sequence/
  std::string outputDir;      //!< where CSV and PNG files go
  bool check = false;         //!< compare the errors with their bounds (exit status)
  unsigned int maxFrames = 0; //!< process only the first frames of each sequence (0: all)
};

//! Running statistics of one error quantity (absolute values are accumulated).
class vpErrorStats
{
public:
  //! Adds one error (its absolute value).
  void add(double error);
  //! Number of samples.
  size_t count() const { return m_values.size(); }
  //! Mean of the absolute errors (NaN when empty).
  double mean() const;
  //! Standard deviation of the absolute errors (NaN when empty).
  double stddev() const;
  //! Median of the absolute errors (NaN when empty).
  double median() const;
  //! Largest absolute error (NaN when empty).
  double max() const;

private:
  std::vector<double> m_values;
};

//! One error quantity of a method, with its display unit and scale.
struct vpErrorColumn
{
  std::string name;   //!< e.g. "altitude"
  std::string unit;   //!< e.g. "mm"
  double scale;       //!< multiplies the stored values for display (e.g. 1000 for m -> mm)
  vpErrorStats stats; //!< the errors, in SI units (m, rad)
};

//! Summary of one method over a sequence.
struct vpMethodSummary
{
  std::string method;                //!< method name as printed
  unsigned int frames = 0;           //!< frames attempted
  unsigned int successes = 0;        //!< frames with a result
  double totalTimeMs = 0.0;          //!< time spent in the estimator
  std::vector<vpErrorColumn> errors; //!< error quantities, in the order printed
};

//! An accuracy bound checked by --check: \e quantity of \e method must not exceed \e value (display unit).
struct vpAccuracyBound
{
  std::string method;    //!< method name as in vpMethodSummary
  std::string quantity;  //!< error column name
  std::string statistic; //!< "mean", "median" or "max"
  double value;          //!< bound in the display unit
  std::string why;       //!< where the bound comes from
};

/*!
  Prints a table: one line per method with its success count, mean +/- std and median of each error
  and its time, then \e note (what the reader needs to interpret the table) when it is not empty.
*/
void printSummary(std::ostream &os, const std::string &title, const std::vector<vpMethodSummary> &summaries,
                  const std::string &note);

/*!
  Compares the summaries with the bounds and with a minimum success rate; prints each failure.
  \return true when every bound holds.
*/
bool checkBounds(std::ostream &os, const std::vector<vpMethodSummary> &summaries,
                 const std::vector<vpAccuracyBound> &bounds, double minSuccessRate);

//! A progress line "label: frame k/n", rewritten in place on a terminal, every tenth frame otherwise.
class vpProgress
{
public:
  vpProgress(const std::string &label, size_t total);
  //! Reports that frame \e index (0-based) is being processed.
  void update(size_t index);
  //! Ends the progress line.
  void done();

private:
  std::string m_label;
  size_t m_total;
  bool m_terminal;
};

/*!
  Runs the laser part; \e note receives a line on the detection for the summary.
  \return false (with a message on stderr) when the data cannot be read.
*/
bool runLaserDemo(const vpDemoOptions &options, std::vector<vpMethodSummary> &summaries, std::string &note,
                  std::vector<std::string> &writtenFiles);

/*!
  Runs the gravity-aided pose part; \e note receives a line on the mismatched points for the summary.
  \return false (with a message on stderr) when the data cannot be read.
*/
bool runGravityDemo(const vpDemoOptions &options, std::vector<vpMethodSummary> &summaries, std::string &note,
                    std::vector<std::string> &writtenFiles);

//! Bounds of --check for the laser part (values and reasons in demoLaser.cpp).
std::vector<vpAccuracyBound> laserBounds();
//! Bounds of --check for the gravity part (values and reasons in demoGravity.cpp).
std::vector<vpAccuracyBound> gravityBounds();

//! Angle difference wrapped to (-pi, pi].
double angleDifference(double a, double b);

#endif
