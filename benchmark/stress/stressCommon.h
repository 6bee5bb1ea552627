/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file stressCommon.h
  \brief Outcome counting shared by the stress programs: the classification of one answer, the
  summary line and the command line (--n, --seed, --verbose and the solver choice).
*/
#ifndef VSP_STRESS_COMMON_H
#define VSP_STRESS_COMMON_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "vpCommandLine.h"
#include "vpCsvTools.h"
#include "vspBenchUtils.h"

namespace vspStress
{
//! An answer within this error (rad for rotations and normals, relative for distances) is correct.
constexpr double kTolerance = 1e-6;
//! Configurations printed per kind of failure: enough to debug, not enough to flood the log.
constexpr int kMaxDumps = 5;

//! Outcome counts of one solver over the random configurations.
struct Tally
{
  long correct = 0;    //!< an answer within kTolerance of the truth
  long degenerate = 0; //!< degenerate by construction: any outcome is accepted
  long ambiguous = 0;  //!< another answer that explains the data exactly (the data admit two)
  long noAnswer = 0;   //!< no answer on a non-degenerate configuration
  long wrong = 0;      //!< answers, none correct nor an exact alternative: the failure the program is for
  long skipped = 0;    //!< the generator could not build the configuration
  double worstCorrectError = 0.0;
};

/*!
  Counts one outcome. \e best is the smallest error of the answers (inf if none), \e exactAlternative
  tells that an answer reproduces the data exactly although it is not the truth. \e dump(what) prints
  the configuration: for the first wrong answers, and for the first non-answers when \e verbose.
*/
template <typename Dump>
void classify(Tally &t, bool degenerate, bool answered, double best, bool exactAlternative, bool verbose, Dump dump)
{
  if (degenerate) {
    ++t.degenerate;
  } else if (!answered) {
    ++t.noAnswer;
    if (verbose && t.noAnswer <= kMaxDumps) {
      dump("no answer");
    }
  } else if (best <= kTolerance) {
    ++t.correct;
    t.worstCorrectError = std::max(t.worstCorrectError, best);
  } else if (exactAlternative) {
    ++t.ambiguous;
  } else {
    ++t.wrong;
    if (t.wrong <= kMaxDumps) {
      dump("WRONG");
    }
  }
}

//! Prints the counts of one solver; \return true when there is no wrong answer.
inline bool report(const char *name, long count, const Tally &t)
{
  std::printf("%-14s n=%ld  correct=%ld  degenerate=%ld  ambiguous=%ld  no-answer=%ld  wrong=%ld  skipped=%ld  "
              "worst-correct-error=%.2e\n",
              name, count, t.correct, t.degenerate, t.ambiguous, t.noAnswer, t.wrong, t.skipped, t.worstCorrectError);
  std::fflush(stdout);
  return t.wrong == 0;
}

//! The command line of a stress program.
struct Options
{
  std::string solver; //!< value of \e solverOption
  long count = 0;     //!< --n: number of configurations (scientific notation accepted)
  unsigned long seed = 1;
  bool verbose = false;
};

/*!
  Reads the command line strictly (vpCommandLine): \e solverOption must be one of \e solvers, --n a
  whole number of configurations in [1, 1e12] (scientific notation accepted: 1e7), --seed a whole
  number; an unknown option, a missing or malformed value is an error naming the option.
  \return true when the program should run; otherwise main() returns \e exitStatus (0 after --help).
*/
inline bool parseOptions(int argc, char **argv, const char *solverOption, const std::vector<std::string> &solvers,
                         const char *defaultSolver, const char *defaultCount, Options &o, int &exitStatus)
{
  o.solver = defaultSolver;
  double count = std::atof(defaultCount);
  unsigned int seed = 1;
  std::string choices;
  for (const std::string &s : solvers)
    choices += (choices.empty() ? "" : "|") + s;
  vpCommandLine cli(std::string("[") + solverOption + " " + choices + "] [--n N] [--seed S] [--verbose]",
                    "Random exact configurations through the minimal solvers; counts wrong answers "
                    "(exit status 1 when there is one).");
  cli.addChoice(solverOption, o.solver, solvers, "solver",
                std::string("solver to stress (default ") + defaultSolver + ")");
  cli.addOption("--n", "N", std::string("number of configurations (default ") + defaultCount + ")",
                [&count](const std::string &value, std::string &error) {
                  if (!vpCsvTools::toDouble(value, count) || count < 1 || count > 1e12 || count != std::floor(count)) {
                    error = "--n expects a whole number in [1, 1e12], got '" + value + "'";
                    return false;
                  }
                  return true;
                });
  cli.addUnsigned("--seed", seed, "S", "seed of the random configurations (default 1)");
  cli.addFlag("--verbose", o.verbose, "print the first failing configurations of each kind");
  if (!cli.parse(argc, argv)) {
    exitStatus = cli.exitStatus();
    return false;
  }
  o.count = static_cast<long>(count);
  o.seed = seed;
  return true;
}
} // namespace vspStress

#endif
