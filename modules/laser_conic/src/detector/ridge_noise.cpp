/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The score noise estimate of the ridge detector: a histogram of sampled differences, its median.
#include "ridge_noise.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "ridge_simd.h"

namespace vsp::laser_detector
{
#if VSP_DETECTOR_AVX2
namespace
{
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
  const __m256i picked =
      _mm256_permutevar8x32_epi32(_mm256_unpacklo_epi32(a0, a1), _mm256_setr_epi32(0, 1, 4, 5, 0, 0, 0, 0));
  _mm_storeu_si128(reinterpret_cast<__m128i *>(out), _mm256_castsi256_si128(picked));
}
} // namespace
#endif

double estimateNoise(const vpImage<vpRGBa> &I, const RegionSpans *region,
                     vpLaserConicDetector::vpInstructionSet instructions)
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
    if (region == nullptr) {
      // The rows sampled are 8 apart, too far for the processor to guess: the next one is asked for while
      // this one is read, which would otherwise wait for memory line by line.
      if (i + 8 < H)
        prefetchBytes(row + 4 * static_cast<size_t>(8) * W, 4 * static_cast<size_t>(W));
      sampleSpan(row, 0, W - 1);
    } else {
      for (const Span *span = region->begin(i); span != region->end(i); ++span)
        sampleSpan(row, span->first, span->second);
    }
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

int beginDetection(const vpImage<vpRGBa> &I, const RidgeSettings &settings, const RegionSpans *region,
                   RidgeWorkspace &work, std::vector<StripeRun> &runs, RidgeReport &report)
{
  runs.clear();
  work.crossings.clear();
  work.keep.clear();
  if (I.getHeight() == 0 || I.getWidth() == 0)
    return -1;
  report.noise = estimateNoise(I, region, settings.instructions);
  report.threshold = std::max(settings.minContrast, settings.noiseFactor * report.noise);
  return toIntAtMost(std::ceil(report.threshold), 255);
}
} // namespace vsp::laser_detector
