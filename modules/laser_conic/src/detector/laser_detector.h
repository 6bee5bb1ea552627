/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_detector.h
  \brief The two laser stripe detectors behind vpLaserConicDetector (internal header): the ridge of a
  red-dominance score with an adaptive threshold, and the historical HSV thresholding.
*/
#ifndef VP_LASER_DETECTOR_H
#define VP_LASER_DETECTOR_H

#include <algorithm>
#include <utility>
#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>

namespace vsp::laser_detector
{
//! A column span [first, last] of an image row.
typedef std::pair<int, int> Span;

/*!
  Column spans of each image row of a search region. The region is rasterised in bands of rows that share
  their spans (one list per band instead of one per row: no per-row allocation), stored one after the
  other: band b owns spans [bandStart[b], bandStart[b + 1]).
*/
struct RegionSpans
{
  static const int bandShift = 3;               //!< rows per band: 2^bandShift (a shift, not a division, per row)
  static const int bandHeight = 1 << bandShift; //!< rows per band
  std::vector<Span> spans;                      //!< the spans of every band, band after band
  std::vector<int> bandStart;                   //!< first span of each band, plus the end
  //! First span of row i.
  const Span *begin(int i) const { return spans.data() + bandStart[static_cast<size_t>(i >> bandShift)]; }
  //! One past the last span of row i.
  const Span *end(int i) const { return spans.data() + bandStart[static_cast<size_t>(i >> bandShift) + 1]; }
};

/*!
  \e value converted to an int no larger than \e highest, the bound applied while it is still a double: the
  minimum segment length and the threshold factors have no upper bound, and a double beyond an int's range
  converted to it is undefined behaviour. A NaN gives \e highest.
*/
inline int toIntAtMost(double value, int highest)
{
  return static_cast<int>(std::min(static_cast<double>(highest), value)); // std::min keeps its first on NaN
}

//! Settings of the ridge detector (see vpLaserConicDetector).
struct RidgeSettings
{
  double minContrast;                                  //!< grey levels
  double noiseFactor;                                  //!< threshold = max(minContrast, noiseFactor x noise)
  int maxWidth;                                        //!< widest stripe and background distance d, pixels
  int saturation;                                      //!< saturated red level
  double minSegment;                                   //!< shortest chain, pixels
  int step;                                            //!< sampling step of the scan lines
  vpLaserConicDetector::vpInstructionSet instructions; //!< one the processor has (never INSTRUCTIONS_BEST)
};

//! What the ridge detector measured besides the points.
struct RidgeReport
{
  double threshold = 0.0; //!< contrast threshold used
  double noise = 0.0;     //!< estimated score noise
};

//! A stripe run measured along a scan line, for the diagnostic mask: along row `line` when alongRow (else
//! along column `line`), its half-maximum run [first, last], accepted (a returned point) or rejected.
typedef vpLaserConicDetectorRun StripeRun;

//! A candidate peak: its scan line and its position along it.
struct Candidate
{
  int line, pos;
};

//! A measured stripe crossing: its sub-pixel centre and its half-maximum run [first, last] along the line.
struct Crossing
{
  vpImagePoint point;
  bool alongRow = true;
  int line = 0, first = 0, last = 0;
};

/*!
  Buffers of the ridge detector kept from frame to frame (by vpLaserConicDetector), so that a detection
  allocates nothing once the first frame of a size has been processed.
*/
struct RidgeWorkspace
{
  std::vector<unsigned char> score;      //!< red-dominance score, H x W
  std::vector<unsigned char> blockFlags; //!< per row, per 16 columns: 0xFF when a score reaches the threshold
  std::vector<Candidate> rowPeaks, columnPeaks;
  std::vector<Crossing> crossings;
  std::vector<int> lastEnd;                    //!< per column, end of the last measured run
  std::vector<unsigned char> zeros;            //!< W zero scores: the rows beyond the image border
  std::vector<int> bandStart;                  //!< chaining: first sorted crossing of each band of rows, plus the end
  std::vector<int> order, cursor, parent;      //!< chaining: sorted order, column then band cursors, union-find
  std::vector<int> bandOf, columnOf, byColumn; //!< chaining: band and column of each crossing, column order
  std::vector<double> sortedU, sortedV;        //!< chaining: the crossings' coordinates in sorted order
  std::vector<int> sortedColumn;               //!< chaining: the crossings' columns in sorted order
  std::vector<double> minU, maxU, minV, maxV;  //!< chain bounding boxes
  std::vector<unsigned char> keep;             //!< crossings on long chains
  RegionSpans scoreRegion, searchRegion;       //!< rasterised search region (see vpLaserConicDetector)
  std::vector<unsigned char> cells;            //!< coarse to fine: the cells near the coarse crossings kept
  RegionSpans fineRegion;                      //!< coarse to fine: those cells rasterised
  std::vector<unsigned char> coarseScore, coarseFlags, coarseZeros; //!< coarse to fine: the coarse columns
  std::vector<Crossing> guided; //!< the crossings the guided pass added (see guided_pass.h)
  //! The ellipse the whole search located, its symmetric 3 x 3 matrix (empty when it located none): the retry
  //! with short chains weighs its own against it (see vpLaserConicDetector's locateFromShortChains()).
  std::vector<double> searchEllipse;
  std::vector<int> guidedCells, guidedNext; //!< guided pass: per cell its last point found, and the previous one's
  std::vector<vpImagePoint> guidedFound;    //!< guided pass: the points found (both passes), in cell lists
  int guidedColumns = 0;                    //!< guided pass: columns of the cell grid of guidedCells
  unsigned int regionHeight = 0, regionWidth = 0, regionGeneration = 0; //!< what the region was rasterised for
  bool regionValid = false;
};

/*!
  Fills \e mask (resized to H x W) with the runs of the last ridge detection: the rejected candidate runs
  \e runs and the measured crossings of \e work, 255 on the crossings kept (on long chains), 100 on the others,
  170 on those of the guided pass (work.guided).
*/
void drawRuns(const std::vector<StripeRun> &runs, const RidgeWorkspace &work, unsigned int H, unsigned int W,
              vpImage<unsigned char> &mask);

/*!
  Ridge detector. \e scoreRegion / \e searchRegion: null for the whole image, else the rows to score
  (the search region dilated by the background distance) and the rows to search. \e work holds the buffers
  and, until the next detection, the measured crossings; \e runs receives the rejected candidate runs (see
  drawRuns()).
*/
std::vector<vpImagePoint> detectRidge(const vpImage<vpRGBa> &I, const RidgeSettings &settings,
                                      const RegionSpans *scoreRegion, const RegionSpans *searchRegion,
                                      RidgeWorkspace &work, std::vector<StripeRun> &runs, RidgeReport &report);

/*!
  The row sample of the ridge detector over the whole image: every sampledRowStep()-th row alone is scored,
  searched and measured (any stripe crossing it, whatever its slope: the rows around are not read), and the
  crossings on chains of the minimum length less three of those steps are returned (the others stay in
  \e work, see drawRuns()). Enough to locate a ring for the guided pass at an eighth of the frame's reads.
*/
std::vector<vpImagePoint> detectRidgeRows(const vpImage<vpRGBa> &I, const RidgeSettings &settings, RidgeWorkspace &work,
                                          std::vector<StripeRun> &runs, RidgeReport &report);

//! The rows of detectRidgeRows() are this many apart: the coarse lines of the whole search (see coarseFactor()).
int sampledRowStep(const RidgeSettings &settings);

//! Settings of the HSV detector.
struct HsvSettings
{
  int maxHueLow, minHueHigh, minSaturation, minValue, maxWidth, step;
};

//! HSV thresholding detector (the historical one); \e mask is resized and filled (255 on the trace pixels).
std::vector<vpImagePoint> detectHsv(const vpImage<vpRGBa> &I, const HsvSettings &settings,
                                    vpImage<unsigned char> &mask);
} // namespace vsp::laser_detector

#endif
