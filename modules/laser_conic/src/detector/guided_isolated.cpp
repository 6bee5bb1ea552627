/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
// The pieces of the guided pass's points that stand alone along the final conic, dropped once the centres are
// regularised (RidgeTuning::guidedIsolatedRun).
#include "guided_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vsp::laser_detector
{
namespace
{
// Whether one of the first pass's points (the anchors) lies within \e side pixels of a point: the anchors
// sorted into square cells of that side on the first question (most frames ask none), the 3 x 3 cells around
// the point read.
class AnchorCells
{
public:
  AnchorCells(const std::vector<vpImagePoint> &anchors, double side) : m_anchors(anchors), m_side(side) {}
  bool near(const vpImagePoint &p)
  {
    if (m_anchors.empty())
      return false;
    if (m_start.empty())
      build();
    const long cu = cellOf(p.get_u()) - m_u0, cv = cellOf(p.get_v()) - m_v0;
    for (long dv = -1; dv <= 1; ++dv)
      for (long du = -1; du <= 1; ++du) {
        const long u = cu + du, v = cv + dv;
        if (u < 0 || v < 0 || u >= m_columns || v >= m_rows)
          continue;
        const size_t cell = static_cast<size_t>(v * m_columns + u);
        for (size_t k = m_start[cell]; k < m_start[cell + 1]; ++k) {
          const vpImagePoint &a = m_anchors[m_sorted[k]];
          const double eu = a.get_u() - p.get_u(), ev = a.get_v() - p.get_v();
          if (eu * eu + ev * ev <= m_side * m_side)
            return true;
        }
      }
    return false;
  }

private:
  long cellOf(double x) const { return static_cast<long>(std::floor(x / m_side)); }
  // Counting sort of the anchors by cell over the cells of their bounding box.
  void build()
  {
    m_u0 = m_v0 = std::numeric_limits<long>::max();
    long u1 = std::numeric_limits<long>::min(), v1 = u1;
    for (const vpImagePoint &a : m_anchors) {
      m_u0 = std::min(m_u0, cellOf(a.get_u())), u1 = std::max(u1, cellOf(a.get_u()));
      m_v0 = std::min(m_v0, cellOf(a.get_v())), v1 = std::max(v1, cellOf(a.get_v()));
    }
    m_columns = u1 - m_u0 + 1, m_rows = v1 - m_v0 + 1;
    std::vector<size_t> cellOfAnchor(m_anchors.size());
    for (size_t k = 0; k < m_anchors.size(); ++k)
      cellOfAnchor[k] = static_cast<size_t>((cellOf(m_anchors[k].get_v()) - m_v0) * m_columns +
                                            (cellOf(m_anchors[k].get_u()) - m_u0));
    groupByKey(cellOfAnchor, static_cast<size_t>(m_columns * m_rows), m_start, m_sorted);
  }
  const std::vector<vpImagePoint> &m_anchors;
  double m_side;
  long m_u0 = 0, m_v0 = 0, m_columns = 0, m_rows = 0;
  std::vector<size_t> m_start, m_sorted; //!< first entry of each cell in m_sorted (and one past the last)
};

} // namespace

void dropIsolatedPieces(const std::vector<int> &order, const std::vector<vpImagePoint> &anchors,
                        std::vector<Crossing> &crossings)
{
  const size_t n = order.size();
  if (n < 2 || n != crossings.size())
    return;
  const double apart = RidgeTuning::guidedGapLength, apart2 = apart * apart;
  // Positions stay under two turns (a piece ends at the gap before \e start, one turn on): onTheRing().
  const auto at = [&](size_t position) -> const vpImagePoint & {
    return crossings[static_cast<size_t>(order[onTheRing(position, n)])].point;
  };
  const auto farApart = [apart2](const vpImagePoint &p, const vpImagePoint &q) {
    const double du = p.get_u() - q.get_u(), dv = p.get_v() - q.get_v();
    return du * du + dv * dv > apart2;
  };
  size_t start = n; // a position after a gap, where a piece starts
  for (size_t i = 0; i < n && start == n; ++i)
    if (farApart(at(i + n - 1), at(i)))
      start = i;
  if (start == n)
    return; // one piece round the ring
  AnchorCells cells(anchors, apart);
  std::vector<unsigned char> drop(n, 0);
  bool any = false;
  for (size_t first = start, done = 0; done < n;) {
    size_t length = 1;
    while (length < n && !farApart(at(first + length - 1), at(first + length)))
      ++length;
    const size_t last = first + length - 1;
    if (length < static_cast<size_t>(RidgeTuning::guidedIsolatedRun) && !cells.near(at(first)) &&
        !cells.near(at(last))) {
      for (size_t p = first; p <= last; ++p)
        drop[static_cast<size_t>(order[onTheRing(p, n)])] = 1;
      any = true;
    }
    first += length;
    done += length;
  }
  if (!any)
    return;
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i)
    if (!drop[i])
      crossings[kept++] = crossings[i];
  crossings.resize(kept);
}
} // namespace vsp::laser_detector
