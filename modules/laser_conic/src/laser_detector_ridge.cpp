/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The ridge detector of vpLaserConicDetector (DETECTION_RIDGE): red-dominance score in one pass over the
// RGBA buffer, top-hat candidates along rows and columns against a threshold estimated from the image,
// profile checks and sub-pixel centre around each candidate only, then a continuity filter; over the whole
// image coarse to fine (every 8th line first, the others near the long coarse chains; see detectRidge()).
#include "laser_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <cstring>
#include <numeric>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// AVX2 code paths, compiled for their functions only and chosen at run time (the library is built for any
// x86-64 processor).
#if defined(__SSE2__) && (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define VSP_DETECTOR_AVX2 1
#include <immintrin.h>
#else
#define VSP_DETECTOR_AVX2 0
#endif

namespace vsp::laser_detector
{
namespace
{
// Width (grey levels of the red channel) of the ramp below the saturation level over which the score goes
// from the red dominance to 255.
const int kSaturationRamp = 30;

// Score of n pixels: the red dominance R - w max(G, B), clipped to [0, 255], where w = 1 below the ramp
// (R <= saturation - 30), falls linearly to 0 at the saturation level and stays 0 above. A stripe whose red
// channel saturates (and a white saturated core) is thus a plateau of 255 joined continuously to its red
// flanks: no jump at the saturation level for the sensor noise to flicker on. Integer arithmetic without
// branch over the bytes of the RGBA buffer, so that the compiler vectorises it.
inline unsigned char scorePixel(const unsigned char *p, int saturation)
{
  const int r = p[0], g = p[1], b = p[2];
  const int m = g > b ? g : b;
  int t = saturation - r; // ramp weight x 30
  t = t < 0 ? 0 : (t > kSaturationRamp ? kSaturationRamp : t);
  const int s = r - (m * t * 2185 >> 16); // 2185 / 65536 = 1 / 30 (to 1e-4)
  return static_cast<unsigned char>(s < 0 ? 0 : s);
}

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
      ramp(_mm_set1_epi16(kSaturationRamp)), third(_mm_set1_epi16(2185)),
      rampStart(_mm_set1_epi32(std::max(0, saturation - kSaturationRamp)))
  {
  }
};

// 0xFF when a score of the 16 reaches the threshold, else 0.
inline unsigned char blockFlag(__m128i s, const ScoreConstants &k)
{
  return _mm_movemask_epi8(_mm_cmpeq_epi8(_mm_max_epu8(s, k.thresholdBytes), s)) ? 0xFF : 0;
}

// Score of the 16 pixels from rgba (16-bit lanes, the same integer arithmetic as scorePixel()) and their flag.
inline void scoreBlockRamp(const unsigned char *rgba, unsigned char *score, unsigned char *flag, const ScoreConstants &k)
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
  const __m128i s = _mm_packus_epi16(_mm_packs_epi32(dominance(a0), dominance(a1)),
                                     _mm_packs_epi32(dominance(a2), dominance(a3)));
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
  return _mm256_and_si256(_mm256_subs_epu8(a, _mm256_max_epu8(_mm256_srli_epi32(a, 8), _mm256_srli_epi32(a, 16))), low8);
}

// scoreSpanScalar() 32 pixels at a time (AVX2), on processors that have it (see scoreSpan()).
__attribute__((target("avx2"))) void scoreSpanAvx2(const unsigned char *rgba, unsigned char *score, int n,
                                                   int saturation, int threshold, unsigned char *flags)
{
  const ScoreConstants k(saturation, threshold);
  const __m256i low8 = _mm256_set1_epi32(0xFF), zero = _mm256_setzero_si256();
  const __m256i rampStart = _mm256_set1_epi32(std::max(0, saturation - kSaturationRamp));
  const __m256i thresholdBytes = _mm256_set1_epi8(static_cast<char>(threshold));
  // The packs work within 128-bit lanes: they leave the groups of 4 pixels in the order 0 2 4 6 1 3 5 7.
  const __m256i groups = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  int j = 0;
  for (; j + 32 <= n; j += 32) {
    const __m256i *in = reinterpret_cast<const __m256i *>(rgba + 4 * j);
    const __m256i a0 = _mm256_loadu_si256(in), a1 = _mm256_loadu_si256(in + 1), a2 = _mm256_loadu_si256(in + 2),
                  a3 = _mm256_loadu_si256(in + 3);
    const __m256i redMax = _mm256_and_si256(_mm256_max_epu8(_mm256_max_epu8(a0, a1), _mm256_max_epu8(a2, a3)), low8);
    if (_mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_subs_epu8(redMax, rampStart), zero)) != -1) {
      scoreBlock(rgba + 4 * j, score + j, flags + (j >> 4), k); // a red above the ramp start: 16-bit arithmetic
      scoreBlock(rgba + 4 * (j + 16), score + j + 16, flags + (j >> 4) + 1, k);
      continue;
    }
    const __m256i packed = _mm256_packus_epi16(_mm256_packs_epi32(dominance8(a0, low8), dominance8(a1, low8)),
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

// scoreSpanScalar() with the instruction set \e instructions (one the processor has).
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

#if VSP_DETECTOR_AVX2
// The unclipped score r - max(g, b) of the 8 RGBA pixels from p, in 32-bit lanes (AVX2).
__attribute__((target("avx2"))) inline __m256i signedDominance8(const unsigned char *p)
{
  const __m256i low8 = _mm256_set1_epi32(0xFF);
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i *>(p));
  const __m256i m = _mm256_max_epi32(_mm256_and_si256(_mm256_srli_epi32(a, 8), low8),
                                     _mm256_and_si256(_mm256_srli_epi32(a, 16), low8));
  return _mm256_sub_epi32(_mm256_and_si256(a, low8), m);
}

// The noise samples of estimateNoise() at columns j, j + 4, j + 8, j + 12 of an RGBA row (AVX2): the
// absolute differences of the unclipped score r - max(g, b) two pixels apart, in out[0..3] (in some order).
// Reads the pixels j to j + 15.
__attribute__((target("avx2"))) void noiseSamples4(const unsigned char *row, int j, int *out)
{
  // Lanes 0 and 4 (pixels j and j + 4 of each load) minus lanes 2 and 6 (two pixels further).
  const __m256i d0 = signedDominance8(row + 4 * j), d1 = signedDominance8(row + 4 * (j + 8));
  const __m256i a0 = _mm256_abs_epi32(_mm256_sub_epi32(d0, _mm256_srli_si256(d0, 8)));
  const __m256i a1 = _mm256_abs_epi32(_mm256_sub_epi32(d1, _mm256_srli_si256(d1, 8)));
  // Lanes 0, 4 of a0 then of a1 into the low 128 bits.
  const __m256i picked = _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi32(a0, a1), _mm256_setr_epi32(0, 1, 4, 5, 0, 0, 0, 0));
  _mm_storeu_si128(reinterpret_cast<__m128i *>(out), _mm256_castsi256_si128(picked));
}
#endif

