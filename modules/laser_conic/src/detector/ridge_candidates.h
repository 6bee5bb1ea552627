/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_candidates.h
  \brief The candidate search of the ridge detector (internal header): the pixels of a score image that
  are local maxima exceeding their background at the stripe width on both sides by the threshold.
*/
#ifndef VP_LASER_RIDGE_CANDIDATES_H
#define VP_LASER_RIDGE_CANDIDATES_H

#include <vector>

#include "laser_detector.h"

namespace vsp::laser_detector
{
/*!
  The columns whose candidates a column pass keeps: the multiples of \e step, except those of \e skip when
  it is not 0 (see detectRidge(): the coarse columns are searched first, the others after).
*/
struct ColumnSelection
{
  int step, skip;
  bool operator()(int j) const { return j % step == 0 && (skip == 0 || j % skip != 0); }
};

/*!
  Candidate peaks along row i of the score image \e c (W columns) within [j0, j1], appended to \e out (near
  the image border one background side only): a pixel is a candidate when its score exceeds the background
  at d pixels (d = stripe width) on both sides by \e threshold and its level at d / 2 + 1 pixels by half of
  it, and is a local maximum along the row. Only the flagged blocks of 16 columns are tested (\e flags: the
  row's block flags, see scoreSpan()).
*/
void rowCandidates(const unsigned char *c, const unsigned char *flags, int W, int i, int j0, int j1, int d,
                   int threshold, vpLaserConicDetector::vpInstructionSet instructions, std::vector<Candidate> &out);

/*!
  Candidate peaks along the columns (those that \e keep selects) at row i within [j0, j1], as
  rowCandidates() along the rows. \e zeros: a row of W zero scores, standing for the rows beyond the image
  border (the score there counts as 0).
*/
void columnCandidates(const unsigned char *c, const unsigned char *flags, const unsigned char *zeros, int W, int H,
                      int i, int j0, int j1, int d, int threshold, const ColumnSelection &keep,
                      vpLaserConicDetector::vpInstructionSet instructions, std::vector<Candidate> &out);
} // namespace vsp::laser_detector

#endif
