/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The candidate search of the ridge detector: the top-hat test of every flagged pixel of a row or of the
// columns at a row, 16 (SSE2) or 32 (AVX2) pixels at a time.
#include "ridge_candidates.h"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "ridge_simd.h"

namespace vsp::laser_detector
{
namespace
{

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
  return static_cast<unsigned int>(
      _mm256_movemask_epi8(_mm256_andnot_si256(notAbove, _mm256_and_si256(high, notBelow))));
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
      return candidates16(row + k, row + k - d, row + k + d, row + k - dn, row + k + dn, row + k - 1, row + k + 1, m_t,
                          m_th);
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
      bits =
          candidates32(row + k, row + k - d, row + k + d, row + k - dn, row + k + dn, row + k - 1, row + k + 1, t, th);
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
} // namespace

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

namespace
{
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
        b + 1 <= lastBlock ? candidates32(row + k, up + k, down + k, nearUp + k, nearDown + k, row + k - stride,
                                          row + k + stride, t, th)
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
} // namespace

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
        int bits = candidates16(row + k, up + k, down + k, nearUp + k, nearDown + k, row + k - stride, row + k + stride,
                                t, th);
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
} // namespace vsp::laser_detector