// Robust noise of the unclipped score r - max(g, b): 1.4826 MAD / sqrt(2) of its differences two pixels
// apart (two apart: the optical blur correlates neighbours), every 4th pixel of every 8th row of the scored
// region (about 60 000 samples in a 1600 x 1200 image: the median is known to a few percent).
double estimateNoise(const vpImage<vpRGBa> &I, const RegionSpans *region, vpLaserConicDetector::vpInstructionSet instructions)
{
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  // Four histograms filled in turn, added at the end: most samples fall in a few bins, and consecutive
  // increments of one counter would wait for each other.
  std::vector<uint32_t> histograms(4 * 511, 0);
  uint64_t count = 0;
  auto sampleSpan = [&](const unsigned char *row, int j0, int j1) {
    auto bin = [row](int j) {
      const unsigned char *p = row + 4 * j, *q = p + 8;
      return std::abs(p[0] - std::max(p[1], p[2]) - (q[0] - std::max(q[1], q[2])));
    };
    auto add4 = [&](const int *bins) {
      for (int h = 0; h < 4; ++h)
        ++histograms[h * 511 + bins[h]];
      count += 4;
    };
    int j = j0;
#if VSP_DETECTOR_AVX2
    if (instructions == vpLaserConicDetector::INSTRUCTIONS_AVX2)
      for (; j + 15 <= j1; j += 16) { // the same samples as below, computed 4 at a time
        int bins[4];
        noiseSamples4(row, j, bins);
        add4(bins);
      }
#endif
    (void)instructions;
    for (; j + 14 <= j1; j += 16) {
      const int bins[4] = {bin(j), bin(j + 4), bin(j + 8), bin(j + 12)};
      add4(bins);
    }
    for (; j + 2 <= j1; j += 4) {
      ++histograms[bin(j)];
      ++count;
    }
  };
  for (int i = 0; i < H; i += 8) {
    const unsigned char *row = reinterpret_cast<const unsigned char *>(I[static_cast<unsigned int>(i)]);
    if (region == nullptr)
      sampleSpan(row, 0, W - 1);
    else
      for (const Span *span = region->begin(i); span != region->end(i); ++span)
        sampleSpan(row, span->first, span->second);
  }
  if (count == 0)
    return 0.0;
  std::vector<uint32_t> histogram(histograms.begin(), histograms.begin() + 511);
  for (int h = 1; h < 4; ++h)
    for (size_t k = 0; k < histogram.size(); ++k)
      histogram[k] += histograms[h * 511 + k];
  // Median of the absolute differences, interpolated inside its bin.
  const double half = 0.5 * count;
  uint64_t below = 0;
  for (size_t k = 0; k < histogram.size(); ++k) {
    if (below + histogram[k] >= half) {
      const double mad = k > 0 ? k - 0.5 + (half - below) / histogram[k] : (half - below) / histogram[k] * 0.5;
      return 1.4826 * mad / std::sqrt(2.0);
    }
    below += histogram[k];
  }
  return 0.0;
}

// Candidate test of one pixel: v exceeds the background bg by threshold and the score `near` (the larger at
// d / 2 + 1 pixels on both sides) by half of it, and is a local maximum (first
// pixel of a plateau) between its neighbours before and after along the scan line. The second test is implied
// by the half-maximum width test of a stripe centred on its peak; it discards early the local maxima of red
// areas a little wider than a stripe, which would fail that test after a longer look. A saturated pixel
// (255) is exempt: it may be the first pixel of the plateau of a saturated core.
inline bool isCandidate(int v, int bg, int near, int before, int after, int threshold, int halfThreshold)
{
  return v >= bg + threshold && (v >= near + halfThreshold || v == 255) && v > before && v >= after;
}

#if defined(__SSE2__)
inline __m128i load16(const unsigned char *p) { return _mm_loadu_si128(reinterpret_cast<const __m128i *>(p)); }

// v - b >= t on unsigned bytes (saturated difference).
inline __m128i atLeast(__m128i v, __m128i b, __m128i t)
{
  const __m128i excess = _mm_subs_epu8(v, b);
  return _mm_cmpeq_epi8(_mm_max_epu8(excess, t), excess);
}

// isCandidate() on 16 consecutive pixels (unsigned saturated byte arithmetic); bit k of the result for pixel
// k. far0/far1, near0/near1: the pixels d and d / 2 + 1 away on each side; before/after: the neighbours.
// The background of a side is the lower of its two samples (a neighbouring red patch at d pixels does not
// hide a stripe whose surroundings at d / 2 + 1 are dark), the background the larger of the two sides.
inline int candidates16(const unsigned char *v, const unsigned char *far0, const unsigned char *far1,
                        const unsigned char *near0, const unsigned char *near1, const unsigned char *before,
                        const unsigned char *after, __m128i threshold, __m128i halfThreshold)
{
  // No early exit: the blocks tested are those with a score reaching the threshold (see scoreSpan()), and
  // on a colourful floor whether one of their pixels passes a first test is a coin toss for the processor,
  // dearer to guess wrong than the remaining loads and comparisons.
  const __m128i x = load16(v), zero = _mm_setzero_si128();
  const __m128i saturated = _mm_cmpeq_epi8(x, _mm_set1_epi8(static_cast<char>(0xFF))); // a plateau of 255 may be wide
  const __m128i n0 = load16(near0), n1 = load16(near1);
  // The inside of a red floor patch reaches the threshold but not its own level at d / 2 + 1 pixels plus
  // half the threshold.
  const __m128i nearTest = _mm_or_si128(saturated, atLeast(x, _mm_max_epu8(n0, n1), halfThreshold));
  const __m128i bg = _mm_max_epu8(_mm_min_epu8(load16(far0), n0), _mm_min_epu8(load16(far1), n1));
  const __m128i high = _mm_and_si128(atLeast(x, bg, threshold), nearTest);
  const __m128i notAbove = _mm_cmpeq_epi8(_mm_subs_epu8(x, load16(before)), zero);
  const __m128i notBelow = _mm_cmpeq_epi8(_mm_subs_epu8(load16(after), x), zero);
  return _mm_movemask_epi8(_mm_andnot_si128(notAbove, _mm_and_si128(high, notBelow)));
}
#endif

#if VSP_DETECTOR_AVX2
__attribute__((target("avx2"))) inline __m256i load32(const unsigned char *p)
{
  return _mm256_loadu_si256(reinterpret_cast<const __m256i *>(p));
}

// atLeast() on 32 bytes.
__attribute__((target("avx2"))) inline __m256i atLeast32(__m256i v, __m256i b, __m256i t)
{
  const __m256i excess = _mm256_subs_epu8(v, b);
  return _mm256_cmpeq_epi8(_mm256_max_epu8(excess, t), excess);
}

// candidates16() on 32 consecutive pixels (AVX2): bit k of the result for pixel k.
__attribute__((target("avx2"))) inline unsigned int
candidates32(const unsigned char *v, const unsigned char *far0, const unsigned char *far1, const unsigned char *near0,
             const unsigned char *near1, const unsigned char *before, const unsigned char *after, __m256i threshold,
             __m256i halfThreshold)
{
  const __m256i x = load32(v), zero = _mm256_setzero_si256();
  const __m256i saturated = _mm256_cmpeq_epi8(x, _mm256_set1_epi8(static_cast<char>(0xFF)));
  const __m256i n0 = load32(near0), n1 = load32(near1);
  const __m256i nearTest = _mm256_or_si256(saturated, atLeast32(x, _mm256_max_epu8(n0, n1), halfThreshold));
  const __m256i bg = _mm256_max_epu8(_mm256_min_epu8(load32(far0), n0), _mm256_min_epu8(load32(far1), n1));
  const __m256i high = _mm256_and_si256(atLeast32(x, bg, threshold), nearTest);
  const __m256i notAbove = _mm256_cmpeq_epi8(_mm256_subs_epu8(x, load32(before)), zero);
  const __m256i notBelow = _mm256_cmpeq_epi8(_mm256_subs_epu8(load32(after), x), zero);
  return static_cast<unsigned int>(_mm256_movemask_epi8(_mm256_andnot_si256(notAbove, _mm256_and_si256(high, notBelow))));
}

