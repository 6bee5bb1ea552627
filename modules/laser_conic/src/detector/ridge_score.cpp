/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The red-dominance score of the ridge detector in one pass over the RGBA buffer (no colour conversion),
// with the block flags that let the candidate passes skip the blocks without a high score.
#include "ridge_score.h"

#include <algorithm>

#include "ridge_simd.h"

namespace vsp::laser_detector
{
namespace
{
// Scores n pixels starting at a column multiple of 16, and sets the flag of each block of 16 columns
// (flags[0] for the first) to 0xFF when a score of the block reaches the threshold, else 0: no pixel of an
// unflagged block can be a candidate (a candidate's score exceeds its background by the threshold), so
// the candidate passes skip these blocks, most of a frame, without reading their scores again. Plain C++
// from pixel j on (the vectorised versions below end with it).
void scoreSpanScalar(const unsigned char *rgba, unsigned char *score, int j, int n, int saturation, int threshold,
                     unsigned char *flags)
{
  for (; j < n; ++j) {
    if (j % 16 == 0)
      flags[j >> 4] = 0;
    score[j] = scorePixel(rgba + 4 * j, saturation);
    if (score[j] >= threshold)
      flags[j >> 4] = 0xFF;
  }
}

#if defined(__SSE2__)
// The constants of the vectorised score.
struct ScoreConstants
{
  __m128i thresholdBytes, low8, sat, zero, ramp, third, rampStart;
  ScoreConstants(int saturation, int threshold)
    : thresholdBytes(_mm_set1_epi8(static_cast<char>(threshold))), low8(_mm_set1_epi32(0xFF)),
      sat(_mm_set1_epi16(static_cast<short>(saturation))), zero(_mm_setzero_si128()),
      ramp(_mm_set1_epi16(RidgeTuning::saturationRamp)), third(_mm_set1_epi16(2185)),
      rampStart(_mm_set1_epi32(std::max(0, saturation - RidgeTuning::saturationRamp)))
  {
  }
};

// 0xFF when a score of the 16 reaches the threshold, else 0.
inline unsigned char blockFlag(__m128i s, const ScoreConstants &k)
{
  return _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_max_epu8(s, k.thresholdBytes), s)) ? 0xFF : 0;
}

// Score of the 16 pixels from rgba (16-bit lanes, the same integer arithmetic as scorePixel()) and their flag.
inline void scoreBlockRamp(const unsigned char *rgba, unsigned char *score, unsigned char *flag,
                           const ScoreConstants &k)
{
  __m128i half[2];
  for (int h = 0; h < 2; ++h) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i *>(rgba + 4 * (8 * h)));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i *>(rgba + 4 * (8 * h + 4)));
    const __m128i r = _mm_packs_epi32(_mm_and_si128(a, k.low8), _mm_and_si128(b, k.low8));
    const __m128i g =
        _mm_packs_epi32(_mm_and_si128(_mm_srli_epi32(a, 8), k.low8), _mm_and_si128(_mm_srli_epi32(b, 8), k.low8));
    const __m128i bl =
        _mm_packs_epi32(_mm_and_si128(_mm_srli_epi32(a, 16), k.low8), _mm_and_si128(_mm_srli_epi32(b, 16), k.low8));
    const __m128i m = _mm_max_epi16(g, bl);
    const __m128i t = _mm_min_epi16(_mm_max_epi16(_mm_sub_epi16(k.sat, r), k.zero), k.ramp);
    const __m128i w = _mm_mulhi_epu16(_mm_mullo_epi16(m, t), k.third);
    half[h] = _mm_max_epi16(_mm_sub_epi16(r, w), k.zero);
  }
  const __m128i s = _mm_packus_epi16(half[0], half[1]);
  _mm_storeu_si128(reinterpret_cast<__m128i *>(score), s);
  *flag = blockFlag(s, k);
}

