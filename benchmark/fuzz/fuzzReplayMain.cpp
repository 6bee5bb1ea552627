/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzReplayMain.cpp
  \brief Without libFuzzer (g++ builds): runs a fuzz target on the files given on the command line,
  or on a fixed number of pseudo-random inputs, so that the targets stay compiled and a crashing
  input found by scripts/run_fuzz.sh can be replayed under a debugger.

  Usage: fuzz-<name>-replay [--random N] [file...]
*/
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "vpCommandLine.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
  unsigned int randomInputs = 0;
  std::vector<std::string> files;
  vpCommandLine cli("[--random N] [FILE...]", "Runs the fuzz target on N pseudo-random inputs, then on each FILE.");
  cli.addUnsigned("--random", randomInputs, "N", "number of pseudo-random inputs (seeded)", 1);
  cli.addPositional(files, "FILE", "an input to replay (a crash found by scripts/run_fuzz.sh)");
  if (!cli.parse(argc, argv))
    return cli.exitStatus();
  if (randomInputs > 0) {
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> byte(0, 255), length(0, 4096);
    for (unsigned int k = 0; k < randomInputs; ++k) {
      std::vector<uint8_t> data(static_cast<size_t>(length(rng)));
      for (uint8_t &b : data) {
        b = static_cast<uint8_t>(byte(rng));
      }
      LLVMFuzzerTestOneInput(data.data(), data.size());
    }
    std::printf("%u random inputs: no failure\n", randomInputs);
  }
  for (const std::string &name : files) {
    std::ifstream file(name, std::ios::binary);
    if (!file)
      return cli.fail("cannot read the input file '" + name + "'");
    const std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(data.data(), data.size());
    std::printf("%s: no failure\n", name.c_str());
  }
  return 0;
}
