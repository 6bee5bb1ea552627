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
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--random") == 0 && i + 1 < argc) {
      const long n = std::stol(argv[++i]);
      std::mt19937 rng(1234);
      std::uniform_int_distribution<int> byte(0, 255), length(0, 4096);
      for (long k = 0; k < n; ++k) {
        std::vector<uint8_t> data(static_cast<size_t>(length(rng)));
        for (uint8_t &b : data) {
          b = static_cast<uint8_t>(byte(rng));
        }
        LLVMFuzzerTestOneInput(data.data(), data.size());
      }
      std::printf("%ld random inputs: no failure\n", n);
      continue;
    }
    std::ifstream file(argv[i], std::ios::binary);
    const std::vector<uint8_t> data((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(data.data(), data.size());
    std::printf("%s: no failure\n", argv[i]);
  }
  return 0;
}