// The same, faster when no red channel of the 16 reaches the ramp (nearly every block of a frame): the
// weight is then exactly 1 (m x 30 x 2185 >> 16 = m for m <= 255) and the score is the saturated byte
// difference R - max(G, B), computed in place in byte 0 of the RGBA lanes, without the 16-bit products.
inline void scoreBlock(const unsigned char *rgba, unsigned char *score, unsigned char *flag, const ScoreConstants &k)
{
  const __m128i *in = reinterpret_cast<const __m128i *>(rgba);
  const __m128i a0 = _mm_loadu_si128(in), a1 = _mm_loadu_si128(in + 1), a2 = _mm_loadu_si128(in + 2),
                a3 = _mm_loadu_si128(in + 3);
  const __m128i redMax = _mm_and_si128(_mm_max_epu8(_mm_max_epu8(a0, a1), _mm_max_epu8(a2, a3)), k.low8);
  if (_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_subs_epu8(redMax, k.rampStart), k.zero)) != 0xFFFF) {
    scoreBlockRamp(rgba, score, flag, k);
    return;
  }
  auto dominance = [&](__m128i a) {
    return _mm_and_si128(_mm_subs_epu8(a, _mm_max_epu8(_mm_srli_epi32(a, 8), _mm_srli_epi32(a, 16))), k.low8);
  };
  const __m128i s =
      _mm_packus_epi16(_mm_packs_epi32(dominance(a0), dominance(a1)), _mm_packs_epi32(dominance(a2), dominance(a3)));
  _mm_storeu_si128(reinterpret_cast<__m128i *>(score), s);
  *flag = blockFlag(s, k);
}

// scoreSpanScalar() 16 pixels at a time (SSE2).
void scoreSpanSse2(const unsigned char *rgba, unsigned char *score, int n, int saturation, int threshold,
                   unsigned char *flags)
{
  const ScoreConstants k(saturation, threshold);
  int j = 0;
  for (; j + 16 <= n; j += 16)
    scoreBlock(rgba + 4 * j, score + j, flags + (j >> 4), k);
  scoreSpanScalar(rgba, score, j, n, saturation, threshold, flags);
}

#if VSP_DETECTOR_AVX2
// R - max(G, B) of 8 RGBA pixels, saturated at 0, in byte 0 of their 32-bit lanes (the others 0).
__attribute__((target("avx2"))) inline __m256i dominance8(__m256i a, __m256i low8)
{
  return _mm256_and_si256(_mm256_subs_epu8(a, _mm256_max_epu8(_mm256_srli_epi32(a, 8), _mm256_srli_epi32(a, 16))),
                          low8);
}

// The channel at bit \e shift of the 16 RGBA pixels of a and b (8 each), in 16-bit lanes (AVX2).
__attribute__((target("avx2"))) inline __m256i channel16(__m256i a, __m256i b, int shift, __m256i low8)
{
  return _mm256_packs_epi32(_mm256_and_si256(_mm256_srli_epi32(a, shift), low8),
                            _mm256_and_si256(_mm256_srli_epi32(b, shift), low8));
}

// The score of the 16 pixels of a and b (8 each) with the ramp weight, in 16-bit lanes: scoreBlockRamp()'s
// arithmetic on twice the pixels; the packs leave them in the order of the 128-bit lanes (as dominance8()'s).
__attribute__((target("avx2"))) inline __m256i rampScore16(__m256i a, __m256i b, __m256i low8, __m256i sat,
                                                           __m256i ramp, __m256i third)
{
  const __m256i zero = _mm256_setzero_si256();
  const __m256i r = channel16(a, b, 0, low8), m = _mm256_max_epi16(channel16(a, b, 8, low8), channel16(a, b, 16, low8));
  const __m256i t = _mm256_min_epi16(_mm256_max_epi16(_mm256_sub_epi16(sat, r), zero), ramp);
  const __m256i w = _mm256_mulhi_epu16(_mm256_mullo_epi16(m, t), third);
  return _mm256_max_epi16(_mm256_sub_epi16(r, w), zero);
}

