/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_simd.h
  \brief The vector instructions of the ridge detector (internal header): SSE2 where the compiler targets
  it, AVX2 code paths compiled for their functions only and chosen at run time (the library is built for
  any x86-64 processor), and the unaligned loads the passes share.
*/
#ifndef VP_LASER_RIDGE_SIMD_H
#define VP_LASER_RIDGE_SIMD_H

#include <cstddef>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VSP_DETECTOR_AVX2 1
#include <immintrin.h>
#else
#define VSP_DETECTOR_AVX2 0
#endif

namespace vsp::laser_detector
{
#if defined(__SSE2__)
//! The 16 bytes from p (unaligned).
inline __m128i load16(const unsigned char *p) { return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p)); }
#endif

//! Asks for the \e n bytes from p to be brought to cache (nothing without SSE2): for rows read far apart,
//! whose next one the processor cannot guess.
inline void prefetchBytes(const unsigned char *p, size_t n)
{
#if defined(__SSE2__)
  for (size_t b = 0; b < n; b += 64)
    _mm_prefetch(reinterpret_cast<const char *>(p + b), _MM_HINT_T0);
#else
  (void)p, (void)n;
#endif
}

#if VSP_DETECTOR_AVX2
//! The 32 bytes from p (unaligned, AVX2).
__attribute__((target("avx2"))) inline __m256i load32(const unsigned char *p)
{
  return _mm256_loadu_si256(reinterpret_cast<const __m256i *>(p));
}
#endif
} // namespace vsp::laser_detector

#endif