// The blocks of 16 columns b, b + 1 (b + 1 <= last) of a row flags: whether one of them has a score reaching
// the threshold.
inline bool pairFlagged(const unsigned char *flags, int b, int last)
{
  return flags[b] || (b + 1 <= last && flags[b + 1]);
}

#endif

// Score at offset k along a line of n pixels from position j (0 beyond the ends).
inline int scoreAt(const unsigned char *line, ptrdiff_t stride, int j, int k, int n)
{
  return j + k >= 0 && j + k < n ? line[(j + k) * stride] : 0;
}

// Candidate peaks of the row \e row (W pixels, index i) within [j0, j1], a subrange of [1, W - 2], pixel
// by pixel (see rowCandidates()).
void rowCandidatesScalar(const unsigned char *row, const unsigned char *flags, int W, int i, int j0, int j1, int d,
                         int threshold, std::vector<Candidate> &out)
{
  const int dn = d / 2 + 1, half = (threshold + 1) / 2;
  for (int j = j0; j <= j1; ++j) {
    if (!flags[j >> 4])
      continue;
    const int bg = std::max(std::min(scoreAt(row, 1, j, -d, W), scoreAt(row, 1, j, -dn, W)),
                            std::min(scoreAt(row, 1, j, d, W), scoreAt(row, 1, j, dn, W)));
    const int near = std::max(scoreAt(row, 1, j, -dn, W), scoreAt(row, 1, j, dn, W));
    if (isCandidate(row[j], bg, near, row[j - 1], row[j + 1], threshold, half))
      out.push_back(Candidate{i, j});
  }
}

#if defined(__SSE2__)
// candidates16() on the block of 16 pixels of a row (W pixels) from column k; a block whose samples leave
// the row (near the image border) is tested on a copy of its surroundings padded with zeros: the score beyond
// the ends counts as 0 (see scoreAt()).
class RowBlockTest
{
public:
  RowBlockTest(int d, int threshold)
    : m_d(d), m_dn(d / 2 + 1), m_t(_mm_set1_epi8(static_cast<char>(threshold))),
      m_th(_mm_set1_epi8(static_cast<char>((threshold + 1) / 2)))
  {
  }
  int operator()(const unsigned char *row, int W, int k) const
  {
    const int d = m_d, dn = m_dn;
    if (k >= d && k + 15 + d < W)
      return candidates16(row + k, row + k - d, row + k + d, row + k - dn, row + k + dn, row + k - 1, row + k + 1, m_t, m_th);
    unsigned char padded[16 + 2 * 101];
    const int from = k - d - 1, to = std::min(W - 1, k + 16 + d); // [from, to] of the row, clipped below
    std::memset(padded, 0, sizeof(padded));
    const int first = std::max(0, from), count = to - first + 1;
    std::memcpy(padded + (first - from), row + first, static_cast<size_t>(count));
    const unsigned char *x = padded + d + 1;
    return candidates16(x, x - d, x + d, x - dn, x + dn, x - 1, x + 1, m_t, m_th);
  }

private:
  int m_d, m_dn;
  __m128i m_t, m_th;
};

#if VSP_DETECTOR_AVX2
// The SSE2 loop of rowCandidates() 32 pixels at a time (AVX2) where the samples stay in the row, block by
// block near its ends. Pixels of an unflagged block of a pair are never candidates (no score reaches the
// threshold there): testing the pair as one changes nothing.
__attribute__((target("avx2"))) void rowCandidatesAvx2(const unsigned char *row, const unsigned char *flags, int W,
                                                       int i, int j0, int j1, int d, int threshold,
                                                       std::vector<Candidate> &out)
{
  const int dn = d / 2 + 1, last = j1 >> 4;
  const RowBlockTest test(d, threshold);
  const __m256i t = _mm256_set1_epi8(static_cast<char>(threshold)),
                th = _mm256_set1_epi8(static_cast<char>((threshold + 1) / 2));
  for (int b = j0 >> 4; b <= last; b += 2) {
    if (!pairFlagged(flags, b, last))
      continue;
    const int k = 16 * b;
    unsigned int bits;
    if (k >= d && k + 31 + d < W)
      bits = candidates32(row + k, row + k - d, row + k + d, row + k - dn, row + k + dn, row + k - 1, row + k + 1, t, th);
    else
      bits = (flags[b] ? static_cast<unsigned int>(test(row, W, k)) : 0u) |
             (b + 1 <= last && flags[b + 1] ? static_cast<unsigned int>(test(row, W, k + 16)) << 16 : 0u);
    // Only the pixels of [j0, j1].
    if (k < j0)
      bits &= ~0u << (j0 - k);
    if (k + 31 > j1)
      bits &= (1u << (j1 - k + 1)) - 1u;
    for (; bits; bits &= bits - 1)
      out.push_back(Candidate{i, k + __builtin_ctz(bits)});
  }
}
#endif
#endif

// Candidate peaks along row i within [j0, j1] (near the image border one background side only). Only the
// flagged blocks of 16 columns are tested (flags: the row's block flags, see scoreSpan()).
void rowCandidates(const unsigned char *c, const unsigned char *flags, int W, int i, int j0, int j1, int d,
                   int threshold, vpLaserConicDetector::vpInstructionSet instructions, std::vector<Candidate> &out)
{
  j0 = std::max(j0, 1);
  j1 = std::min(j1, W - 2);
  if (j0 > j1)
    return;
  const unsigned char *row = c + static_cast<size_t>(i) * W;
  if (instructions == vpLaserConicDetector::INSTRUCTIONS_SCALAR) {
    rowCandidatesScalar(row, flags, W, i, j0, j1, d, threshold, out);
    return;
  }
#if defined(__SSE2__)
#if VSP_DETECTOR_AVX2
  if (instructions == vpLaserConicDetector::INSTRUCTIONS_AVX2) {
    rowCandidatesAvx2(row, flags, W, i, j0, j1, d, threshold, out);
    return;
  }
#endif
  const RowBlockTest test(d, threshold);
  for (int b = j0 >> 4; b <= j1 >> 4; ++b) {
    if (!flags[b])
      continue;
    const int k = 16 * b;
    int bits = test(row, W, k);
    // Only the pixels of [j0, j1].
    if (k < j0)
      bits &= static_cast<int>(~0u << (j0 - k));
    if (k + 15 > j1)
      bits &= (1 << (j1 - k + 1)) - 1;
    for (; bits; bits &= bits - 1)
      out.push_back(Candidate{i, k + __builtin_ctz(bits)});
  }
#else
  rowCandidatesScalar(row, flags, W, i, j0, j1, d, threshold, out);
#endif
}

// The columns whose candidates a column pass keeps: the multiples of \e step, except those of \e skip when
// it is not 0 (see detectRidge(): the coarse columns are searched first, the others after).
struct ColumnSelection
{
  int step, skip;
  bool operator()(int j) const { return j % step == 0 && (skip == 0 || j % skip != 0); }
};

