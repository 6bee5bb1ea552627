/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicDetector.h
  \brief Red laser trace extraction in a colour image: ridge of a red-dominance score with a threshold
  adapted to the image (default), or HSV thresholding (Sec. 7.2 of the paper).
*/
#ifndef VP_LASER_CONIC_DETECTOR_H
#define VP_LASER_CONIC_DETECTOR_H

#include <memory>
#include <utility>
#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicException.h>
#include <visp3/laser_conic/vpLaserConicImageMember.h>

namespace vsp::laser_detector
{
struct RidgeWorkspace;
struct GuidedSettings;
struct RidgeSettings;
} // namespace vsp::laser_detector

//! A stripe run measured by vpLaserConicDetector (the diagnostic mask getMask() is drawn from them).
struct vpLaserConicDetectorRun
{
  bool alongRow; //!< measured along row \e line (else along column \e line)
  int line;      //!< row or column index
  int first;     //!< first pixel of the half-maximum run along the line
  int last;      //!< last pixel of the half-maximum run along the line
  bool accepted; //!< a returned point (else a rejected candidate)
};

/*!
  \ingroup group_laser_conic
  \brief Extracts the sub-pixel image points of a red laser stripe (the trace of a circular laser).

  <b>Ridge method (default, DETECTION_RIDGE).</b> Each pixel gets a red-dominance score
  \f$ s = \max(0, R - \max(G, B)) \f$, or 255 when its red channel is saturated (R >= setSaturationLevel()),
  computed in one pass over the RGBA buffer (no colour conversion). A laser stripe is a thin ridge of
  that score across its width, whatever the floor's brightness; it is found along the image rows and
  along the columns:
  -# <em>Candidates.</em> A pixel is a candidate peak along a scan line when its score is a local maximum
     that exceeds the score at \f$ \pm d \f$ pixels on both sides by at least the contrast threshold
     T, with d = setMaxStripeWidth() (a top-hat test: a step edge or a plateau wider than the stripe
     fails it). T = max(setMinContrast(), setNoiseFactor() x sigma), where sigma is the noise of the score
     estimated from the image itself (robust spread, 1.4826 MAD / sqrt(2), of the score differences
     two pixels apart on a sample of rows), so the threshold follows the image's own background and noise
     instead of an absolute saturation/value.
  -# <em>Shape.</em> The stripe around the peak is the run of pixels above half of its contrast (half
     maximum above the background, the larger score at \f$ \pm d \f$). Runs wider than
     setMaxStripeWidth() are wide red objects, not a stripe, and are rejected. A run containing white
     saturated pixels (R >= saturation level, low score) is one stripe with a saturated core only when red
     pixels flank the white on both sides; white light without a red flank (a lamp reflection, white tiles)
     is rejected.
  -# <em>Sub-pixel centre.</em> The centroid of the score above a quarter of the contrast over the run
     (a saturated core is a plateau of 255: the centre is the centre of the whole profile).
  -# <em>Scan direction.</em> A row measures the parts of the curve closer to vertical, a column the parts
     closer to horizontal: a row point is kept when the stripe's half-maximum run along the row is not
     longer than along the column through its peak (and conversely), so the centre of a run along a
     nearly tangent line is never returned (both may be kept at 45 degrees).
  -# <em>Continuity.</em> Points are chained (neighbours within 2 sampling steps) and chains whose extent
     (bounding-box diagonal) is below setMinSegmentLength() are dropped: small red clutter and isolated
     texture or noise peaks give short chains, the trace long ones.

  <em>Whole image: a sample of rows, then the ring along its ellipse (default).</em> With the guided pass
  on (setGuidedSearch(), below), every 8th row (every 8 x setSamplingStep()-th, as the coarse lines below)
  is scored, searched and measured alone, an eighth of the frame read; a stripe crossing a row is measured
  whatever its slope (the rows around are not read), and the crossings on chains of the minimum length are
  fitted with an ellipse as below. When it is found, the guided pass measures the ring along it, and only
  the sample's crossings on the ellipse where a row crosses it more steeply than a column are returned with
  the guided pass's points (clutter and distractors the sample crossed are not). When the rows locate no
  ellipse (a small or partial trace, a hyperbola, a line), or the guided pass ends with a point on fewer
  than 80 % of its profiles (an ellipse through clutter and a piece of the ring, or extrapolated from the
  bright arcs of a fading ring), or on fewer than 95 % when the ellipse holds under half the sample's
  crossings (a red cable, the edges of a colourful floor: the pass finds stripe-like profiles along most
  curves there), the whole image is searched as follows and the guided pass follows that
  search's ellipse (sought with more RANSAC samples: such frames hold clutter); when the pass finds the ring
  along 80 % of that ellipse, the search's points off it are not returned either. When it finds it along
  less than 95 %, the search runs once more with chains a third of setMinSegmentLength() long (through
  strong JPEG compression a ring on a colourful floor, or the near side of a faint one, breaks at every
  patch into pieces of 16-45 px): the ellipse through them (2000 RANSAC samples, half of them two points of
  one chain, two of another and one of a third: the ring is a fifth to a half of such points, in a few of many
  chains), sought without the points on straight runs of 150 px or more (a red cable, tape on
  the floor: an arc of a ring that fits in the image never is one), is taken when the guided pass finds the
  ring along 95 % of it and 10 % more of it than along the first search's, or when it holds 90 % of the short
  chains' points and the pass finds half of it, and either 10 % more than along the first search's ellipse or
  twice as many of those points lie on it as on the first search's (a faint ring alone in a dark scene, whose
  far side the image no longer holds, and of whose near side the first search kept one arc); otherwise the
  first search's points are returned. A frame of 1600 x 1200 pixels costs a third of one cv::cvtColor pass; a
  frame where no ring is located (the laser off) costs the three searches: 0.9 times one on plain floors with
  red patches, 2.1 times on a colourful floor with them (bench-peers --only laser-frame).

  <em>Coarse to fine.</em> Over the whole image the candidates of every 8th row and column only are
  measured first (every 8 x setSamplingStep()-th line; fewer when setMinSegmentLength() is below 32
  sampling steps, and none of this below 8), their crossings chained at that scale; the other lines are
  then searched only around the coarse chains that may reach the minimum length. On a textured floor
  most candidates are short ridges (a corner of a tile between two dark joints is a thin wedge of its
  colour), which are measured on the coarse lines only. On every rendered test case and every frame
  shipped in data/, the points are those of the search of every line (in another order).

  <em>Second pass, guided by the conic (default, setGuidedSearch()).</em> The first pass keeps the bright
  parts of a ring whose brightness falls along it (distance to the laser, incidence angle, dark or black
  floor patches). After it (or after the sample of rows above), an ellipse is fitted robustly to the points
  kept (RANSAC on five-point conics, 2 px), provided at least 30 of them agree over an arc of 60 degrees or
  more and its minor axis is at least a tenth of its major (flatter, it lies along both sides of a short,
  nearly straight arc), and the image is searched
  along that predicted curve: on every setGuidedStep()-th row (where the curve is closer to vertical) and
  column (elsewhere) it crosses, where no point lies on it yet, a profile of the red dominance across the
  curve within setGuidedMargin() pixels of it, averaged over three neighbouring lines shifted along the
  curve, goes through a matched filter for a stripe of the observed width (the median half-maximum width
  of the first pass's crossings, those of the sample of rows converted to the line crossing more steeply) whose response must exceed setGuidedThresholdFactor() times its own noise,
  measured along that profile (robust spread of its second differences, which the blurred steps between
  the patches of a textured floor do not raise): a threshold local to the profile instead of the global
  contrast. Around the best response, the first pass's shape tests (width, white light) and
  sub-pixel centre apply (a saturated core needs red flanks out of one line's noise by the same factor, or,
  in a lamp's glare, where the red channel in the saturation ramp raises that noise, out of the red
  dominance's own noise along the line).
  A profile next to one with a point is first searched within 3 px (across the curve) of that point, with
  the noise of the last full profile (measured at most 8 profiles before); the whole margin is searched
  when that finds nothing. A piece of curve moves by about a pixel per profile: the short profile finds its
  continuation at a third of the cost. Where the last full profile's response reached 4 times its threshold
  (a bright stripe), the short profile reads the sample's line alone. Where the three-line profile finds
  nothing, one of nine lines is measured: a faint stripe's response grows as the lines averaged, the
  noise as their square root. Where all of these lose a followed stripe, the 3 px window is searched once
  more on the brightness R + G + B (three lines, nine where they find nothing; its noise measured across
  the whole margin), and a point within 1 px of the followed one is kept: JPEG stores the colour at half
  resolution and coarser than the brightness, and beside a colour edge it smears a dim red stripe's
  dominance into a plateau several pixels wide, while the brightness keeps the stripe's bump. For the same
  reason, a profile that finds nothing where the prediction crosses a colour edge (its two background boxes
  there differ by a quarter of the threshold or more) is searched on the brightness within 1 px of the
  prediction, its point kept at 4 times the noise (not in tracking, whose prediction is the previous frame's).
  The walk goes one way round the curve: where it loses the stripe and finds it again a few profiles on, the profiles in
  between are followed back from there.
  Only pieces of curve that continue it are kept: runs of found profiles whose
  offset to the prediction changes smoothly, touching a point already known or at least 8 profiles long.
  The ellipse is refitted on all the points and the walk repeated until no point is added (at most 4
  times), or until a walk takes points along a third of the curve without covering a tenth more of it
  (refits moving the ellipse through clutter: each walk measures the moved curve again). A pass whose
  ellipse is taken only from a coverage on (the sample of rows', the retry's: see above) stops at a walk
  that covers 0.6 less than that, and skips the final steps below when its last walk covers less than
  that. Over the whole image the final ellipse is then refitted on the points within 2.5 px of it, twice
  (the fit of all the points was pulled by the pieces a walk took beside the ring), and the points more
  than 2.5 px from it are dropped (a walk that slid onto a red cable's flank or a joint's edge beside the
  stripe). Every profile of the final ellipse that no point covers, in a gap of at most 30 px between points
  (longer, the ring may have left the ellipse: onto a box, under an object), is measured once more within
  1 px of where the points on either side put the ring (the ellipse itself on an undistorted image), on the red
  score (three lines then nine, kept at 4 times the noise), then on the brightness (6 times), its points
  kept in pieces as the walk's are (not in tracking, whose prediction is the previous frame's and whose
  points are dropped at the ellipse refitted on them all). A longer gap is followed from each of its ends
  where the stripe has faded (under 4 times its threshold on the red score: a bright stripe that stops was
  hidden, not faded) on the brightness, nine lines within 1 px of the last point's offset, each point kept
  at 4 times the noise, until 4 profiles in a row find none or, once it has found the stripe past its end,
  until it is 20 px past its last point (a point after more than 4 misses in a row must stand 4 grey levels
  of R + G + B a line above its background): through strong JPEG a faint ring's dim side keeps its
  brightness but hardly its colour (not in tracking either). Last, the centres of this pass are regularised
  along the curve: each one's offset to the final
  ellipse is replaced by a straight-line fit of the offsets within 80 px of arc on either side (offsets more than
  1 px from a first fit left out), since one profile's centre is noisy (sensor noise, JPEG's 8 x 8 blocks)
  but the centre line is smooth; then a piece of this pass's points shorter than 16 points with no other
  point within 30 px of its ends is dropped (on a far side under 2 times the noise, a walk's lone guess over
  a stretch it otherwise lost, and nothing around it to correct it). On a ring that fades (a gap was followed
  from a faded end), the final ellipse is then measured stretch by stretch: the brightness R + G + B read
  across it at every pixel of arc, averaged over 24 px on each side of a point, and a stripe of the observed
  width, or of a narrower one down to 3 px, whichever fits best (the brightness keeps the luma's full
  resolution where JPEG widens the colour the width is observed on), over a quadratic background (the floor's
  texture averaged along a stretch leaves it a shallow trough) fitted to that mean profile within 5 px of the
  ellipse (significant at 6 standard errors, both halves of the stretch agreeing, over a tenth of the ring's
  own amplitude and over 2.2 times the noise of one pixel's brightness beside the ring). Where such a dim stripe lies more than 1 px from
  the points there and stands 4.4 times that noise, they are moved to it; a gap is filled where the ring
  fades into it or where it is short (30 px), each stretch within 1 px (plus 0.02 px per pixel of arc) of the
  stripe before it; then the ellipse is refitted and the stretches measured once more. A profile alone holds
  such a stripe's line no better than the codec's blocks (see the limits below); 48 px of it do. A walk along
  a refitted ellipse measures again a profile whose prediction moved along its line and finds the same centre:
  each centre is returned once. The points
  of this pass follow those of the first pass in the list returned (getGuidedPointCount()). Distractors stay out: a point must lie within the margin of the predicted curve
  and have a stripe's profile.

  A search region (setSearchRegion()) restricts the search to a band around the predicted curve:
  distractors outside the band are ignored. Given as points (e.g. the previous frame's trace), every
  line of the band is searched by the first pass, and the guided pass stays within the band (on a
  1600 x 1200 frame a band of 20 px costs about as much as the whole image's sample of rows). Given as a
  conic (e.g. the image conic of the previous frame's estimate, vpLaserConicPose::getImageConic()), it is
  the prediction of the guided pass itself (tracking): only the profiles along that conic are read, within
  the region's margin; when they find fewer than 30 points (track lost), the first pass searches the band
  and the guided pass follows as for points.

  <em>Limits, measured on rendered frames against their ground truth.</em> The red dominance is all colour,
  which JPEG keeps at half resolution and quantises coarsely: at quality 60 the far side of a ring fading to
  twice the sensor noise is rounded away, and its brightness alone locates it. There, where the stripe is 3-4
  times the noise, the decoded pixels keep no peak of colour across it (a flat 0-3 grey levels of red dominance
  over 15-20 px) and its brightness survives as the low frequencies of the codec's 8 x 8 blocks, whose peak in
  one profile lies up to 2-3 px from the stripe, or splits in two; the ellipse extrapolated from the bright side
  is then 1-4 px inside it. Averaged over 48 px of arc, the line crosses the blocks at every phase, and the
  stretches measure it within a pixel (the faint frame 56 of `make-laser-sequence --hard --seed 19`: every
  48 px stretch at 3 sigma or more within 0.84 px of it). The faint frame of that sequence, seeds 1-24: 97.4 %
  of the ring at 3 sigma on average, under 95 % on 3 seeds (93.3 % and 14 seeds before the stretches);
  seeds 65-80, never tuned on, 98.2 %, none under 95 % (`scripts/faint_ring_seeds.sh`). What is still lost is
  the darkest stretch, where no fit reaches its significance, and the stretches whose points were off and their
  stripe too dim to move them: at 2-3 times the noise of what the compression kept, the profiles' points may lie
  1.5-2 px inside the ring whatever ellipse they are measured along, and a stretch whose two halves disagree
  may lie as far outside it (seed 71), so neither overrides the other (at quality 80 every seed found 98.1 % or
  more). The centres found on the colour through quality 60 are
  biased by its 16 px blocks, not merely noisy (the test StrongJpegsErrorIsTheColourBlocksBiasNotNoise of
  testLaserConicGuidedSearch measures this on three faint rings, each against the same frame uncompressed):
  the second pass's RMS is 0.28-0.43 px whatever the stripe's strength (3-6, 6-10 or 10-20 times the noise;
  uncompressed 0.01-0.04 px, falling with the strength), the mean error over 15 degrees of arc reaches
  0.62-0.71 px (uncompressed 0.03-0.10 px), and where the ring runs along the columns the mean error in u
  against the column modulo 16 is a sawtooth 0.40-0.58 px deep (uncompressed 0.03-0.04 px): there the line
  keeps its phase to the blocks, and the centres' regularisation along the curve cannot average it away.
  Whence an RMS of 0.35-0.42 px where quality 90 gives 0.15-0.24 px. Such errors are correlated along the ring
  (see vpLaserConicPose::setCovarianceInflation()).
  Record the ring at quality 80 or more when its far side matters.
  A red cable that runs along the ring for a few tens of pixels merges with it into one wider stripe, and the
  ring is not measured there; a ring inside a dark joint beside a brighter tile is a step of the image, not a
  ridge, and is found there in pieces.

  <b>HSV method (DETECTION_HSV, the historical detector).</b> The image is converted to HSV with OpenCV
  and a pixel belongs to the trace when its hue is in the red band (setHueRange()) and its saturation and
  value reach setMinSaturationValue(); each run along a row or column gives its brightness-weighted centre.
  Fixed thresholds: it misses dim stripes and splits saturated ones; kept for comparison.

  The diagnostic mask getMask() marks the runs of the first pass's points (or of the sample of rows') 255,
  those of the guided pass 170 and the rejected candidate runs and crossings not returned 100 (ridge method;
  over the whole image, away from the trace, only those of the sampled or coarse lines), or the thresholded pixels 255 (HSV method). An empty image gives no point and an empty mask.

  \code
  vpLaserConicDetector detector;                       // ridge method, settings for real images by default
  std::vector<vpImagePoint> points = detector.detect(I); // I: vpImage<vpRGBa>
  detector.setSearchRegion(points, 20.0);              // next frame: search within 20 px of this trace
  \endcode
*/
class VISP_EXPORT vpLaserConicDetector
{
public:
  //! Detection method.
  enum vpDetectionMethod {
    DETECTION_RIDGE, //!< ridge of the red-dominance score, adaptive threshold (default)
    DETECTION_HSV    //!< fixed HSV thresholds (historical)
  };

