/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpCommandLine.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <sstream>

#include "vpCsvTools.h"

namespace
{
std::string lowercase(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

//! "A, B or C" (\e last: "or", "and").
std::string enumerate(const std::vector<std::string> &items, const std::string &last)
{
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : (i + 1 == items.size() ? " " + last + " " : ", ")) + items[i];
  return text;
}

//! Whole number in [minimum, maximum], or an error naming the option.
bool parseInteger(const std::string &name, const std::string &value, long long minimum, long long maximum,
                  long long &result, std::string &error)
{
  if (!vpCsvTools::toInteger(value, result) || result < minimum || result > maximum) {
    error = name + " expects a whole number in [" + std::to_string(minimum) + ", " + std::to_string(maximum) +
            "], got '" + value + "'";
    return false;
  }
  return true;
}
} // namespace

vpCommandLine::vpCommandLine(const std::string &synopsis, const std::string &description)
  : m_synopsis(synopsis), m_description(description), m_program("program"), m_exitStatus(EXIT_SUCCESS)
{
}

void vpCommandLine::addFlag(const std::string &name, bool &target, const std::string &help, bool value)
{
  Option option;
  option.name = name;
  option.help = help;
  option.set = [&target, value]() { target = value; };
  m_options.push_back(option);
}

void vpCommandLine::addOption(const std::string &name, const std::string &valueName, const std::string &help,
                              const vpApply &apply)
{
  Option option;
  option.name = name;
  option.valueName = valueName;
  option.help = help;
  option.apply = apply;
  m_options.push_back(option);
}

void vpCommandLine::addString(const std::string &name, std::string &target, const std::string &valueName,
                              const std::string &help)
{
  addOption(name, valueName, help, [&target](const std::string &value, std::string &) {
    target = value;
    return true;
  });
}

void vpCommandLine::addChoice(const std::string &name, std::string &target, const std::vector<std::string> &choices,
                              const std::string &valueName, const std::string &help)
{
  const std::string what = lowercase(valueName);
  addOption(name, valueName, help, [&target, choices, what](const std::string &value, std::string &error) {
    if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
      error = "unknown " + what + " '" + value + "' (" + enumerate(choices, "or") + ")";
      return false;
    }
    target = value;
    return true;
  });
}

void vpCommandLine::addDouble(const std::string &name, double &target, const std::string &valueName,
                              const std::string &help, vpNumberDomain domain)
{
  addOption(name, valueName, help, [name, &target, domain](const std::string &value, std::string &error) {
    double v = 0.0;
    const bool valid = vpCsvTools::toDouble(value, v);
    if (!valid || (domain == POSITIVE && !(v > 0.0)) || (domain == NON_NEGATIVE && !(v >= 0.0))) {
      const char *kind = domain == POSITIVE ? "a positive" : (domain == NON_NEGATIVE ? "a non-negative" : "a finite");
      error = name + " expects " + kind + " number, got '" + value + "'";
      return false;
    }
    target = v;
    return true;
  });
}

void vpCommandLine::addUnsigned(const std::string &name, unsigned int &target, const std::string &valueName,
                                const std::string &help, unsigned int minimum, unsigned int maximum)
{
  addOption(name, valueName, help, [=, &target](const std::string &value, std::string &error) {
    long long v = 0;
    if (!parseInteger(name, value, minimum, maximum, v, error))
      return false;
    target = static_cast<unsigned int>(v);
    return true;
  });
}

void vpCommandLine::addInt(const std::string &name, int &target, const std::string &valueName, const std::string &help,
                           int minimum, int maximum)
{
  addOption(name, valueName, help, [=, &target](const std::string &value, std::string &error) {
    long long v = 0;
    if (!parseInteger(name, value, minimum, maximum, v, error))
      return false;
    target = static_cast<int>(v);
    return true;
  });
}

const vpCommandLine::Option *vpCommandLine::find(const std::string &name) const
{
  for (const Option &option : m_options)
    if (option.name == name)
      return &option;
  return nullptr;
}

bool vpCommandLine::parse(int argc, const char *const argv[])
{
  m_program = argc > 0 ? argv[0] : "program";
  m_given.clear();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      printUsage(std::cout);
      m_exitStatus = EXIT_SUCCESS;
      return false;
    }
    const Option *option = find(arg);
    std::string error;
    if (option == nullptr && m_positional != nullptr && !arg.empty() && arg[0] != '-') {
      m_positional->push_back(arg);
      continue;
    }
    if (option == nullptr)
      error = "unknown option '" + arg + "'";
    else if (option->apply && i + 1 >= argc)
      error = "option " + arg + " needs a value (" + option->valueName + ")";
    else if (option->apply)
      option->apply(argv[++i], error);
    else
      option->set();
    if (!error.empty()) {
      m_exitStatus = fail(error);
      return false;
    }
    m_given.push_back(arg);
  }
  std::vector<std::string> missing;
  for (const std::string &name : m_required)
    if (!given(name))
      missing.push_back(name);
  if (!missing.empty()) {
    m_exitStatus =
        fail("missing required option" + std::string(missing.size() > 1 ? "s " : " ") + enumerate(missing, "and"));
    return false;
  }
  return true;
}

void vpCommandLine::addPositional(std::vector<std::string> &target, const std::string &valueName,
                                  const std::string &help)
{
  m_positional = &target;
  m_positionalName = valueName;
  m_positionalHelp = help;
}

void vpCommandLine::require(const std::vector<std::string> &names)
{
  m_required.insert(m_required.end(), names.begin(), names.end());
}

bool vpCommandLine::given(const std::string &name) const
{
  return std::find(m_given.begin(), m_given.end(), name) != m_given.end();
}

int vpCommandLine::fail(const std::string &error) const
{
  // The usage would bury the message: point to it instead.
  std::cerr << m_program << ": " << error << "\n(" << m_program << " --help lists the options)" << std::endl;
  return EXIT_FAILURE;
}

void vpCommandLine::printUsage(std::ostream &os) const
{
  os << "Usage: " << m_program << " " << m_synopsis << "\n";
  if (!m_description.empty())
    os << m_description << "\n";
  // One row per option, then --help; the help texts start in one column.
  std::vector<std::pair<std::string, std::string> > rows;
  for (const Option &option : m_options)
    rows.emplace_back(option.name + (option.valueName.empty() ? "" : " " + option.valueName), option.help);
  if (m_positional != nullptr)
    rows.emplace_back(m_positionalName, m_positionalHelp);
  rows.emplace_back("--help", "this message");
  size_t width = 0;
  for (const auto &row : rows)
    width = std::max(width, row.first.size());
  for (const auto &row : rows) {
    // A help text may span several lines: continuation lines are aligned with the first.
    std::istringstream lines(row.second);
    std::string line;
    std::string head = "  " + row.first + std::string(width + 2 - row.first.size(), ' ');
    while (std::getline(lines, line)) {
      os << head << line << "\n";
      head = std::string(width + 4, ' ');
    }
  }
}

int vpCommandLine::runGuarded(int (*program)(int, char **), int argc, char **argv)
{
  try {
    return program(argc, argv);
  } catch (const std::exception &e) { // vpException included
    std::cerr << (argc > 0 ? argv[0] : "program") << ": " << e.what() << std::endl;
  }
  return EXIT_FAILURE;
}