#if VSP_DETECTOR_AVX2
// The whole blocks [firstBlock, lastBlock] of the column pass of columnCandidates(), two at a time (AVX2):
// row, up, down, nearUp, nearDown: row i and the rows d and d / 2 + 1 away (or zeros beyond the image).
__attribute__((target("avx2"))) void columnBlocksAvx2(const unsigned char *row, const unsigned char *up,
                                                      const unsigned char *down, const unsigned char *nearUp,
                                                      const unsigned char *nearDown, ptrdiff_t stride,
                                                      const unsigned char *flags, int firstBlock, int lastBlock,
                                                      int threshold, const ColumnSelection &keep, int i,
                                                      std::vector<Candidate> &out)
{
  const __m256i t = _mm256_set1_epi8(static_cast<char>(threshold)),
                th = _mm256_set1_epi8(static_cast<char>((threshold + 1) / 2));
  const __m128i t16 = _mm_set1_epi8(static_cast<char>(threshold)),
                th16 = _mm_set1_epi8(static_cast<char>((threshold + 1) / 2));
  for (int b = firstBlock; b <= lastBlock; b += 2) {
    if (!pairFlagged(flags, b, lastBlock))
      continue;
    const int k = 16 * b;
    unsigned int bits =
        b + 1 <= lastBlock
            ? candidates32(row + k, up + k, down + k, nearUp + k, nearDown + k, row + k - stride, row + k + stride, t, th)
            : static_cast<unsigned int>(candidates16(row + k, up + k, down + k, nearUp + k, nearDown + k,
                                                     row + k - stride, row + k + stride, t16, th16));
    for (; bits; bits &= bits - 1) {
      const int jj = k + __builtin_ctz(bits);
      if (keep(jj))
        out.push_back(Candidate{jj, i});
    }
  }
}
#endif

// Candidate peaks along the columns (those that keep selects) at row i within [j0, j1]. Only the flagged
// blocks of 16 columns are tested (flags: the row's block flags, see scoreSpan()). \e zeros: a row of W
// zero scores, standing for the rows beyond the image border (the score there counts as 0).
void columnCandidates(const unsigned char *c, const unsigned char *flags, const unsigned char *zeros, int W, int H,
                      int i, int j0, int j1, int d, int threshold, const ColumnSelection &keep,
                      vpLaserConicDetector::vpInstructionSet instructions, std::vector<Candidate> &out)
{
  if (i < 1 || i > H - 2)
    return;
  const unsigned char *row = c + static_cast<size_t>(i) * W;
  const ptrdiff_t stride = W;
  const int dn = d / 2 + 1, half = (threshold + 1) / 2;
  auto scalar = [&](int first, int last) {
    for (int j = first; j <= last; ++j) {
      if (!flags[j >> 4] || !keep(j))
        continue;
      const unsigned char *column = c + j; // the column j, row 0
      const int bg = std::max(std::min(scoreAt(column, stride, i, -d, H), scoreAt(column, stride, i, -dn, H)),
                              std::min(scoreAt(column, stride, i, d, H), scoreAt(column, stride, i, dn, H)));
      const int near = std::max(scoreAt(column, stride, i, -dn, H), scoreAt(column, stride, i, dn, H));
      if (isCandidate(row[j], bg, near, row[j - stride], row[j + stride], threshold, half))
        out.push_back(Candidate{j, i});
    }
  };
  int j = j0;
#if defined(__SSE2__)
  // Whole blocks of 16 columns inside [j0, j1], 16 pixels at once.
  const int firstBlock = (j0 + 15) >> 4, lastBlock = (j1 - 15) >> 4;
  if (firstBlock <= lastBlock && instructions != vpLaserConicDetector::INSTRUCTIONS_SCALAR) {
    const __m128i t = _mm_set1_epi8(static_cast<char>(threshold)), th = _mm_set1_epi8(static_cast<char>(half));
    auto rowAt = [&](int r) { return r >= 0 && r < H ? c + static_cast<size_t>(r) * W : zeros; };
    const unsigned char *up = rowAt(i - d), *down = rowAt(i + d), *nearUp = rowAt(i - dn), *nearDown = rowAt(i + dn);
    scalar(j0, 16 * firstBlock - 1);
#if VSP_DETECTOR_AVX2
    if (instructions == vpLaserConicDetector::INSTRUCTIONS_AVX2)
      columnBlocksAvx2(row, up, down, nearUp, nearDown, stride, flags, firstBlock, lastBlock, threshold, keep, i, out);
    else
#endif
      for (int b = firstBlock; b <= lastBlock; ++b) {
        if (!flags[b])
          continue;
        const int k = 16 * b;
        int bits = candidates16(row + k, up + k, down + k, nearUp + k, nearDown + k, row + k - stride, row + k + stride, t, th);
        for (; bits; bits &= bits - 1) {
          const int jj = k + __builtin_ctz(bits);
          if (keep(jj))
            out.push_back(Candidate{jj, i});
        }
      }
    j = 16 * (lastBlock + 1);
  }
#endif
  (void)zeros, (void)instructions;
  scalar(j, j1);
}

// Access to the score and the pixels along one scan line: pointers to its first pixel and the stride
// between its pixels, set once per candidate (the accesses of the profile tests are then one multiply-add).
struct ScanLine
{
  const unsigned char *score; // the whole score image
  int W, H;
  bool alongRow;
  int line;
  const unsigned char *lineScore, *lineRgba; // pixel 0 of the line in the score and in the RGBA buffer
  ptrdiff_t stride;                          // pixels between two consecutive pixels of the line
  int n;                                     // length of the line
  ScanLine(const unsigned char *score_, const unsigned char *rgba, int W_, int H_, bool alongRow_, int line_)
    : score(score_), W(W_), H(H_), alongRow(alongRow_), line(line_),
      lineScore(score_ + (alongRow_ ? static_cast<size_t>(line_) * W_ : static_cast<size_t>(line_))),
      lineRgba(rgba + 4 * (alongRow_ ? static_cast<size_t>(line_) * W_ : static_cast<size_t>(line_))),
      stride(alongRow_ ? 1 : W_), n(alongRow_ ? W_ : H_)
  {
  }
  int length() const { return n; }
  int at(int pos) const { return lineScore[pos * stride]; }
  // Unclipped red dominance of the pixel (negative for grey or other colours).
  int dominance(int pos) const
  {
    const unsigned char *p = lineRgba + 4 * pos * stride;
    return p[0] - std::max(p[1], p[2]);
  }
  int red(int pos) const { return lineRgba[4 * pos * stride]; }
};

// Run of scores above `level` through (i, j) along the direction (di, dj), up to limit pixels per side:
// its length and its largest score.
struct Run
{
  int length, maxScore;
};
// (di, dj) is (1, 0) or (0, 1); \e above: the integer part of the level (the scores are integers: v > level
// is v > floor(level)).
Run runThrough(const unsigned char *score, int W, int H, int i, int j, int di, int dj, int above, int limit)
{
  const unsigned char *centre = score + static_cast<size_t>(i) * W + j;
  const ptrdiff_t stride = static_cast<ptrdiff_t>(di) * W + dj;
  const int before = std::min(limit, di ? i : j), after = std::min(limit, di ? H - 1 - i : W - 1 - j);
  Run run = {1, *centre};
  for (int k = 1; k <= before && centre[-k * stride] > above; ++k) {
    ++run.length;
    run.maxScore = std::max(run.maxScore, static_cast<int>(centre[-k * stride]));
  }
  for (int k = 1; k <= after && centre[k * stride] > above; ++k) {
    ++run.length;
    run.maxScore = std::max(run.maxScore, static_cast<int>(centre[k * stride]));
  }
  return run;
}