  /*!
    Instruction set of the vectorised passes of the ridge method (score, candidate search). Every choice
    gives the same points; the library is built for any x86-64 processor and picks the AVX2 code at run
    time when the processor has it.
  */
  enum vpInstructionSet {
    INSTRUCTIONS_SCALAR, //!< plain C++ (reference)
    INSTRUCTIONS_SSE2,   //!< 16 pixels at a time (every x86-64 processor)
    INSTRUCTIONS_AVX2,   //!< 32 pixels at a time where it pays (processors with AVX2)
    INSTRUCTIONS_BEST    //!< the best this processor has (default)
  };

  /*!
    Detector with the defaults: ridge method, minimum contrast 10 grey levels, noise factor 5, stripes of at
    most 12 pixels, saturation level 250, segments of at least 50 pixels, every row and column, no search
    region, the best instruction set of the processor; for the HSV method hue <= 10 or >= 170, saturation
    >= 80, value >= 80.
  */
  vpLaserConicDetector();

  //! Chooses the detection method (default DETECTION_RIDGE).
  void setMethod(vpDetectionMethod method) { m_method = method; }
  //! The detection method.
  vpDetectionMethod getMethod() const { return m_method; }

  /*!
    Ridge method: smallest contrast (grey levels of the score R - max(G, B)) of a stripe peak above its
    background; default 10. The threshold used is max(this, noise factor x estimated noise).
    \exception vpLaserConicException::badValueError when not in [1, 255].
  */
  void setMinContrast(double greyLevels);
  //! Smallest stripe contrast, grey levels.
  double getMinContrast() const { return m_minContrast; }
  /*!
    Ridge method: the threshold is at least this many times the score noise estimated from the image;
    default 5. 0 uses the minimum contrast alone; no upper bound (the threshold is capped at 255 grey
    levels, the largest score).
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setNoiseFactor(double factor);
  //! Noise factor of the threshold.
  double getNoiseFactor() const { return m_noiseFactor; }
  /*!
    Widest stripe, pixels: the half-maximum run of a stripe along a scan line (ridge method) or its
    thresholded run (HSV method) must not be longer (blobs are rejected); the ridge method also compares
    a peak with the background at this distance. Default 12 pixels.
    \exception vpLaserConicException::badValueError when 0 or above 100.
  */
  void setMaxStripeWidth(unsigned int pixels);
  //! Widest stripe, pixels.
  unsigned int getMaxStripeWidth() const { return m_maxStripeWidth; }
  /*!
    Ridge method: a red channel at or above this level (0-255) is saturated (core of a bright stripe);
    default 250.
    \exception vpLaserConicException::badValueError when not in [128, 255].
  */
  void setSaturationLevel(unsigned int level);
  //! Saturation level of the red channel.
  unsigned int getSaturationLevel() const { return m_saturationLevel; }
  /*!
    Ridge method: chains of points shorter than this (bounding-box diagonal, pixels) are dropped; default
    50 (red clutter and the thin corners of red floor patches make shorter chains). 0 keeps every point; no
    upper bound (a length longer than the image's diagonal keeps nothing).
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setMinSegmentLength(double pixels);
  //! Shortest kept chain, pixels.
  double getMinSegmentLength() const { return m_minSegmentLength; }
  /*!
    Scans one row/column every \e step (1 = every line); default 1. The guided pass has its own step
    (setGuidedStep()): with the default 1 it measures the lines between.
    \exception vpLaserConicException::badValueError on 0 or above getMaxStep().
  */
  void setSamplingStep(unsigned int step);
  /*!
    The largest step setSamplingStep(), setGuidedStep() and setTrackingStep() take: 10000 lines. A step longer
    than an image's side already reads one line of it; beyond this one a step is taken for a mistake (a value in
    other units, a negative number converted to unsigned).
  */
  static unsigned int getMaxStep() { return 10000; }
  //! Sampling step of the scan lines.
  unsigned int getSamplingStep() const { return m_step; }

