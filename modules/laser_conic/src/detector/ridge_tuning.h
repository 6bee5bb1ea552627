/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_tuning.h
  \brief The fixed shape rules of the ridge detector (internal header), named in one place: each is a
  property of a laser stripe seen by a camera, not a setting a user would change.
*/
#ifndef VP_LASER_RIDGE_TUNING_H
#define VP_LASER_RIDGE_TUNING_H

namespace vsp::laser_detector
{
//! The ridge detector's fixed shape rules (the settings a user may change are in RidgeSettings).
struct RidgeTuning
{
  // --- Score (ridge_score.cpp) ---
  //! Grey levels of the red channel below the saturation level over which the score ramps from the red
  //! dominance to 255: a saturating stripe is then a plateau joined continuously to its red flanks, with
  //! no jump at the saturation level for the sensor noise to flicker on.
  static constexpr int saturationRamp = 30;

  // --- Profile test (ridge_profile.cpp) ---
  //! Pixels beyond the half-maximum run searched for the red flanks of a white saturated core: the
  //! bloom of a saturated core leaves its red flanks about that far out.
  static constexpr int whiteFlankReach = 2;
  //! A crossing whose peak across the line exceeds its own background by more than this times its
  //! contrast along the line is a line grazing the flank of a stripe (nearly tangent to it).
  static constexpr double grazingPeakRatio = 1.5;
  //! The same against the background across the line: the stripe's contrast across a grazing line is
  //! more than this times its contrast along it.
  static constexpr int grazingContrastRatio = 2;
  //! The sub-pixel centre is the centroid of the score above bg + contrast / centroidLevelDivisor: low
  //! enough to use the whole stripe, high enough to leave out the background's noise.
  static constexpr int centroidLevelDivisor = 4;

  // --- Chaining (ridge_chains.cpp) ---
  //! Neighbours along a chain are within linkSteps sampling steps (plus linkSlack pixel): two steps
  //! bridge a line where a dim stripe misses its crossing.
  static constexpr double linkSteps = 2.0;
  //! Slack (pixels) of every link radius: crossings exactly linkSteps steps apart stay linked despite
  //! their sub-pixel centres.
  static constexpr double linkSlack = 0.5;

  // --- Coarse to fine (ridge_cells.cpp, ridge_detect.cpp) ---
  //! The coarse lines are every maxCoarseFactor-th line at most: beyond, a stripe's few coarse crossings
  //! no longer tell it from a short red ridge.
  static constexpr int maxCoarseFactor = 8;
  //! A chain of the minimum length crosses at least this many coarse lines (it sets the coarse factor).
  static constexpr double coarseLinesPerChain = 4.0;
  //! The coarse crossings of a chain may fall short of its ends by up to a coarse step each way: the
  //! coarse chains need only be the minimum length minus this many coarse steps.
  static constexpr double coarseShortfallSteps = 3.0;
  //! Link radius of the coarse chains, in coarse steps (as linkSteps for the lines of the fine pass).
  static constexpr double coarseLinkSteps = 2.0;
  //! Link radius, in coarse steps, of the short coarse chains near the long ones: a dim stripe misses a
  //! coarse crossing here and there, and two coarse steps along a stripe at 45 degrees are 2.8 apart.
  static constexpr double coarseBridgeSteps = 3.0;
  //! The short chains joined to the long ones are those in the cells within coarseReachSteps coarse
  //! steps + coarseReachExtra pixels of a long chain's crossing (the bridge radius, rounded up).
  static constexpr int coarseReachSteps = 3;
  //! See coarseReachSteps.
  static constexpr int coarseReachExtra = 1;
  //! The fine lines are searched around the kept coarse crossings up to half the bridge reach plus this
  //! many pixels: the fine crossings between two linked coarse ones, and the stripe's width about them.
  static constexpr int fineReachExtra = 4;
};
} // namespace vsp::laser_detector

#endif
