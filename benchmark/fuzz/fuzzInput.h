/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*!
  \file fuzzInput.h
  \brief Turns fuzzer bytes into the doubles the estimators see: raw IEEE bit patterns (NaN, inf,
  denormals), special values, moderate reals and small integers, so that both garbage and
  nearly-valid geometry are reached.
*/
#ifndef VSP_FUZZ_INPUT_H
#define VSP_FUZZ_INPUT_H

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <fuzzer/FuzzedDataProvider.h>

#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>

namespace vspFuzz
{
//! One double, drawn from a mix of encodings chosen by the first byte.
inline double consumeDouble(FuzzedDataProvider &fdp)
{
  switch (fdp.ConsumeIntegralInRange<int>(0, 4)) {
  case 0: { // any bit pattern, NaN and infinities included
    const uint64_t bits = fdp.ConsumeIntegral<uint64_t>();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof(v));
    return v;
  }
  case 1: {
    // Sixteen values, kept as written.
    // clang-format off
    static const double special[] = {0.0, -0.0, 1.0, -1.0, 1e-300, -1e-300, 1e300, -1e300,
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::denorm_min(), 1e-8, 1e8, 0.5, 2.0};
    // clang-format on
    return special[fdp.ConsumeIntegralInRange<int>(0, 15)];
  }
  case 2:
    return static_cast<double>(fdp.ConsumeIntegralInRange<int>(-4, 4));
  case 3:
    return fdp.ConsumeFloatingPointInRange<double>(-10.0, 10.0);
  default:
    return fdp.ConsumeFloatingPointInRange<double>(-1.0, 1.0);
  }
}

//! A homogeneous matrix: usually a true rigid motion (theta-u + translation), sometimes raw entries.
inline vpHomogeneousMatrix consumePose(FuzzedDataProvider &fdp)
{
  if (fdp.ConsumeIntegralInRange<int>(0, 7) == 0) {
    vpHomogeneousMatrix M;
    for (unsigned int r = 0; r < 3; ++r) {
      for (unsigned int c = 0; c < 4; ++c) {
        M[r][c] = consumeDouble(fdp);
      }
    }
    return M;
  }
  const double tx = consumeDouble(fdp), ty = consumeDouble(fdp), tz = consumeDouble(fdp);
  const double rx = consumeDouble(fdp), ry = consumeDouble(fdp), rz = consumeDouble(fdp);
  vpHomogeneousMatrix M;
  if (std::isfinite(rx) && std::isfinite(ry) && std::isfinite(rz) && std::abs(rx) + std::abs(ry) + std::abs(rz) < 1e6) {
    M.buildFrom(tx, ty, tz, rx, ry, rz);
  } else {
    M[0][3] = tx;
    M[1][3] = ty;
    M[2][3] = tz;
  }
  return M;
}

//! True when every entry of the 3x4 top of \e M is finite and its 3x3 block is a rotation.
inline bool isFiniteRigid(const vpHomogeneousMatrix &M)
{
  for (unsigned int r = 0; r < 3; ++r) {
    for (unsigned int c = 0; c < 4; ++c) {
      if (!std::isfinite(M[r][c])) {
        return false;
      }
    }
  }
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      double dot = 0.0;
      for (unsigned int k = 0; k < 3; ++k) {
        dot += M[k][i] * M[k][j];
      }
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-6) {
        return false;
      }
    }
  }
  return true;
}

//! Applies the setting \e set; one refused with a vpException keeps its previous value, and the run goes on.
template <typename Set> void tryApply(Set set)
{
  try {
    set();
  } catch (const vpException &) {
    // Refused with a clear error: the setting keeps its previous value.
  }
}

//! tryApply(\e set) when the input says so (one byte).
template <typename Set> void maybeApply(FuzzedDataProvider &fdp, Set set)
{
  if (fdp.ConsumeBool()) {
    tryApply(set);
  }
}

//! Stops the run: libFuzzer reports the input that led here as a crash.
[[noreturn]] inline void fail(const char *what)
{
  std::fprintf(stderr, "FUZZ FAILURE: %s\n", what);
  std::abort();
}

/*!
  The body of LLVMFuzzerTestOneInput: \e run(provider) on the input bytes. A vpException is the
  documented refusal of invalid input and ends the input quietly; any other exception escapes, and
  libFuzzer reports it as a crash.
*/
template <typename Run> int runInput(const uint8_t *data, size_t size, Run run)
{
  FuzzedDataProvider fdp(data, size);
  try {
    run(fdp);
  } catch (const vpException &) {
    // Invalid input refused with a clear error: the documented behaviour.
  }
  return 0;
}
} // namespace vspFuzz

#endif