  /*!
    Ridge method: instruction set of the vectorised passes; default INSTRUCTIONS_BEST. One the processor
    lacks is replaced by the best it has (see getInstructionSetUsed()); the points do not depend on it.
  */
  void setInstructionSet(vpInstructionSet instructions) { m_instructions = instructions; }
  //! Instruction set asked for by setInstructionSet().
  vpInstructionSet getInstructionSet() const { return m_instructions; }
  //! Instruction set the detection runs with: the one asked for, or the best of this processor if it lacks it.
  vpInstructionSet getInstructionSetUsed() const;
  //! Best instruction set of this processor (and build): INSTRUCTIONS_AVX2, INSTRUCTIONS_SSE2 or INSTRUCTIONS_SCALAR.
  static vpInstructionSet getBestInstructionSet();

  /*!
    Ridge method: searches every pixel within \e margin pixels of the given points (e.g. the trace or the
    inliers of the previous frame; consecutive points along the curve must be closer than the margin), in
    blocks of 16 columns by 8 rows: the band may reach up to 1.15 margin and a block beyond.
    \exception vpLaserConicException::badValueError when the margin is not positive or above getMaxMargin(),
    a point is not finite or the list is empty.
  */
  void setSearchRegion(const std::vector<vpImagePoint> &trace, double margin);
  /*!
    Ridge method: searches only within about \e margin pixels of the conic \e C (3x3 symmetric, pixel
    coordinates: \f$ (u, v, 1) C (u, v, 1)^T = 0 \f$), e.g. the image conic predicted from the previous
    frame's plane (vpLaserConicPose::getImageConic()): the guided pass searches along it (see the class
    description), or, when the track is lost, the first pass searches the band it defines (sampled at each
    image row and column) and the guided pass follows. The track is lost when the guided pass's points
    cover less than 40 % of the predicted curve's length in the image (a frame without the laser over a
    textured floor gives up to 16 %, a ring tracked from frame to frame of a drone-like flight 77-100 %).
    Each tracked frame's stripe width is the next one's matched filter's (the stripe narrows in the image as
    the vehicle climbs). The conic is one of the image searched: with a
    distorted camera, getImageConic() is that of the undistorted image, so the margin must cover the
    distortion along the trace, or the points of the previous trace serve as the region instead. The guided
    pass follows an ellipse only: a hyperbola (the image of a ring seen at a grazing angle, which
    vpLaserConicPose::getImageConic() can be) is searched by the first pass in its band on every frame, as
    when the track is lost.
    \exception vpLaserConicException::badValueError when \e C is not a finite 3x3 matrix, is zero, has no
    real point near the image, or the margin is not positive or above getMaxMargin().
  */
  void setSearchRegion(const vpMatrix &C, double margin);
  //! Removes the search region: the whole image is searched.
  void clearSearchRegion()
  {
    m_region.clear();
    m_regionIsConic = false;
  }
  //! True when a search region is set.
  bool hasSearchRegion() const { return m_regionIsConic || !m_region.empty(); }