enum Verdict
{
  ACCEPTED,
  REJECTED, // shape, width or white light: mark the run
  IGNORED   // not measured by this direction (the other direction crosses more steeply)
};

// Checks the profile around the candidate peak p and measures its sub-pixel centre.
Verdict analyse(const ScanLine &s, int p, const RidgeSettings &settings, int threshold, Crossing &out)
{
  const int n = s.length(), d = settings.maxWidth, dn = d / 2 + 1;
  const int peak = s.at(p);
  auto side = [&](int sign) { // the lower of the scores d and d / 2 + 1 pixels away on one side
    const int a = p + sign * d, b = p + sign * dn;
    return std::min(a >= 0 && a < n ? s.at(a) : 0, b >= 0 && b < n ? s.at(b) : 0);
  };
  const int bg = std::max(side(-1), side(1));
  const int contrast = peak - bg;
  if (contrast < threshold)
    return IGNORED;
  // Half-maximum run.
  const int aboveHalf = bg + contrast / 2; // floor(half): integer scores, s > half is s > floor(half)
  int a = p, b = p;
  while (a - 1 >= 0 && s.at(a - 1) > aboveHalf && p - a <= d)
    --a;
  while (b + 1 < n && s.at(b + 1) > aboveHalf && b - p <= d)
    ++b;
  out.alongRow = s.alongRow;
  out.line = s.line;
  out.first = a;
  out.last = b;
  if (b - a + 1 > settings.maxWidth)
    return REJECTED; // a wide red object, not a stripe
  // White pixels (red channel in the saturation ramp or above, low dominance) must be flanked by red on both
  // sides: a saturated core, not white light.
  int firstWhite = -1, lastWhite = -1;
  for (int k = a; k <= b; ++k)
    if (s.red(k) >= settings.saturation - kSaturationRamp && s.dominance(k) < threshold) {
      if (firstWhite < 0)
        firstWhite = k;
      lastWhite = k;
    }
  if (firstWhite >= 0) {
    bool redLeft = false, redRight = false;
    for (int k = std::max(0, a - 2); k < firstWhite && !redLeft; ++k)
      redLeft = s.dominance(k) >= threshold;
    for (int k = lastWhite + 1; k <= std::min(n - 1, b + 2) && !redRight; ++k)
      redRight = s.dominance(k) >= threshold;
    if (!redLeft || !redRight)
      return REJECTED; // white light, not a laser
  }
  // The other scan direction crosses the stripe more steeply here: it measures this part of the curve.
  const int i = s.alongRow ? s.line : p, j = s.alongRow ? p : s.line;
  const Run across = runThrough(s.score, s.W, s.H, i, j, s.alongRow ? 1 : 0, s.alongRow ? 0 : 1, aboveHalf, d + 1);
  if (across.length < b - a + 1)
    return IGNORED;
  // A line grazing the edge of a stripe (nearly tangent to it) runs inside the stripe's flank: its contrast
  // along the line is a fraction of the stripe's contrast across it. A sliver, not a crossing.
  const int di = s.alongRow ? d : 0, dj = s.alongRow ? 0 : d;
  const int acrossBg = std::max(i - di >= 0 && j - dj >= 0 ? s.score[static_cast<size_t>(i - di) * s.W + (j - dj)] : 0,
                                i + di < s.H && j + dj < s.W ? s.score[static_cast<size_t>(i + di) * s.W + (j + dj)] : 0);
  if (across.maxScore - bg > 1.5 * contrast || 2 * contrast < across.maxScore - acrossBg)
    return IGNORED;
  // Centroid of the score above a quarter of the contrast, over the connected part around the peak.
  const double level = bg + 0.25 * contrast;
  const int aboveLevel = bg + contrast / 4; // floor(level)
  int lo = a, hi = b;
  while (lo - 1 >= 0 && s.at(lo - 1) > aboveLevel && p - lo < d - 1)
    --lo;
  while (hi + 1 < n && s.at(hi + 1) > aboveLevel && hi - p < d - 1)
    ++hi;
  double sumW = 0.0, sumWk = 0.0;
  for (int k = lo; k <= hi; ++k) {
    const double w = s.at(k) - level;
    if (w > 0.0) {
      sumW += w;
      sumWk += w * k;
    }
  }
  const double centre = sumW > 0.0 ? sumWk / sumW : p;
  out.point = s.alongRow ? vpImagePoint(s.line, centre) : vpImagePoint(centre, s.line);
  return ACCEPTED;
}

// Union-find root with path halving.
int root(std::vector<int> &parent, int k)
{
  while (parent[k] != k) {
    parent[k] = parent[parent[k]];
    k = parent[k];
  }
  return k;
}

