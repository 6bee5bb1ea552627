/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include <visp3/robust/vpRansac.h>

#include <algorithm>
#include <cmath>

int vpRansacTrialCount(double probability, double outlierRatio, int sampleSize, int maxTrials)
{
  if (!(probability > 0.0))
    return std::min(1, maxTrials);
  if (std::isnan(outlierRatio))
    return maxTrials;
  if (!(outlierRatio > 0.0))
    return 0;
  if (!(probability < 1.0) || !(outlierRatio < 1.0))
    return maxTrials;
  const double goodSample = std::pow(1.0 - outlierRatio, sampleSize);
  if (!(goodSample > 0.0))
    return maxTrials;
  // log1p keeps precision when good samples are rare.
  const double n = std::log(1.0 - probability) / std::log1p(-goodSample);
  if (!(n < double(maxTrials)))
    return maxTrials;
  return std::max(1, static_cast<int>(std::ceil(n)));
}
