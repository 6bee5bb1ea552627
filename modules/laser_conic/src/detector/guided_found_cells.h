/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file guided_found_cells.h
  \brief The points the guided pass has found, by cell of the image (internal header): whether a sample of
  the predicted conic is already covered by one.
*/
#ifndef VP_LASER_GUIDED_FOUND_CELLS_H
#define VP_LASER_GUIDED_FOUND_CELLS_H

#include <cmath>
#include <cstddef>
#include <vector>

#include <visp3/core/vpImagePoint.h>

#include "guided_detail.h"
#include "laser_detector.h"

namespace vsp::laser_detector
{
// The points found (by either pass), in lists per cell of 2^cellShift pixels.
class FoundCells
{
public:
  FoundCells(int W, int H, RidgeWorkspace &work)
    : m_columns((W >> RidgeTuning::guidedCellShift) + 1), m_rows((H >> RidgeTuning::guidedCellShift) + 1),
      m_heads(work.guidedCells), m_next(work.guidedNext), m_points(work.guidedFound)
  {
    const size_t cells = static_cast<size_t>(m_columns) * m_rows;
    if (m_heads.size() != cells || work.guidedColumns != m_columns) {
      m_heads.assign(cells, -1);
      m_points.clear();
    }
    work.guidedColumns = m_columns;
    clear();
  }
  // Forgets the points marked. Only their cells are reset: clearing the whole grid (half a megabyte at
  // 1600 x 1200) for each detection cost a tenth of the tracking mode's time.
  void clear()
  {
    for (const vpImagePoint &p : m_points) {
      int a = 0, b = 0;
      if (cellOf(p.get_u(), p.get_v(), a, b))
        m_heads[static_cast<size_t>(b) * m_columns + a] = -1;
    }
    m_next.clear();
    m_points.clear();
  }
  void mark(const vpImagePoint &p)
  {
    int a = 0, b = 0;
    if (!cellOf(p.get_u(), p.get_v(), a, b))
      return;
    int &head = m_heads[static_cast<size_t>(b) * m_columns + a];
    m_next.push_back(head);
    head = static_cast<int>(m_points.size());
    m_points.push_back(p);
  }
  // Whether a point found lies on the profile of sample s: within RidgeTuning::guidedKnownAlong pixels of it along
  // the predicted curve and RidgeTuning::guidedKnownAcross across it. \e offset: then that point's offset across
  // the predicted curve (as ProfileResult::offset).
  bool covers(const GuidedSample &s, double &offset) const
  {
    if (m_points.empty()) // the first walk of a tracking pass: nothing to look up in the grid
      return false;
    const double u = s.alongRow ? s.pos : s.line, v = s.alongRow ? s.line : s.pos;
    int a = 0, b = 0;
    if (!cellOf(u, v, a, b))
      return false;
    const double norm = std::sqrt(s.slope * s.slope + 1.0); // not std::hypot: a call per sample
    const double tu = (s.alongRow ? s.slope : 1.0) / norm, tv = (s.alongRow ? 1.0 : s.slope) / norm;
    // The sample's own cell first: a point that covers it is most often there.
    static const int around[9][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    for (const int *cell : around) {
      const int x = a + cell[0], y = b + cell[1];
      if (x < 0 || y < 0 || x >= m_columns || y >= m_rows)
        continue;
      for (int k = m_heads[static_cast<size_t>(y) * m_columns + x]; k >= 0; k = m_next[static_cast<size_t>(k)]) {
        const double du = m_points[static_cast<size_t>(k)].get_u() - u,
                     dv = m_points[static_cast<size_t>(k)].get_v() - v;
        if (std::fabs(du * tu + dv * tv) <= RidgeTuning::guidedKnownAlong &&
            std::fabs(du * tv - dv * tu) <= RidgeTuning::guidedKnownAcross) {
          offset = acrossOf(s, s.alongRow ? du - s.slope * dv : dv - s.slope * du);
          return true;
        }
      }
    }
    return false;
  }

  //! Whether \e p itself (the same centre, to 1e-9 px) is marked.
  bool holds(const vpImagePoint &p) const
  {
    int a = 0, b = 0;
    if (m_points.empty() || !cellOf(p.get_u(), p.get_v(), a, b))
      return false;
    for (int k = m_heads[static_cast<size_t>(b) * m_columns + a]; k >= 0; k = m_next[static_cast<size_t>(k)])
      if (std::fabs(m_points[static_cast<size_t>(k)].get_u() - p.get_u()) <= 1e-9 &&
          std::fabs(m_points[static_cast<size_t>(k)].get_v() - p.get_v()) <= 1e-9)
        return true;
    return false;
  }

private:
  bool cellOf(double u, double v, int &a, int &b) const
  {
    if (!(u >= 0.0 && v >= 0.0))
      return false;
    a = static_cast<int>(u) >> RidgeTuning::guidedCellShift;
    b = static_cast<int>(v) >> RidgeTuning::guidedCellShift;
    return a < m_columns && b < m_rows;
  }
  int m_columns, m_rows;
  std::vector<int> &m_heads, &m_next;
  std::vector<vpImagePoint> &m_points;
};

//! How many of the centres of the samples \e keep marks (in \e results) \e found holds already: samples measured
//! again, by a later walk or along the final conic (see dropRepeatedCentres() in guided_pass.cpp).
inline int heldCentres(const std::vector<unsigned char> &keep, const std::vector<ProfileResult> &results,
                       const FoundCells &found)
{
  int held = 0;
  for (size_t i = 0; i < keep.size(); ++i)
    held += keep[i] && found.holds(results[i].crossing.point) ? 1 : 0;
  return held;
}

} // namespace vsp::laser_detector

#endif