  /*!
    Ridge method: runs the second pass guided by the conic of the first pass's points (see the class
    description); default true. With a conic search region the guided pass is the search itself, whatever
    this setting.
  */
  void setGuidedSearch(bool enable) { m_guided = enable; }
  //! Whether the guided pass runs after the first one.
  bool getGuidedSearch() const { return m_guided; }
  /*!
    Ridge method: the guided pass searches within this many pixels (across the curve) of the conic fitted
    to the first pass's points; default 12 (the fit's extrapolation over a missing part of the ring is off
    by a few pixels; a wider band lets more distractors in). A conic search region uses its own margin.
    \exception vpLaserConicException::badValueError when not positive or above getMaxMargin().
  */
  void setGuidedMargin(double pixels);
  /*!
    The largest margin setGuidedMargin() and setSearchRegion() take: 10000 pixels. A margin wider than the
    image already searches whole image lines; beyond this one a margin is taken for a mistake (a value in
    other units, an uninitialised number).
  */
  static double getMaxMargin() { return 10000.0; }
  //! Margin of the guided pass, pixels.
  double getGuidedMargin() const { return m_guidedMargin; }
  /*!
    Ridge method: the guided pass measures a profile on every \e lines-th image row or column crossed by
    the curve; default 1 (one point per pixel of curve, as the first pass). Larger steps read less of the
    image and give fewer points (faster tracking, faster estimation).
    \exception vpLaserConicException::badValueError on 0 or above getMaxStep().
  */
  void setGuidedStep(unsigned int lines);
  //! Step of the guided pass, image lines.
  unsigned int getGuidedStep() const { return m_guidedStep; }
  /*!
    Ridge method, tracking (a conic search region, setSearchRegion(const vpMatrix &, double)): the guided
    pass that is then the whole search measures a profile on every \e lines-th image row or column crossed
    by the predicted curve; default 2. A profile averages three neighbouring lines, so with 2 every image
    line enters a profile, except along a stripe four times over its threshold, where a profile reads its
    own line alone (then one line in two); the points are at most 2 sqrt(2) pixels apart along the curve:
    half the points and the time of step 1 for the same coverage and accuracy on the rendered tracking
    cases.
    The guided pass after a first pass keeps its own step (setGuidedStep()): there it extrapolates a fit
    over the missing part of the ring, and its continuity rules are counted in profiles of one line.
    \exception vpLaserConicException::badValueError on 0 or above getMaxStep().
  */
  void setTrackingStep(unsigned int lines);
  //! Step of the guided pass along a conic search region, image lines.
  unsigned int getTrackingStep() const { return m_trackingStep; }
  /*!
    Ridge method: a profile of the guided pass holds a stripe when its matched-filter response exceeds
    this many times the response's noise, measured along that profile; default 3.5 (the continuity rule
    removes the rare noise peak that passes). No upper bound: a factor no profile reaches leaves the first
    pass's points alone. The noise is estimated from the differences of the profile's pixels, as for white
    sensor noise. A JPEG stream's noise is correlated over the codec's blocks: on the rendered faint rings
    at quality 90 the responses spread 1.9-2.7 times that estimate (1.0 uncompressed), so the default
    stands at about 1.5 of their real spread there, and the dim side's centres at 2-3 times the sensor
    noise come out 0.2-0.6 px RMS from the stripe (0.04 px uncompressed), about what such a frame holds: the
    profiles averaged along the true centre line over 80 px of arc put the stripe 0.25-0.62 px RMS from it
    there (0.07-0.15 px uncompressed). Uncompressed frames keep that side's colour; a larger factor finds less
    of it.
    \exception vpLaserConicException::badValueError when not positive and finite.
  */
  void setGuidedThresholdFactor(double factor);
  //! Threshold factor of the guided pass.
  double getGuidedThresholdFactor() const { return m_guidedFactor; }
  //! Points of the last detection found by the guided pass: the last ones of the list detect() returned.
  unsigned int getGuidedPointCount() const { return m_guidedCount; }