// Marks in work.keep the crossings of work.crossings that belong to chains (neighbours within `link`
// pixels) at least minLength long.
void longChains(RidgeWorkspace &work, int W, int H, double link, double minLength)
{
  const std::vector<Crossing> &crossings = work.crossings;
  const int n = static_cast<int>(crossings.size());
  std::vector<unsigned char> &keep = work.keep;
  keep.assign(n, 1);
  if (minLength <= 0.0 || n == 0)
    return;
  // The crossings sorted by bands of rows at least `link` high, each band by column (two counting sorts,
  // by column then by band: no comparison whose outcome the processor must guess): the neighbours of a
  // crossing lie after it in its band or in the next band, within ceil(link) columns, each pair seen once,
  // found by a window sliding along the columns. The buffers have the size of the crossings and of the
  // image's width and height: nothing to reset between frames, and little memory to bring to cache (a grid
  // of cells over the image is touched at random).
  std::vector<int> &bandStart = work.bandStart, &order = work.order, &parent = work.parent, &cursor = work.cursor;
  std::vector<int> &bandOf = work.bandOf, &columnOf = work.columnOf, &byColumn = work.byColumn;
  std::vector<double> &u = work.sortedU, &v = work.sortedV;
  std::vector<int> &column = work.sortedColumn;
  // Bands of 2^shift >= max(4, link) rows: the band of a crossing is the integer part of v shifted.
  int shift = 2;
  while ((1 << shift) < link)
    ++shift;
  const int bands = (H >> shift) + 1;
  bandOf.resize(n);
  columnOf.resize(n);
  bandStart.assign(static_cast<size_t>(bands) + 1, 0);
  cursor.assign(static_cast<size_t>(W) + 1, 0); // first the column counts
  for (int k = 0; k < n; ++k) {
    const vpImagePoint &p = crossings[k].point;
    bandOf[k] = std::min(H - 1, std::max(0, static_cast<int>(p.get_v()))) >> shift;
    columnOf[k] = std::min(W - 1, std::max(0, static_cast<int>(p.get_u())));
    ++bandStart[static_cast<size_t>(bandOf[k]) + 1];
    ++cursor[static_cast<size_t>(columnOf[k]) + 1];
  }
  std::partial_sum(bandStart.begin(), bandStart.end(), bandStart.begin());
  std::partial_sum(cursor.begin(), cursor.end(), cursor.begin());
  byColumn.resize(n);
  for (int k = 0; k < n; ++k)
    byColumn[cursor[columnOf[k]]++] = k;
  cursor.assign(bandStart.begin(), bandStart.end() - 1); // the next free place of each band
  order.resize(n);
  for (int k : byColumn)
    order[cursor[bandOf[k]]++] = k;
  u.resize(n);
  v.resize(n);
  column.resize(n);
  for (int pos = 0; pos < n; ++pos) {
    u[pos] = crossings[order[pos]].point.get_u();
    v[pos] = crossings[order[pos]].point.get_v();
    column[pos] = columnOf[order[pos]];
  }
  parent.resize(n);
  std::iota(parent.begin(), parent.end(), 0);
  const double link2 = link * link;
  const int reach = static_cast<int>(std::ceil(link)); // |du| <= link: the columns differ by ceil(link) at most
  auto join = [&](int a, int b) {
    const double du = u[a] - u[b], dv = v[a] - v[b];
    if (du * du + dv * dv <= link2) {
      const int ra = root(parent, a), rb = root(parent, b);
      if (ra != rb)
        parent[ra] = rb;
    }
  };
  for (int band = 0; band < bands; ++band) {
    const int end = bandStart[band + 1], nextEnd = band + 1 < bands ? bandStart[band + 2] : end;
    int next = end; // first crossing of the next band not left of the window
    for (int a = bandStart[band]; a < end; ++a) {
      for (int b = a + 1; b < end && column[b] <= column[a] + reach; ++b)
        join(a, b);
      while (next < nextEnd && column[next] < column[a] - reach)
        ++next;
      for (int b = next; b < nextEnd && column[b] <= column[a] + reach; ++b)
        join(a, b);
    }
  }
  // Extent of each chain: bounding-box diagonal.
  work.minU.assign(n, 1e30);
  work.maxU.assign(n, -1e30);
  work.minV.assign(n, 1e30);
  work.maxV.assign(n, -1e30);
  for (int k = 0; k < n; ++k) {
    parent[k] = root(parent, k);
    const int r = parent[k];
    work.minU[r] = std::min(work.minU[r], u[k]);
    work.maxU[r] = std::max(work.maxU[r], u[k]);
    work.minV[r] = std::min(work.minV[r], v[k]);
    work.maxV[r] = std::max(work.maxV[r], v[k]);
  }
  const double min2 = minLength * minLength;
  for (int k = 0; k < n; ++k) {
    const int r = parent[k];
    const double du = work.maxU[r] - work.minU[r], dv = work.maxV[r] - work.minV[r];
    keep[order[k]] = du * du + dv * dv >= min2;
  }
}
#if defined(__SSE2__)
// Bytes 0, 8, ..., 56 of the 64 bytes from p, to out (8 bytes): the coarse columns of a scored row.
inline void everyEighthByte(const unsigned char *p, unsigned char *out)
{
  const __m128i low = _mm_set_epi32(0, 0xFF, 0, 0xFF); // byte 0 of each 8, in 32-bit lanes 0 and 2
  const __m128i a = _mm_and_si128(load16(p), low), b = _mm_and_si128(load16(p + 16), low),
                c = _mm_and_si128(load16(p + 32), low), d = _mm_and_si128(load16(p + 48), low);
  // 16-bit lanes x0 0 x8 0 x16 0 x24 0, i.e. 32-bit lanes x0 x8 x16 x24; then 16-bit lanes x0 x8 ... x56.
  const __m128i x = _mm_packs_epi32(_mm_packs_epi32(a, b), _mm_packs_epi32(c, d));
  _mm_storel_epi64(reinterpret_cast<__m128i *>(out), _mm_packus_epi16(x, x));
}
#endif

// Coarse to fine (see detectRidge()): the coarse lines are every coarseFactor() x step-th. The largest
// factor up to 8 for which a chain of the minimum length, setMinSegmentLength(), still crosses four coarse
// lines; below 2 (short chains kept, or a sampling step already coarse), one pass.
int coarseFactor(const RidgeSettings &settings)
{
  return std::min(8, static_cast<int>(settings.minSegment / (4.0 * settings.step)));
}

// Cells of 16 columns x RegionSpans::bandHeight rows over an image of W x H pixels.
struct CellGrid
{
  int columns, rows;
  CellGrid(int W, int H) : columns((W + 15) >> 4), rows((H + RegionSpans::bandHeight - 1) >> RegionSpans::bandShift) {}
  int rowOf(const vpImagePoint &p) const
  {
    return std::min(rows - 1, std::max(0, static_cast<int>(p.get_v()) >> RegionSpans::bandShift));
  }
  int columnOf(const vpImagePoint &p) const { return std::min(columns - 1, std::max(0, static_cast<int>(p.get_u()) >> 4)); }
  size_t index(int row, int column) const { return static_cast<size_t>(row) * columns + column; }
};

// The cells (work.cells, see CellGrid) within \e reach pixels (at least, in whole cells) of a crossing that
// work.keep marks: 1, the others 0.
void markCellsAroundKept(RidgeWorkspace &work, int W, int H, int reach)
{
  const CellGrid grid(W, H);
  const int cellsAround = (reach + 15) >> 4, bandsAround = (reach + RegionSpans::bandHeight - 1) >> RegionSpans::bandShift;
  std::vector<unsigned char> &cells = work.cells;
  cells.assign(static_cast<size_t>(grid.columns) * grid.rows, 0);
  for (size_t k = 0; k < work.crossings.size(); ++k) {
    if (!work.keep[k])
      continue;
    const int ci = grid.rowOf(work.crossings[k].point), cj = grid.columnOf(work.crossings[k].point);
    for (int a = std::max(0, ci - bandsAround); a <= std::min(grid.rows - 1, ci + bandsAround); ++a)
      for (int b = std::max(0, cj - cellsAround); b <= std::min(grid.columns - 1, cj + cellsAround); ++b)
        cells[grid.index(a, b)] = 1;
  }
}

// Whether the crossing k lies in a marked cell (see markCellsAroundKept()).
bool inMarkedCell(const RidgeWorkspace &work, int W, int H, size_t k)
{
  const CellGrid grid(W, H);
  const vpImagePoint &p = work.crossings[k].point;
  return work.cells[grid.index(grid.rowOf(p), grid.columnOf(p))] != 0;
}

// The marked cells (see markCellsAroundKept()) rasterised into \e region (spans on multiples of 16 columns).
void markedCellsToSpans(const RidgeWorkspace &work, int W, int H, RegionSpans &region)
{
  const CellGrid grid(W, H);
  region.spans.clear();
  region.bandStart.assign(1, 0);
  for (int a = 0; a < grid.rows; ++a) {
    const unsigned char *row = work.cells.data() + grid.index(a, 0);
    for (int b = 0; b < grid.columns; ++b) {
      const int first = b;
      while (b < grid.columns && row[b])
        ++b;
      if (b > first)
        region.spans.push_back(Span(16 * first, std::min(W - 1, 16 * b - 1)));
    }
    region.bandStart.push_back(static_cast<int>(region.spans.size()));
  }
}

