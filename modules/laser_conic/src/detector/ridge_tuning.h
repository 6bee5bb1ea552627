/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file ridge_tuning.h
  \brief The fixed shape rules of the ridge detector and of its conic-guided pass (internal header), named
  in one place: each is a property of a laser stripe seen by a camera, not a setting a user would change.
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

  // --- Guided pass (guided_*.cpp) ---
  //! Noise floor (grey levels) of a profile: 8-bit quantisation and JPEG leave at least this much, and a
  //! flat profile (a clipped dark floor) must not make every bump significant.
  static constexpr double guidedNoiseFloor = 0.5;
  //! Smallest matched-filter response (grey levels) whatever the noise: two quantisation steps.
  static constexpr double guidedMinResponse = 2.0;
  //! Pixels between the stripe box and its background boxes of the matched filter (the stripe's tails).
  static constexpr int guidedGap = 1;
  //! A kept piece of curve is anchored to a point already found, or has at least this many points.
  static constexpr int guidedMinRun = 8;
  //! Consecutive samples without a point that still leave a piece of curve unbroken.
  static constexpr int guidedMaxMisses = 3;
  //! Largest change (pixels) of the offset to the prediction between consecutive points of a piece,
  //! plus guidedPerSampleJump per sample between them: the prediction is smooth, so is the true curve.
  static constexpr double guidedMaxJump = 1.0;
  //! See guidedMaxJump.
  static constexpr double guidedPerSampleJump = 0.5;
  //! Largest distance (pixels) of a second-pass point to the final conic, and of the points that conic is
  //! refitted on (refitOnItsInliers()) to the fit of them all: the first pass's inlier threshold (its centres
  //! are within a few tenths of a pixel of a conic trace), plus half a pixel for JPEG: where the stripe runs
  //! along a step of the floor's red, the chroma (at half resolution) moves its red-dominance peak 1-2 px
  //! towards the brighter side, and such a point is still the stripe (regularised along the curve,
  //! smoothAlongCurve(), it is moved onto its neighbours' line). 2 px dropped them: 94.9 -> 95.8 % of the ring
  //! found on FadingRingOnATexturedFloorWithReflectanceScaledLight, 93.4 -> 94.5 % on average over ten seeds of
  //! it, precision 0.999 -> 0.998.
  static constexpr double guidedFinalDistance = 2.5;
  //! Refits of the final conic on the points within guidedFinalDistance of it (refitOnItsInliers()).
  static constexpr int guidedFinalRefits = 2;
  //! Covered samples on each side of a gap whose offsets to the final conic are interpolated across it
  //! (ringOffsets()).
  static constexpr int guidedGapEnds = 5;
  //! Longest gap (pixels between the covered samples at its ends) across which the final conic's samples are
  //! measured again (ringOffsets()): a stretch where the walk lost the stripe (a joint crossed, a cable's
  //! flank), not one where the ring may have left the ellipse. On the servo-landing tutorial (ctest
  //! tutorial_laser_servo_landing), whose ring steps onto a box beside the landing pad, longer gaps measured
  //! again fed GP-3 points of the box's arc near the ellipse, and through the next frame's search region
  //! more of them, until its plane lay 80-130 mm above the floor: without a limit, or at 60 or 80 px, the
  //! filter rejected 60-61 frames and diverged; at 30, 40 or 50 px it rejected 1 (as before the step). Mosaic
  //! floor, seeds 73-102, ring at 3 sigma: 97.45 % without a limit, 97.37 % at 40 px, 97.33 % at 30 px.
  static constexpr double guidedGapLength = 30.0;
  //! Farthest (pixels) the walk into a long gap on the brightness (walkIntoLongGaps()), once it has found the
  //! stripe past its covered end, goes past its last point without finding another. Near 3 sigma through strong
  //! JPEG a profile of nine lines finds the stripe at one sample in a few, in runs of misses longer than
  //! guidedMaxMisses, where the walk stopped before: the faint ring through JPEG 60 (testLaserConicGuidedSearch,
  //! seeds 72, 60, 65) 92.10 -> 93.80 % of the ring at 3 sigma on average. A walk that has found nothing past
  //! its end still stops at guidedMaxMisses: beside a dark box over a ring the ends are too dim for
  //! guidedStrongStripe, and a longer first reach took the JPEG blocks of the box's flat face near the ellipse
  //! (`make-laser-sequence --hard --seed 10`, frame 36: altitude 1.1 -> 6.8 mm). At 30 px (with that first reach
  //! too) walks through the wide lens took points 1.5 px off the ring.
  static constexpr double guidedWalkGap = 20.0;
  //! Smallest response (grey levels of R + G + B a line) of a point the walk into a long gap finds after more
  //! than guidedMaxMisses samples in a row without one (walkKeeps()). The brightness's threshold comes from the
  //! noise along the profile, which on a flat dark face (a box over the ring) is so low that JPEG's blocks pass
  //! it: past such a run a walk took them as the stripe (`make-laser-sequence --hard --seed 33`, frame 13:
  //! altitude 16.3 -> 20.7 mm, 29 of the frame's points outliers of GP-3). At 6 the faint rings kept a third
  //! of the gain.
  static constexpr double guidedBridgeLevel = 4.0;
  //! Largest Sampson distance (pixels) of a point on the ellipse that locates a trace (fitTraceEllipse()): the
  //! first pass's centres are within a few tenths of a pixel of the trace.
  static constexpr double traceInlierDistance = 2.0;
  //! Smallest minor-to-major axis ratio of the ellipse that locates a trace (fitTraceEllipse()). An ellipse fitted
  //! to a short arc that is nearly straight can be flat enough to run along the arc on both of its long sides
  //! (semi-axes 70 and 0.8 px through 25 degrees of a faint ring's near side, which JPEG 60 had broken into
  //! pieces elsewhere): the guided pass then found most of its samples covered by the arc's own points and
  //! trusted it (coverage 0.97), and the retry that locates the ring from shorter chains did not run. A ring
  //! seen at 84 degrees from its plane's normal is still 0.1; the rendered tests and the hard sequences' rings
  //! are 0.24 and more.
  static constexpr double traceMinAxisRatio = 0.1;
  //! Refits at most: the coverage stops growing after two or three on every case seen.
  static constexpr int guidedMaxIterations = 4;
  /*!
    A walk along a refitted conic that takes points at more than guidedWanderShare of its samples while the
    coverage grows by less than guidedWanderGain is the last: the refits move the conic through clutter
    (the edges and patches of a colourful floor where the laser is off, or away from the ring), and each walk
    measures the moved curve again, finding stripe-like profiles along a third of it. On the shipped hard
    sequence such walks took 0.34-0.45 of their samples for a gain of -0.02 to 0.05 (frames 11, 41 and 47,
    1.1 ms each, none of their ellipses kept), a ring's later walks at most 0.14 (0.37 once, for a gain of 0.26:
    a conic refitted from an arc of a faint ring onto the whole of it).
  */
  static constexpr double guidedWanderShare = 0.3;
  //! See guidedWanderShare.
  static constexpr double guidedWanderGain = 0.1;
  /*!
    A walk whose coverage is more than this under the coverage its caller needs (GuidedSettings::usefulCoverage)
    ends the pass: the refits would have to grow it by more than any did. From its first walk to its last a
    pass grew by 0.445 at most over the 2832 passes of the hard sequences of seeds 1-24 at JPEG 60 and 80
    (`make-laser-sequence --hard --seed N`). On a frame without the laser, the walks along the retry's ellipse
    through a colourful floor's red patches covered 0.08 of it (the benchmark's 1600 x 1200 frames, 5 ms each).
  */
  static constexpr double guidedMaxCoverageGrowth = 0.6;
  //! Side (2^guidedCellShift pixels) of the cells that record where points were found (a sample near one is not
  //! measured again).
  static constexpr int guidedCellShift = 2;
  //! A sample is known (not measured again) when a point found lies within guidedKnownAlong pixels of it along
  //! the predicted curve (half the spacing of the profiles, rounded up) and within guidedKnownAcross pixels across
  //! it (the prediction's error): a sample just beyond the end of a first-pass chain is measured.
  static constexpr double guidedKnownAlong = 1.0;
  //! See guidedKnownAlong (under 2^guidedCellShift - guidedKnownAlong: the cells searched are those around the sample's).
  static constexpr double guidedKnownAcross = 3.0;
  //! The centres of the second pass are regularised along the curve: their offsets to the final conic are
  //! replaced by a straight-line fit of the offsets of the points within guidedSmoothRadius pixels (the true
  //! centre line is smooth over that length; the noise of one profile is not). The errors of the centres are
  //! correlated over several pixels (JPEG's 8 x 8 blocks, and on a textured floor the stretches of a patch's
  //! edge along which the chroma pulls them to one side), so the radius is long: 40 px against 20 px took the
  //! second pass's RMS on the rendered rings from 0.30 to 0.22 px (mosaic), 0.26 to 0.19 px (faint ring, mean
  //! of seven seeds), 0.10 to 0.08 px (dark floor); the RMS of testLaserConicDetector's traces fell or stayed
  //! (the distorted lens: 0.021 -> 0.019 px). The residuals the pose's covariance is scaled by shrink with it
  //! (vpLaserConicPose::setCovarianceInflation(): raw NEES 55-64 -> 72-84 on its seeds 101-104). 80 px against
  //! 40 px: mosaic seeds 73-102 RMS mean 0.202 -> 0.135 px, worst seed 0.356 -> 0.258 px, precision 0.9988 ->
  //! 0.9996, ring at 3 sigma 97.33 -> 97.45 %; seeds 103-132 RMS 0.210 -> 0.146 px (worst 0.318 -> 0.239),
  //! worst precision 0.978 -> 0.998; faint ring (seeds 100-119) RMS 0.252 -> 0.201 px; the distorted lens's trace
  //! 0.018 px. 120 px went further on these rendered rings (mosaic 0.106 px) whose centre line is an exact conic
  //! of the image but for the lens's distortion; a real floor's ring is not, so the window stops at 80 px. Raw
  //! NEES 74-87 -> 88-105 (recommendedDetectorInflation() 20 -> 32).
  static constexpr double guidedSmoothRadius = 80.0;
  //! A centre with less than guidedSmoothEnd pixels of arc on one side within guidedSmoothRadius (the end of a
  //! piece of curve, beside a gap) takes the mean of the offsets instead of the straight line, which is
  //! extrapolated there and pulled its last points 1.5-3 px aside along the mosaic's patch joints. Measured:
  //! mosaic (ten seeds) 94.92 -> 95.02 % of the ring, precision 0.9971 -> 0.9984, RMS 0.218 -> 0.212 px (twenty
  //! other seeds: worst precision 0.971 -> 0.988); seven faint rings precision 0.993 -> 0.997, RMS 0.215 ->
  //! 0.188 px; data/laser_hard GP-3 pitch 0.190 -> 0.162 deg. At 20 px and more (the mean nearly everywhere:
  //! mosaic RMS 0.19 px) the servo-landing tutorial's filter rejected 60 frames (1-2 otherwise) and lost the
  //! altitude: its box-edge frames, where the ring steps onto the box (two planes in one trace; GP-3 up to 4 deg
  //! off before too), came 4-5 deg off in a row.
  static constexpr double guidedSmoothEnd = 10.0;
  //! Points a regularised centre needs in its neighbourhood (itself included), else it is left as measured.
  static constexpr int guidedSmoothMinPoints = 5;
  //! Offsets (pixels) farther than this from their neighbourhood's median are left out of its fit.
  static constexpr double guidedSmoothOutlier = 1.0;
  //! A piece of the second pass's points (consecutive along the curve, none farther than guidedGapLength from
  //! the next) with fewer points than this, and no other point (the pass's or the first pass's) within
  //! guidedGapLength of its ends, is dropped once the centres are regularised (dropIsolatedPieces()): where a
  //! ring fades below 2 sigma, such a piece is the walk's best guess over a stretch it otherwise lost, and
  //! whether right or 1.5-2.5 px beside it, nothing around it corrects it. On the faint ring through the wide
  //! lens (testLaserConicGuidedSearch, seed 61) 12 points 1.4 px beside the ring at 1.6-1.8 sigma were 40 % of
  //! the second pass's squared error: RMS 0.329 -> 0.253 px, the seven seeds' mean 0.228 -> 0.206 px, the
  //! faint ring's 0.202 -> 0.191 px; held-out seeds 100-119 faint 0.194 -> 0.183 px, wide lens 0.221 -> 0.206
  //! px (seeds over 0.3 px 2 -> 1), worst precision 0.989 -> 0.992; the ring at 3 sigma as before but for a
  //! piece at 3.4 sigma that JPEG 60 had cut off on both sides (dark box seed 61: 91.8 -> 91.0 %; through the
  //! wide lens and JPEG 60, seed 62: 88.7 -> 87.7 %). Hard sequences (seeds 1-40 at JPEG 60, 1-24 at 80): 3
  //! frames of 3648 moved, by under 1 degree. At 12 seed 61 kept its piece (0.311 px); at 24 the wide lens
  //! lost ring at 3 sigma (worst seed 97.17 -> 96.86 %).
  static constexpr int guidedIsolatedRun = 16;
  //! Image guidedLines averaged into one profile (the line of the sample and its neighbours, shifted along the
  //! predicted curve): the noise falls by sqrt(guidedLines), so a stripe 3 times the background noise stands out.
  static constexpr int guidedLines = 3;
  //! Pixels of background on each side of the matched filter's stripe box, at least: the longer, the less
  //! noisy the background level.
  static constexpr int guidedMinFlank = 4;
  //! A sample next to one whose point is known is first searched within guidedFollowMargin pixels (across the
  //! curve) of that point's offset: a piece of curve moves by guidedMaxJump per sample at most, and the short
  //! profile costs a third of the full margin's. Its threshold uses the noise of a full profile measured at
  //! most guidedNoiseReuse samples before (the background's noise changes slowly along the curve).
  static constexpr double guidedFollowMargin = 3.0;
  //! See guidedFollowMargin.
  static constexpr int guidedNoiseReuse = 8;
  //! A profile searched over its whole margin takes the best response within guidedNearMargin pixels (across the
  //! curve) of the prediction when it passes the threshold, even where a stronger one lies farther off: the
  //! prediction is a fit on hundreds of points (the first pass's inliers lie within 2 px of it; the measured
  //! predictions of the later walks, within half a pixel of the rendered line), so a stripe-like response near it
  //! is more likely the stripe than a stronger one farther off. On a textured floor that one was a patch's edge,
  //! which the following samples then tracked (their follow window is around the last offset) until the piece
  //! broke and the stripe's own points were lost with it (FadingRingOnATexturedFloorWithReflectanceScaledLight:
  //! 93.2 -> 93.6 % of the ring found). The same 3 px as guidedFollowMargin. A follow window that has drifted
  //! farther than guidedNearMargin from a prediction fitted to the points of the whole image (not in tracking)
  //! yields likewise to a stripe near it (the same floor: mean of ten seeds 94.48 -> 94.96 %).
  static constexpr double guidedNearMargin = 3.0;
  //! A sample whose red profile finds nothing where the prediction (fitted to the points of the whole image, not
  //! in tracking) crosses a colour edge, its two background boxes there differing by at least guidedColourEdge
  //! times the response threshold, is measured on its brightness within guidedMaxJump of the prediction, and
  //! its point kept when the response reaches guidedBrightnessStrength times the threshold
  //! (brightnessAtPrediction()). JPEG keeps the colour at half resolution: a stripe running along a patch's edge
  //! is a plateau of the red dominance there, not a peak, while its brightness keeps a bump. Mosaic floor, ring
  //! at 3 sigma: seeds 73-82 95.59 -> 95.82 %, held-out seeds 83-102 94.97 -> 95.34 %; faint rings 98.50 ->
  //! 99.28 %. Measured and not kept: a window of 3 px (the faint rings' precision 0.97 on one seed: noise on
  //! their grey tiles' steps); an edge of half the threshold and any response above it (every mosaic seed >= 95
  //! %, but a faint ring's second-pass RMS 0.32 px, over the 0.3); an edge of three quarters of the
  //! threshold (the faint rings' RMS mean 0.196 -> 0.173 px, through the wide lens seed 61 0.358 -> 0.210 px:
  //! JPEG's colour block steps pass a quarter, and where the ellipse lies inside a distorted trace noise at the
  //! prediction made pieces 1.2-1.4 px inside the ring), but on the hard sequence rendered with seeds 1-24 at
  //! JPEG 80 the faint frame's attitude came 0.1 degree or more worse on 14 seeds, better on 5 (one 2.6 -> 5.3
  //! degrees of roll): the points it leaves out fill the gaps of the dim side, which GP-3 needs more.
  static constexpr double guidedColourEdge = 0.25;
  //! See guidedColourEdge: 4 sigma at the default threshold factor of 3.
  static constexpr double guidedBrightnessStrength = 4.0 / 3.0;
  //! A point measured on the brightness at the prediction (brightnessAtPrediction()) stands at least this share
  //! of the step of the brightness across it (ProfileResult::stepAtStripe) above its background: JPEG rings at a
  //! strong edge, with a bump of a fraction of the step. A dark box over the dim side of the faint ring through
  //! JPEG 60 (testLaserConicGuidedSearch's ADarkBoxOverTheDimSideAddsNoPointAlongItsEdge, its edge 3 px from
  //! the ring) gave 27, 30 and 57 points along its edge on seeds 60, 65 and 61, 2.7-4 px off the ring
  //! (precision 0.954-0.967), none with it (0.982-0.987), their rings at 3 sigma within 0.4 %. On the test cases
  //! without a box: the mosaic's mean 97.73 -> 97.69 % (seeds 73-82), faint ring through the wide lens seed 61's
  //! RMS 0.351 -> 0.329 px, seed 63's 0.190 -> 0.256 px. At 1 or 2 the rings lost more (seed 65 90.5 % at 2).
  static constexpr double guidedEdgeBump = 0.5;
  //! A sample of the final conic that no point covers, in a gap of at most guidedGapLength (the walk lost the
  //! stripe there, or followed a red cable's flank or a joint's edge beside it and its points were dropped as
  //! off the final curve), is measured again within guidedMaxJump of the ring (measureAlongTheFinalCurve()): on
  //! the red score, three lines then nine, its point kept at guidedRemeasureRedStrength times the threshold (4
  //! sigma at the default factor, as guidedBrightnessStrength), then on the brightness, kept at
  //! guidedRemeasureStrength times (6 sigma: the walk was misled there, and a clear bump is asked).
  static constexpr double guidedRemeasureStrength = 2.0;
  //! See guidedRemeasureStrength.
  static constexpr double guidedRemeasureRedStrength = 4.0 / 3.0;
  //! Where the profile of guidedLines lines finds nothing, one of guidedFaintLines lines is measured: the stripe's
  //! response grows as the number of lines, its noise as its square root (three times the noise of one pixel
  //! then stands out by 3.5 times the noise of the response), and the predicted curve is straight within a
  //! twentieth of a pixel over 9 lines on the rings seen (radius 200 px and more). On the rendered faint ring
  //! (JPEG 90) this found 94.7-96.9 % of the ring at 3 sigma or more over seven seeds, against 92.6-95.6 %.
  static constexpr int guidedFaintLines = 9;
  //! The pixels of the profile guidedPrefetchAhead samples on are prefetched while a sample is measured: far
  //! enough for memory to answer, near enough to be still in cache when read.
  static constexpr int guidedPrefetchAhead = 6;
  //! Pixels on each side of the predicted crossing prefetched (a short profile and its background boxes).
  static constexpr int guidedPrefetchReach = 12;
  //! Where the last full profile's response reached guidedStrongStripe times its threshold, the short profile reads
  //! the sample's line alone: the stripe stands out of one line's noise by more than twice the threshold factor,
  //! and the regularisation along the curve averages the noisier centres.
  static constexpr double guidedStrongStripe = 4.0;
  //! measureStretches(): pixels read across the curve on each side of it.
  static constexpr int stretchReach = 10;
  //! measureStretches(): pixels of arc on each side of a point averaged into its stretch's profile (48 px
  //! stretches hold a faint ring's line through JPEG 60 to 0.84 px, see guided_stretches.cpp).
  static constexpr int stretchHalfLength = 24;
  //! measureStretches(): largest offset (pixels) from the final conic fitted; the dim side of a faint ring
  //! through JPEG 60 lay 1.2-3.5 px outside the conic of the points (4.4 px outside the pass's final conic).
  static constexpr double stretchMaxOffset = 5.0;
  //! measureStretches(): a stripe's amplitude over its standard error (from the residuals of the fit, which
  //! hold the profile's misfit as well as its noise: 8-11 along the bright side of the faint ring, 4-12 on its
  //! dim side). At 8, 14 -> 6 of the 24 faint frames under 95 % (seeds 1-24, JPEG 60); at 6, 4.
  static constexpr double stretchSignificance = 6.0;
  //! measureStretches(): the points within this many pixels of their stretch's stripe stay where they are.
  static constexpr double stretchAgreement = 1.0;
  //! measureStretches(): the background's slope (its linear term) over this many stripe sigmas on each side
  //! must stay under half the stripe's amplitude (a colour edge is not a stripe).
  static constexpr double stretchStepWidth = 3.0;
  //! measureStretches(): a stretch's stripe under this share of the ring's (the upper quartile of its stretches)
  //! is no stripe: the shading of an object over the ring fitted 1.3 grey levels at 40 standard errors.
  static constexpr double stretchFaintShare = 0.1;
  //! measureStretches(): the points of a stretch whose stripe is over this share of the ring's (the upper quartile
  //! of its stretches) stay where they are: a bright stripe's profiles hold its line to a few tenths of a pixel,
  //! where a 48 px stretch of the final conic can bend away from it by a pixel (an object's edge over the ring).
  static constexpr double stretchDimShare = 0.35;
  //! measureStretches(): a stretch's stripe fills a gap only where it stands stretchMinPixelSnr times the noise
  //! of one pixel's brightness beside the ring (pixelNoiseBeside()), and moves points only at stretchMoveSnr
  //! times (they were measured: the stretch must say more than they do). On the faint ring at JPEG 90
  //! (testLaserConicGuidedSearch's never-tuned seed 104), stretches at 1.3-2.0 times that noise filled its far
  //! side 1.0-1.3 px off the line and one at 3.0-3.6 times moved five points to 1.6-1.7 px off it: second-pass
  //! RMS 0.334 px, 0.287 px at most over seeds 100-119 since. Through JPEG 60, whose blocks smooth the noise
  //! beside the ring, the fills that find a faint ring's dim side stand at 2.5-5 times it and the moves at 9-27
  //! times (the strong-JPEG test and the hard sequences, seeds 1-24 and 65-80, found the same share of the ring).
  static constexpr double stretchMinPixelSnr = 2.2;
  static constexpr double stretchMoveSnr = 4.4;
  //! measureStretches(): a gap's stretch fills it when its stripe lies within stretchGapContinuity pixels, plus
  //! stretchGapDrift per pixel of arc, of the offset of the last point before it (a fading ring's dim side
  //! drifts from the conic of its points by 1.2-3.5 px over ~300 px of arc).
  static constexpr double stretchGapContinuity = 1.0;
  static constexpr double stretchGapDrift = 0.02;
  //! measureStretches(): no stretch is measured along a conic whose perimeter is over this many times W + H.
  static constexpr double stretchMaxPerimeter = 8.0;
  //! measureStretches(): rounds, the final conic refitted on the points between them.
  static constexpr int stretchRounds = 2;
  //! oneStripe(): the two halves of a stretch agree on the stripe's offset within this many pixels and on
  //! its amplitude within this factor (a stretch across the edge of an object over the ring does not: without
  //! the test, GP-3's attitude over the occluded frames of seeds 1-24 went from 0.385 to 0.408 degree on
  //! average, with it 0.378).
  static constexpr double stretchHalvesAgreement = 1.5;
  static constexpr double stretchHalvesRatio = 3.0;
};
} // namespace vsp::laser_detector

#endif