  /*!
    HSV method: hue band, a pixel is red when hue <= \e maxHueLow or hue >= \e minHueHigh (OpenCV scale
    0-179).
    \exception vpLaserConicException::badValueError when a bound is outside [0, 179].
  */
  void setHueRange(int maxHueLow, int minHueHigh);
  /*!
    HSV method: minimum saturation and value (0-255).
    \exception vpLaserConicException::badValueError when a bound is outside [0, 255].
  */
  void setMinSaturationValue(int minSaturation, int minValue);

  //! Detects the trace points of \e I (pixel coordinates, sub-pixel); empty for an empty image.
  std::vector<vpImagePoint> detect(const vpImage<vpRGBa> &I);
  /*!
    Diagnostic mask of the last detection, the size of the image (ridge method: 255 on the accepted stripe
    runs of the first pass, 170 on those of the guided pass, 100 on the rejected candidate runs, 0
    elsewhere; HSV method: 255 on the thresholded pixels). Drawn on the first call after a detection (the
    detection itself does not pay for it).
  */
  const vpImage<unsigned char> &getMask() const;
  //! Contrast threshold T used by the last ridge detection, grey levels.
  double getThreshold() const { return m_threshold; }
  //! Score noise estimated by the last ridge detection, grey levels.
  double getNoiseLevel() const { return m_noise; }

private:
  /*!
    Work buffers of the ridge detector, kept from frame to frame (no allocation once a frame of the size
    has been processed); a copy of the detector starts with buffers of its own, empty.
  */
  class VISP_EXPORT vpWorkspace
  {
  public:
    vpWorkspace();                         //!< empty buffers
    vpWorkspace(const vpWorkspace &other); //!< empty buffers, the last detection's crossings copied
    vpWorkspace &
    operator=(const vpWorkspace &other); //!< keeps its buffers, forgets its rasterised region, copies the crossings
    ~vpWorkspace();                      //!< frees the buffers
    vsp::laser_detector::RidgeWorkspace &get() { return *m_work; }             //!< the buffers
    const vsp::laser_detector::RidgeWorkspace &get() const { return *m_work; } //!< the buffers (read only)