// One ridge detection: the score, the candidate searches along rows and columns and their measurement,
// over the buffers of a RidgeWorkspace (see detectRidge()).
class RidgeScan
{
public:
  RidgeScan(const vpImage<vpRGBa> &I, const RidgeSettings &settings, int threshold, RidgeWorkspace &work,
            std::vector<StripeRun> &runs)
    : m_rgba(reinterpret_cast<const unsigned char *>(I.bitmap)), m_H(static_cast<int>(I.getHeight())),
      m_W(static_cast<int>(I.getWidth())), m_flagStride((m_W + 15) >> 4), m_d(settings.maxWidth),
      m_threshold(threshold), m_settings(settings), m_work(work), m_runs(runs)
  {
    work.score.resize(static_cast<size_t>(m_W) * m_H);
    work.blockFlags.resize(static_cast<size_t>(m_flagStride) * m_H, 0);
    work.zeros.assign(m_W, 0);
    work.lastEnd.assign(m_W, -1);
    work.rowPeaks.clear();
    work.columnPeaks.clear();
    work.crossings.clear();
  }

  /*!
    The pass over the rows, while they are in cache: row i is scored (over \e scoreRegion only when not
    null: nothing outside it is read) and, when a multiple of \e step, searched along its length; the
    columns multiple of \e step are searched at row i - d, the last row whose neighbours up to d rows away
    are scored (in the image of the coarse columns when \e coarse); the candidates of row i - d - 1, the
    last row whose profiles (up to d + 1 rows away) are scored, are measured.
  */
  void streamRows(const RegionSpans *scoreRegion, const RegionSpans *searchRegion, int step, bool coarse)
  {
    if (coarse)
      startCoarseColumns(step);
    auto searchColumnsAt = [&](int r) {
      if (coarse)
        searchCoarseColumns(r, step);
      else
        searchColumns(r, searchRegion, ColumnSelection{step, 0});
    };
    for (int i = 0; i < m_H; ++i) {
      scoreRow(i, scoreRegion);
      if (i % step == 0)
        searchRow(i, searchRegion);
      if (coarse)
        keepCoarseColumns(i, step);
      if (i - m_d >= 0)
        searchColumnsAt(i - m_d);
      measureUpTo(i - m_d - 1);
    }
    for (int r = std::max(0, m_H - m_d); r < m_H; ++r)
      searchColumnsAt(r);
    measureUpTo(m_H);
  }

  /*!
    Searches the lines of \e region that streamRows() left out (the rows and columns multiple of \e step but
    not of \e coarseStep), row by row over the scored image, and measures each row's candidates at once.
  */
  void searchBetween(const RegionSpans &region, int step, int coarseStep)
  {
    for (int i = 0; i < m_H; ++i) {
      if (region.begin(i) == region.end(i))
        continue;
      m_work.rowPeaks.clear();
      m_work.columnPeaks.clear();
      m_nextRowPeak = m_nextColumnPeak = 0;
      if (i % step == 0 && i % coarseStep != 0)
        searchRow(i, &region);
      searchColumns(i, &region, ColumnSelection{step, coarseStep});
      measureUpTo(i);
    }
  }

  //! Keeps the crossings work.keep marks; the others become rejected runs (for the mask, see drawRuns()).
  void keepMarkedCrossings()
  {
    std::vector<Crossing> &crossings = m_work.crossings;
    size_t kept = 0;
    for (size_t k = 0; k < crossings.size(); ++k) {
      const Crossing &c = crossings[k];
      if (m_work.keep[k])
        crossings[kept++] = c;
      else
        m_runs.push_back(StripeRun{c.alongRow, c.line, c.first, c.last, false});
    }
    crossings.resize(kept);
  }

private:
  void scoreRow(int i, const RegionSpans *region)
  {
    const size_t offset = static_cast<size_t>(i) * m_W;
    unsigned char *flags = m_work.blockFlags.data() + static_cast<size_t>(i) * m_flagStride;
    if (region == nullptr) {
      scoreSpan(m_rgba + 4 * offset, &m_work.score[offset], m_W, m_settings.saturation, m_threshold, flags,
                m_settings.instructions);
      return;
    }
    // The spans start at multiples of 16 columns (see RegionSpans): the blocks of the flags.
    for (const Span *span = region->begin(i); span != region->end(i); ++span)
      scoreSpan(m_rgba + 4 * (offset + span->first), &m_work.score[offset + span->first],
                span->second - span->first + 1, m_settings.saturation, m_threshold, flags + (span->first >> 4),
                m_settings.instructions);
  }

  const unsigned char *flagsOf(int i) const
  {
    return m_work.blockFlags.data() + static_cast<size_t>(i) * m_flagStride;
  }

  void searchRow(int i, const RegionSpans *region)
  {
    if (region == nullptr) {
      rowCandidates(m_work.score.data(), flagsOf(i), m_W, i, 0, m_W - 1, m_d, m_threshold, m_settings.instructions,
                    m_work.rowPeaks);
      return;
    }
    for (const Span *span = region->begin(i); span != region->end(i); ++span)
      rowCandidates(m_work.score.data(), flagsOf(i), m_W, i, span->first, span->second, m_d, m_threshold,
                    m_settings.instructions, m_work.rowPeaks);
  }

  void searchColumns(int i, const RegionSpans *region, const ColumnSelection &columns)
  {
    if (region == nullptr) {
      columnCandidates(m_work.score.data(), flagsOf(i), m_work.zeros.data(), m_W, m_H, i, 0, m_W - 1, m_d,
                       m_threshold, columns, m_settings.instructions, m_work.columnPeaks);
      return;
    }
    for (const Span *span = region->begin(i); span != region->end(i); ++span)
      columnCandidates(m_work.score.data(), flagsOf(i), m_work.zeros.data(), m_W, m_H, i, span->first,
                       span->second, m_d, m_threshold, columns, m_settings.instructions, m_work.columnPeaks);
  }

  // The coarse columns: the column tests read nothing across, so every coarseStep-th column of the score
  // makes an image of its own, coarseStep times narrower, searched whole (all its blocks flagged); its
  // candidates are mapped back to the image's columns. Its rows are padded with zeros to whole pairs of
  // blocks (no pixel-by-pixel end: a zero score is never a candidate).
  int coarseColumns(int coarseStep) const { return (m_W - 1) / coarseStep + 1; }
  int coarseStride(int coarseStep) const { return (coarseColumns(coarseStep) + 31) & ~31; }
  void startCoarseColumns(int coarseStep)
  {
    const int w = coarseStride(coarseStep);
    m_work.coarseScore.resize(static_cast<size_t>(w) * m_H);
    m_work.coarseFlags.assign(static_cast<size_t>(w >> 4), 0xFF);
    m_work.coarseZeros.assign(w, 0);
  }
  void keepCoarseColumns(int i, int coarseStep)
  {
    const int n = coarseColumns(coarseStep), w = coarseStride(coarseStep);
    const unsigned char *row = m_work.score.data() + static_cast<size_t>(i) * m_W;
    unsigned char *coarse = m_work.coarseScore.data() + static_cast<size_t>(i) * w;
    int k = 0;
#if defined(__SSE2__)
    if (coarseStep == 8 && m_settings.instructions != vpLaserConicDetector::INSTRUCTIONS_SCALAR)
      for (; 8 * k + 64 <= m_W; k += 8)
        everyEighthByte(row + 8 * k, coarse + k);
#endif
    for (; k < n; ++k)
      coarse[k] = row[static_cast<size_t>(k) * coarseStep];
    std::fill(coarse + n, coarse + w, 0);
  }
  void searchCoarseColumns(int i, int coarseStep)
  {
    const int w = coarseStride(coarseStep);
    std::vector<Candidate> &peaks = m_work.columnPeaks;
    const size_t first = peaks.size();
    columnCandidates(m_work.coarseScore.data(), m_work.coarseFlags.data(), m_work.coarseZeros.data(), w, m_H, i, 0,
                     w - 1, m_d, m_threshold, ColumnSelection{1, 0}, m_settings.instructions, peaks);
    for (size_t k = first; k < peaks.size(); ++k)
      peaks[k].line *= coarseStep;
  }

