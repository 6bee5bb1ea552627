/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file search_region.h
  \brief The search region of vpLaserConicDetector (internal header): a conic sampled along the image
  rows and columns, and a band around sampled points rasterised into the spans the ridge passes read.
*/
#ifndef VP_LASER_SEARCH_REGION_H
#define VP_LASER_SEARCH_REGION_H

#include <vector>

#include <visp3/core/vpImagePoint.h>

#include "laser_detector.h"

namespace vsp::laser_detector
{
//! Real roots of a t^2 + b t + c = 0 (a may be zero) written to \e roots; returns how many (0 to 2).
int quadraticRoots(double a, double b, double c, double roots[2]);
//! Real roots of a t^2 + b t + c = 0 (a may be zero) appended to \e roots.
void solveQuadratic(double a, double b, double c, std::vector<double> &roots);

/*!
  The points of the conic a u^2 + 2 b uv + c v^2 + 2 d u + 2 e v + f = 0 on every row and every column of
  a large image (16384 pixels, from -margin - 1), appended to \e points: the points outside an image are
  ignored when the region is rasterised. With \e points null, the search stops at the first point. Returns
  whether the conic has any.
*/
bool sampleConicOnLines(double a, double b, double c, double d, double e, double f, double margin,
                        std::vector<vpImagePoint> *points);

/*!
  Rasterises the band within \e margin pixels of the points \e region, for an image of H x W pixels and
  stripes up to \e stripeWidth pixels wide: \e searched receives the blocks of 16 columns by bands of
  RegionSpans::bandHeight rows that meet the band, \e scored the same dilated by the reach of the ridge tests
  (profileReach() of the stripe width along the rows and the columns, rounded up to whole blocks and bands).
*/
void rasteriseBand(const std::vector<vpImagePoint> &region, double margin, int stripeWidth, int H, int W,
                   RegionSpans &searched, RegionSpans &scored);
} // namespace vsp::laser_detector

#endif