  private:
    std::unique_ptr<vsp::laser_detector::RidgeWorkspace> m_work;
  };

  //! Rasterises the search region for an image of \e H x \e W pixels into the workspace (once per region and size).
  void rasteriseRegion(int H, int W);
  //! The first pass (over the search region of points, if any), then the guided pass if enabled; \e coverage:
  //! the share of the fitted ellipse's samples the guided pass covered (0 without an ellipse).
  std::vector<vpImagePoint> detectInTwoPasses(const vpImage<vpRGBa> &I, bool inRegion, double &coverage);
  //! The settings of the guided pass with the band half-width \e margin (pixels), the others from this detector's.
  vsp::laser_detector::GuidedSettings guidedSettings(double margin, unsigned int step) const;
  //! The guided pass along the conic search region; false when it found too few points (track lost).
  bool trackConic(const vpImage<vpRGBa> &I, std::vector<vpImagePoint> &points);
  //! Over the whole image: the ring located by a sample of rows, then measured by the guided pass along it;
  //! false when the sample makes no ellipse or the pass finds too little of it (then the whole search runs).
  bool locateFromRows(const vpImage<vpRGBa> &I, std::vector<vpImagePoint> &points);
  //! Over the whole image, after a search whose location is not trusted (its guided pass covered \e firstCoverage
  //! of its ellipse, 0 without one): the ellipse through chains shorter than the minimum segment, measured by
  //! the guided pass; false when it does not locate the ring better.
  bool locateFromShortChains(const vpImage<vpRGBa> &I, double firstCoverage, std::vector<vpImagePoint> &points);
  //! locateFromShortChains(), the first search's crossings and runs put back when it fails.
  bool retryWithShortChains(const vpImage<vpRGBa> &I, double firstCoverage, std::vector<vpImagePoint> &points);
  //! The settings of the first pass.
  vsp::laser_detector::RidgeSettings ridgeSettings() const;