// scoreSpanScalar() 32 pixels at a time (AVX2), on processors that have it (see scoreSpan()).
__attribute__((target("avx2"))) void scoreSpanAvx2(const unsigned char *rgba, unsigned char *score, int n,
                                                   int saturation, int threshold, unsigned char *flags)
{
  const ScoreConstants k(saturation, threshold);
  const __m256i low8 = _mm256_set1_epi32(0xFF), zero = _mm256_setzero_si256();
  const __m256i rampStart = _mm256_set1_epi32(std::max(0, saturation - RidgeTuning::saturationRamp));
  const __m256i thresholdBytes = _mm256_set1_epi8(static_cast<char>(threshold));
  // The packs work within 128-bit lanes: they leave the groups of 4 pixels in the order 0 2 4 6 1 3 5 7.
  const __m256i groups = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  const __m256i sat = _mm256_set1_epi16(static_cast<short>(saturation)),
                ramp = _mm256_set1_epi16(RidgeTuning::saturationRamp), third = _mm256_set1_epi16(2185);
  int j = 0;
  for (; j + 32 <= n; j += 32) {
    const __m256i *in = reinterpret_cast<const __m256i *>(rgba + 4 * j);
    const __m256i a0 = _mm256_loadu_si256(in), a1 = _mm256_loadu_si256(in + 1), a2 = _mm256_loadu_si256(in + 2),
                  a3 = _mm256_loadu_si256(in + 3);
    const __m256i redMax = _mm256_and_si256(_mm256_max_epu8(_mm256_max_epu8(a0, a1), _mm256_max_epu8(a2, a3)), low8);
    // A red above the ramp start (the warm patches of a colourful floor under a lamp): 16-bit arithmetic.
    const bool inRamp = _mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_subs_epu8(redMax, rampStart), zero)) != -1;
    const __m256i packed = inRamp ? _mm256_packus_epi16(rampScore16(a0, a1, low8, sat, ramp, third),
                                                        rampScore16(a2, a3, low8, sat, ramp, third))
                                  : _mm256_packus_epi16(_mm256_packs_epi32(dominance8(a0, low8), dominance8(a1, low8)),
                                                        _mm256_packs_epi32(dominance8(a2, low8), dominance8(a3, low8)));
    const __m256i s = _mm256_permutevar8x32_epi32(packed, groups);
    _mm256_storeu_si256(reinterpret_cast<__m256i *>(score + j), s);
    const unsigned int reached =
        static_cast<unsigned int>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_max_epu8(s, thresholdBytes), s)));
    flags[j >> 4] = (reached & 0xFFFFu) ? 0xFF : 0;
    flags[(j >> 4) + 1] = (reached >> 16) ? 0xFF : 0;
  }
  for (; j + 16 <= n; j += 16)
    scoreBlock(rgba + 4 * j, score + j, flags + (j >> 4), k);
  scoreSpanScalar(rgba, score, j, n, saturation, threshold, flags);
}
#endif
#endif
} // namespace

void scoreSpan(const unsigned char *rgba, unsigned char *score, int n, int saturation, int threshold,
               unsigned char *flags, vpLaserConicDetector::vpInstructionSet instructions)
{
#if defined(__SSE2__)
#if VSP_DETECTOR_AVX2
  if (instructions == vpLaserConicDetector::INSTRUCTIONS_AVX2) {
    scoreSpanAvx2(rgba, score, n, saturation, threshold, flags);
    return;
  }
#endif
  if (instructions != vpLaserConicDetector::INSTRUCTIONS_SCALAR) {
    scoreSpanSse2(rgba, score, n, saturation, threshold, flags);
    return;
  }
#endif
  (void)instructions;
  scoreSpanScalar(rgba, score, 0, n, saturation, threshold, flags);
}
} // namespace vsp::laser_detector