  // Measures the candidate c: one crossing per run, a later peak inside a measured run is skipped (the
  // candidates come line by line for the rows, row by row for the columns: one run end per column).
  void measure(const Candidate &c, bool alongRow)
  {
    if (alongRow && c.line != m_lastRow) {
      m_lastRow = c.line;
      m_lastRowEnd = -1;
    }
    int &end = alongRow ? m_lastRowEnd : m_work.lastEnd[static_cast<size_t>(c.line)];
    if (c.pos <= end)
      return;
    const ScanLine s(m_work.score.data(), m_rgba, m_W, m_H, alongRow, c.line);
    Crossing crossing;
    const Verdict verdict = analyse(s, c.pos, m_settings, m_threshold, crossing);
    if (verdict == IGNORED)
      return;
    end = crossing.last;
    if (verdict == ACCEPTED)
      m_work.crossings.push_back(crossing);
    else
      m_runs.push_back(StripeRun{alongRow, crossing.line, crossing.first, crossing.last, false});
  }

  // Measures the candidates of the rows <= r not measured yet.
  void measureUpTo(int r)
  {
    const std::vector<Candidate> &rows = m_work.rowPeaks, &columns = m_work.columnPeaks;
    for (; m_nextRowPeak < rows.size() && rows[m_nextRowPeak].line <= r; ++m_nextRowPeak)
      measure(rows[m_nextRowPeak], true);
    for (; m_nextColumnPeak < columns.size() && columns[m_nextColumnPeak].pos <= r; ++m_nextColumnPeak)
      measure(columns[m_nextColumnPeak], false);
  }

  const unsigned char *m_rgba;
  const int m_H, m_W, m_flagStride, m_d, m_threshold;
  const RidgeSettings &m_settings;
  RidgeWorkspace &m_work;
  std::vector<StripeRun> &m_runs;
  int m_lastRow = -1, m_lastRowEnd = -1;
  size_t m_nextRowPeak = 0, m_nextColumnPeak = 0;
};
} // namespace

std::vector<vpImagePoint> detectRidge(const vpImage<vpRGBa> &I, const RidgeSettings &settings,
                                      const RegionSpans *scoreRegion, const RegionSpans *searchRegion,
                                      RidgeWorkspace &work, std::vector<StripeRun> &runs, RidgeReport &report)
{
  std::vector<vpImagePoint> points;
  runs.clear();
  work.crossings.clear();
  work.keep.clear();
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  if (H == 0 || W == 0)
    return points;

  // 1. Threshold from the image's own noise (a sparse sample of rows).
  report.noise = estimateNoise(I, scoreRegion, settings.instructions);
  report.threshold = std::max(settings.minContrast, settings.noiseFactor * report.noise);
  const int threshold = std::min(255, static_cast<int>(std::ceil(report.threshold)));

  // 2. Score, candidates and profiles. Over the whole image, coarse to fine: on a textured floor nearly
  // every block of the image has candidates, most of them short ridges (a patch corner between two grout
  // lines is a thin wedge of its colour), and measuring them all took most of a frame's time. The pass
  // over the rows measures the candidates of the coarse lines only (every coarseStep-th row and column),
  // whose crossings are chained as in 3.; the other lines are then searched only near the coarse crossings
  // on chains that may reach the minimum length. A chain of that length crosses four coarse lines at least;
  // its coarse crossings may fall short of its ends by up to a coarse step each way (hence the shorter
  // coarse length). A search region is already small: one pass.
  const int step = settings.step, factor = searchRegion == nullptr ? coarseFactor(settings) : 1;
  RidgeScan scan(I, settings, threshold, work, runs);
  if (factor < 2)
    scan.streamRows(scoreRegion, searchRegion, step, false);
  else {
    const int coarseStep = factor * step;
    scan.streamRows(nullptr, nullptr, coarseStep, true);
    // The coarse chains: linked within two coarse steps, as the lines in 3.; then the short ones near the
    // long ones are linked within three steps: a dim stripe misses a coarse crossing here and there, and
    // two coarse steps along a stripe at 45 degrees are 2.8 steps apart (the dim frames of the shipped hard
    // sequence lost pieces of trace). Only near the long chains: linked within three steps everywhere, the
    // wedges of a mosaic make networks, all to be searched.
    const double coarseMin = std::max(0.0, settings.minSegment - 3.0 * coarseStep);
    longChains(work, W, H, 2.0 * coarseStep + 0.5, coarseMin);
    markCellsAroundKept(work, W, H, 3 * coarseStep + 1);
    for (size_t k = 0; k < work.crossings.size(); ++k)
      work.keep[k] = work.keep[k] || inMarkedCell(work, W, H, k);
    scan.keepMarkedCrossings();
    longChains(work, W, H, 3.0 * coarseStep + 0.5, coarseMin);
    // The other lines are searched around the coarse crossings kept, a few pixels beyond half the distance
    // of two linked ones (16 pixels for coarse lines every 8th).
    markCellsAroundKept(work, W, H, (3 * coarseStep + 1) / 2 + 4);
    markedCellsToSpans(work, W, H, work.fineRegion);
    scan.keepMarkedCrossings();
    scan.searchBetween(work.fineRegion, step, coarseStep);
  }

  // 3. Continuity: drop the short chains.
  longChains(work, W, H, 2.0 * step + 0.5, settings.minSegment);
  // The runs of the crossings stay in the workspace for the mask (see drawRuns()).
  points.reserve(static_cast<size_t>(std::count(work.keep.begin(), work.keep.end(), 1)));
  for (size_t k = 0; k < work.crossings.size(); ++k)
    if (work.keep[k])
      points.push_back(work.crossings[k].point);
  return points;
}
} // namespace vsp::laser_detector

namespace vsp::laser_detector
{
void drawRuns(const std::vector<StripeRun> &runs, const RidgeWorkspace &work, unsigned int H, unsigned int W,
              vpImage<unsigned char> &mask)
{
  mask.resize(H, W, 0);
  auto draw = [&mask](bool alongRow, int line, int first, int last, unsigned char value) {
    for (int k = first; k <= last; ++k) {
      unsigned char &m = alongRow ? mask[static_cast<unsigned int>(line)][static_cast<unsigned int>(k)]
                                  : mask[static_cast<unsigned int>(k)][static_cast<unsigned int>(line)];
      m = std::max(m, value);
    }
  };
  for (const StripeRun &r : runs)
    draw(r.alongRow, r.line, r.first, r.last, r.accepted ? 255 : 100);
  for (size_t k = 0; k < work.crossings.size() && k < work.keep.size(); ++k) {
    const Crossing &c = work.crossings[k];
    draw(c.alongRow, c.line, c.first, c.last, work.keep[k] ? 255 : 100);
  }
}
} // namespace vsp::laser_detector