  vpDetectionMethod m_method;
  double m_minContrast, m_noiseFactor, m_minSegmentLength;
  unsigned int m_maxStripeWidth, m_saturationLevel, m_step;
  vpInstructionSet m_instructions;
  int m_maxHueLow, m_minHueHigh, m_minSaturation, m_minValue;
  //! The search region's points (with m_regionIsConic, the conic's, sampled when the band is first searched;
  //! empty without either: the whole image)
  std::vector<vpImagePoint> m_region;
  double m_regionMargin;
  unsigned int m_regionGeneration; //!< changes with the region or the stripe width: the rasterisation is then redone
  mutable vpLaserConicImageMember<unsigned char> m_mask; //!< drawn from m_runs by getMask() when m_maskDirty
  mutable bool m_maskDirty;
  unsigned int m_height, m_width; //!< size of the last image
  double m_threshold, m_noise;
  bool m_guided; //!< the guided pass runs after the first
  double m_guidedMargin, m_guidedFactor;
  unsigned int m_guidedStep;
  unsigned int m_trackingStep; //!< step of the guided pass along a conic search region
  unsigned int m_guidedCount;  //!< points of the last detection from the guided pass
  int m_stripeWidth;           //!< observed stripe width of the last detection (0: none yet)
  bool m_regionIsConic;        //!< the search region is m_regionConic (else the points m_region)
  //! The predicted conic (pixels) when m_regionIsConic, else 3x3 zeros: never empty, since ViSP 3.5 copies an
  //! empty matrix from a null pointer (copying a detector would then be undefined).
  vpMatrix m_regionConic;
  vpWorkspace m_work; //!< score, block flags, candidates, crossings, chaining and rasterised region of the ridge method
  std::vector<vpLaserConicDetectorRun>
      m_runs; //!< rejected candidate runs of the last ridge detection (its crossings are in m_work)
};

#endif
