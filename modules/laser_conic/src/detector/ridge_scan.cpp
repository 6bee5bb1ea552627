/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The scan driver of the ridge detector: the score, the candidate searches along rows and columns and
// their measurement in one pass over the rows, and the search of the lines left between the coarse ones.
#include "ridge_scan.h"

#include <algorithm>

#include "ridge_profile.h"
#include "ridge_score.h"
#include "ridge_simd.h"

namespace vsp::laser_detector
{
namespace
{
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
} // namespace

RidgeScan::RidgeScan(const vpImage<vpRGBa> &I, const RidgeSettings &settings, int threshold, RidgeWorkspace &work,
                     std::vector<StripeRun> &runs)
  : m_rgba(reinterpret_cast<const unsigned char *>(I.bitmap)), m_H(static_cast<int>(I.getHeight())),
    m_W(static_cast<int>(I.getWidth())), m_flagStride((m_W + 15) >> 4), m_d(settings.maxWidth), m_threshold(threshold),
    m_settings(settings), m_work(work), m_runs(runs)
{
  work.score.resize(static_cast<size_t>(m_W) * m_H);
  work.blockFlags.resize(static_cast<size_t>(m_flagStride) * m_H, 0);
  work.zeros.assign(m_W, 0);
  work.lastEnd.assign(m_W, -1);
  work.rowPeaks.clear();
  work.columnPeaks.clear();
  work.crossings.clear();
}

void RidgeScan::streamRows(const RegionSpans *scoreRegion, const RegionSpans *searchRegion, int step, bool coarse)
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
    measureUpTo(i - profileReach(m_d));
  }
  for (int r = std::max(0, m_H - m_d); r < m_H; ++r)
    searchColumnsAt(r);
  measureUpTo(m_H);
}

void RidgeScan::searchBetween(const RegionSpans &region, int step, int coarseStep)
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

void RidgeScan::keepMarkedCrossings()
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

void RidgeScan::scoreRow(int i, const RegionSpans *region)
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
    scoreSpan(m_rgba + 4 * (offset + span->first), &m_work.score[offset + span->first], span->second - span->first + 1,
              m_settings.saturation, m_threshold, flags + (span->first >> 4), m_settings.instructions);
}

const unsigned char *RidgeScan::flagsOf(int i) const
{
  return m_work.blockFlags.data() + static_cast<size_t>(i) * m_flagStride;
}

void RidgeScan::searchRow(int i, const RegionSpans *region)
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

void RidgeScan::searchColumns(int i, const RegionSpans *region, const ColumnSelection &columns)
{
  if (region == nullptr) {
    columnCandidates(m_work.score.data(), flagsOf(i), m_work.zeros.data(), m_W, m_H, i, 0, m_W - 1, m_d, m_threshold,
                     columns, m_settings.instructions, m_work.columnPeaks);
    return;
  }
  for (const Span *span = region->begin(i); span != region->end(i); ++span)
    columnCandidates(m_work.score.data(), flagsOf(i), m_work.zeros.data(), m_W, m_H, i, span->first, span->second, m_d,
                     m_threshold, columns, m_settings.instructions, m_work.columnPeaks);
}

void RidgeScan::startCoarseColumns(int coarseStep)
{
  const int w = coarseStride(coarseStep);
  m_work.coarseScore.resize(static_cast<size_t>(w) * m_H);
  m_work.coarseFlags.assign(static_cast<size_t>(w >> 4), 0xFF);
  m_work.coarseZeros.assign(w, 0);
}

void RidgeScan::keepCoarseColumns(int i, int coarseStep)
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

void RidgeScan::searchCoarseColumns(int i, int coarseStep)
{
  const int w = coarseStride(coarseStep);
  std::vector<Candidate> &peaks = m_work.columnPeaks;
  const size_t first = peaks.size();
  columnCandidates(m_work.coarseScore.data(), m_work.coarseFlags.data(), m_work.coarseZeros.data(), w, m_H, i, 0, w - 1,
                   m_d, m_threshold, ColumnSelection{1, 0}, m_settings.instructions, peaks);
  for (size_t k = first; k < peaks.size(); ++k)
    peaks[k].line *= coarseStep;
}

void RidgeScan::measure(const Candidate &c, bool alongRow)
{
  if (alongRow && c.line != m_lastRow) {
    m_lastRow = c.line;
    m_lastRowEnd = -1;
  }
  int &end = alongRow ? m_lastRowEnd : m_work.lastEnd[static_cast<size_t>(c.line)];
  if (c.pos <= end)
    return;
  const ScanLine s(m_work.score.data(), m_rgba, m_W, m_H, alongRow, c.line);
  const int last = measureCandidate(s, c.pos, m_settings, m_threshold, true, m_work, m_runs);
  if (last >= 0)
    end = last;
}

void RidgeScan::measureUpTo(int r)
{
  const std::vector<Candidate> &rows = m_work.rowPeaks, &columns = m_work.columnPeaks;
  for (; m_nextRowPeak < rows.size() && rows[m_nextRowPeak].line <= r; ++m_nextRowPeak)
    measure(rows[m_nextRowPeak], true);
  for (; m_nextColumnPeak < columns.size() && columns[m_nextColumnPeak].pos <= r; ++m_nextColumnPeak)
    measure(columns[m_nextColumnPeak], false);
}
} // namespace vsp::laser_detector
