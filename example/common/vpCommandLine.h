/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpCommandLine.h
  \brief Command-line options of the example programs, declared once with their help line and the
  variable they fill. Parsing is strict, so that every program reacts the same way to a typo: an
  unknown option, a missing value, a number with trailing characters or out of range, or a value
  outside a list of choices is an error naming the option. The usage text is built from the
  declarations, so it cannot drift from what the program accepts.
*/
#ifndef VP_COMMAND_LINE_H
#define VP_COMMAND_LINE_H

#include <climits>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

/*!
  \brief Declarative command-line parser (GNU-style long options, one value per option).

  \code
  vpCommandLine cli("--input FILE [--threshold T]", "Estimates something.");
  cli.addString("--input", opt.input, "FILE", "input file");
  cli.addDouble("--threshold", opt.threshold, "T", "inlier threshold (default 2)", vpCommandLine::POSITIVE);
  if (!cli.parse(argc, argv))
    return cli.exitStatus(); // --help printed the usage (0), or a bad command line was reported (1)
  \endcode
*/
class vpCommandLine
{
public:
  //! Values accepted by addDouble().
  enum vpNumberDomain {
    ANY,          //!< any finite number
    NON_NEGATIVE, //!< >= 0
    POSITIVE      //!< > 0
  };
  //! Applies the value of an option; \return false with \e error when the value is refused.
  typedef std::function<bool(const std::string &value, std::string &error)> vpApply;

  /*!
    \param synopsis : what follows the program name on the "Usage:" line.
    \param description : one or more lines printed under it.
  */
  vpCommandLine(const std::string &synopsis, const std::string &description);

  //! An option without value that sets \e target to \e value.
  void addFlag(const std::string &name, bool &target, const std::string &help, bool value = true);
  //! An option whose value is copied to \e target.
  void addString(const std::string &name, std::string &target, const std::string &valueName, const std::string &help);
  //! An option whose value must be one of \e choices ("unknown <valuename> 'x' (A, B or C)" otherwise).
  void addChoice(const std::string &name, std::string &target, const std::vector<std::string> &choices,
                 const std::string &valueName, const std::string &help);
  //! A finite number in \e domain.
  void addDouble(const std::string &name, double &target, const std::string &valueName, const std::string &help,
                 vpNumberDomain domain = ANY);
  //! A whole number in [minimum, maximum].
  void addUnsigned(const std::string &name, unsigned int &target, const std::string &valueName, const std::string &help,
                   unsigned int minimum = 0, unsigned int maximum = UINT_MAX);
  //! A whole number in [minimum, maximum] (programs whose counts are int).
  void addInt(const std::string &name, int &target, const std::string &valueName, const std::string &help, int minimum,
              int maximum = INT_MAX);
  //! An option with a value handled by \e apply (conversions the other kinds do not cover).
  void addOption(const std::string &name, const std::string &valueName, const std::string &help, const vpApply &apply);

  /*!
    Accepts arguments that are not options (they do not start with '-'), appended to \e target in
    their order; without this call such an argument is an error.
  */
  void addPositional(std::vector<std::string> &target, const std::string &valueName, const std::string &help);

  //! Makes options \e names mandatory: parse() fails when one of them is absent.
  void require(const std::vector<std::string> &names);

  /*!
    Parses argv[1..argc-1]. --help (or -h) prints the usage on stdout; an error is printed on stderr,
    with a pointer to --help.
    \return true when the program should run; otherwise main() should return exitStatus().
  */
  bool parse(int argc, const char *const argv[]);

  //! After parse() returned false: EXIT_SUCCESS after --help, EXIT_FAILURE after an error.
  int exitStatus() const { return m_exitStatus; }

  //! True when option \e name appeared on the parsed command line.
  bool given(const std::string &name) const;

  /*!
    Reports an error found after parsing (incompatible options, an output naming an input): prints
    "<program>: <error>" and a pointer to --help on stderr. \return EXIT_FAILURE, for main() to return.
  */
  int fail(const std::string &error) const;

  /*!
    Runs \e program(argc, argv) and returns its exit status; an exception that escapes it is
    reported on stderr with the program name and gives EXIT_FAILURE instead of std::terminate().
  */
  static int runGuarded(int (*program)(int, char **), int argc, char **argv);

  //! Prints the usage: synopsis, description and one aligned line per option.
  void printUsage(std::ostream &os) const;

private:
  struct Option
  {
    std::string name, valueName, help;
    vpApply apply;             //!< empty for a flag
    std::function<void()> set; //!< what a flag does
  };
  const Option *find(const std::string &name) const;

  std::string m_synopsis, m_description, m_program;
  std::vector<Option> m_options;
  std::vector<std::string> m_given, m_required;
  std::vector<std::string> *m_positional = nullptr; //!< where addPositional() arguments go
  std::string m_positionalName, m_positionalHelp;
  int m_exitStatus;
};

/*!
  The main() of a program whose options are a struct: \e declare fills it with the defaults' command
  line (`vpCommandLine commandLine(Options &)`), the command line is parsed, then run(options, cli) does
  the work and returns the exit status. After `--help` or a bad command line, the command line's exit
  status is returned and run() is not called.

  \code
  int main(int argc, char **argv) { return vpRunProgram(argc, argv, commandLine, run); }
  \endcode
*/
template <typename Options>
int vpRunProgram(int argc, char **argv, vpCommandLine (*declare)(Options &),
                 int (*run)(Options &, const vpCommandLine &))
{
  Options options; // the command line refers to its fields: it stays here while run() works
  vpCommandLine cli = declare(options);
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  return run(options, cli);
}

#endif
