/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicSimulator.h
  \brief Simulated camera/circular-laser rig: exact and noisy trace points, outliers, rendered images.
*/
#ifndef VP_LASER_CONIC_SIMULATOR_H
#define VP_LASER_CONIC_SIMULATOR_H

#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicImageMember.h>

/*!
  \ingroup group_laser_conic
  \brief Simulates what the camera of a camera/circular-laser rig sees over a ground plane.

  The ground plane is the plane Z = 0 of a ground frame g whose pose in the camera frame is cMg
  (the camera must lie on the side Z > 0 or Z < 0, not on the plane). The laser is given as for
  vpLaserConicPose::setLaser(): full opening angle A and pose cMl of the laser frame, whose origin is
  the cone apex and whose +Z axis is the cone axis. A ray of the cone has the direction
  \f$ {}^c\mathbf{R}_l (\sin\frac{A}{2}\cos\gamma, \sin\frac{A}{2}\sin\gamma, \cos\frac{A}{2})^T \f$ from
  the apex; only the forward half-line lights the ground.

  Image points follow ViSP's conventions. Without distortion a camera point is projected with
  vpMeterPixelConversion. With perspectiveProjWithDistortion, the simulator's lens is the pixel-to-metre
  model of vpPixelMeterConversion, \f$ x = \frac{u - u_0}{p_x} (1 + k_{du} r_d^2) \f$ with
  \f$ r_d^2 = (\frac{u - u_0}{p_x})^2 + (\frac{v - v_0}{p_y})^2 \f$ (idem for y): a camera point is
  projected on the pixel that this model maps back onto it (Newton's method on the distorted radius, to
  1e-16), and render() casts, for each pixel, the ray that vpPixelMeterConversion gives. So the pixels of
  tracePoints() and of the rendered images convert exactly (to rounding) into the normalized coordinates of
  the true trace with the conversion the estimators use, and the laser module recovers the exact plane from
  them. The coefficient \f$ k_{ud} \f$ (metre to pixel) is not used; fitInverseDistortion() gives the
  \f$ k_{ud} \f$ that best inverts \f$ k_{du} \f$, as a calibration would estimate both.

  The ground is rendered at fixed ground coordinates (X, Y of the frame g), so that a sequence sees the
  same floor from frame to frame and a chessboard or texture placed with setGroundChessboard() or
  setGroundTexture() has known corner coordinates. render(I, settings) adds what real images of a laser
  ring show (vpLaserConicSimulator::vpRenderSettings): a dim or saturating stripe with bloom, a stripe that
  fades along the ring (distance and incidence fall-off) and whose light is scaled by the surface's
  reflectance, floors of several kinds with ambient light and a specular lamp reflection, red distractors
  and clutter, occluders, frames without laser, motion blur, sensor noise and JPEG compression. traceTruth()
  gives the ground truth of the rendered stripe: its centre line and its peak brightness over the noise.

  Errors are reported with vpLaserConicException (vpLaserConicException.h), a vpException.

  All random draws come from one generator seeded by setSeed() (default seed 0): the same sequence of
  calls with the same seed gives the same results.

  \code
  vpLaserConicSimulator sim;
  sim.setCamera(vpCameraParameters(1600, 1600, 800, 600), 1600, 1200);
  sim.setLaser(vpMath::rad(34), vpHomogeneousMatrix(0.1, 0, 0, 0, 0, 0));
  sim.setGroundPose(vpHomogeneousMatrix(0, 0, 1, vpMath::rad(10), 0, 0));
  sim.setSeed(42);
  std::vector<vpImagePoint> points = sim.addNoise(sim.tracePoints(500), 0.5);
  vpImage<vpRGBa> I;
  sim.render(I);
  \endcode
*/
class VISP_EXPORT vpLaserConicSimulator
{
public:
  //! Procedural floors, defined at ground coordinates (they depend on the seed only).
  enum vpFloorType {
    FLOOR_DARK_TILES,  //!< dark grey tiles (3 cm, grey 25-70) with a fine grain: the default
    FLOOR_BRIGHT_GREY, //!< plain bright grey concrete (V about 40-110 under ambient 1) with a soft mottling
    FLOOR_MOSAIC,      //!< colourful mosaic of warm-toned patches (orange, brown, ochre, brick, beige)
    FLOOR_WHITE_TILES  //!< white glossy tiles (grey 200-230) with darker grout lines
  };

  //! Kind of a red distractor lying on the ground.
  enum vpDistractorShape {
    DISTRACTOR_DISC,      //!< disc of diameter \e size
    DISTRACTOR_RECTANGLE, //!< axis-aligned (ground frame) square of side \e size
    DISTRACTOR_LINE       //!< segment from (x, y) to (x2, y2), \e size wide (a red cable, a painted line)
  };

  //! A coloured object lying on the ground (ground coordinates, metres).
  struct vpDistractor
  {
    vpDistractorShape shape = DISTRACTOR_DISC; //!< shape
    double x = 0.0;                            //!< centre (disc, square) or first end (line): x, metres
    double y = 0.0;                            //!< centre (disc, square) or first end (line): y, metres
    double x2 = 0.0;                           //!< second end of a line: x, metres
    double y2 = 0.0;                           //!< second end of a line: y, metres
    double size = 0.1;                         //!< diameter, side or line width, metres
    vpRGBa colour = vpRGBa(200, 25, 20, 255);  //!< albedo under ambient 1 (default: a laser-like red)

    //! A red disc of diameter \e size centred at (x, y).
    static vpDistractor disc(double x, double y, double size)
    {
      vpDistractor d;
      d.x = x;
      d.y = y;
      d.size = size;
      return d;
    }
    //! A red square of side \e size centred at (x, y), sides along the ground axes.
    static vpDistractor square(double x, double y, double size)
    {
      vpDistractor d = disc(x, y, size);
      d.shape = DISTRACTOR_RECTANGLE;
      return d;
    }
    //! A red line (a cable) from (x, y) to (x2, y2), \e width wide.
    static vpDistractor line(double x, double y, double x2, double y2, double width)
    {
      vpDistractor d = disc(x, y, width);
      d.shape = DISTRACTOR_LINE;
      d.x2 = x2;
      d.y2 = y2;
      return d;
    }
  };

  /*!
    What render() draws. The defaults give the historical image: dark tiles, a red stripe of 3 px FWHM
    peaking about 250 grey levels above the floor, blur 0.7 px, sensor noise 2 grey levels.
  */
  struct vpRenderSettings
  {
    vpFloorType floor = FLOOR_DARK_TILES; //!< procedural floor
    //! Seed of the floor and of the clutter (negative: the simulator's seed, setSeed()); a fixed value keeps
    //! the scene of a sequence while setSeed() changes the sensor noise from frame to frame.
    int sceneSeed = -1;
    double ambient = 1.0;    //!< multiplier of the floor (and distractor) brightness, >= 0
    double specular = 0.0;   //!< peak grey level of the lamp's specular reflection on the floor, >= 0
    double shininess = 60.0; //!< Phong exponent of that reflection (larger: smaller highlight), > 0
    double lampX = 0.3;      //!< lamp position in the ground frame: x, metres
    double lampY = 0.2;      //!< lamp position in the ground frame: y, metres
    double lampZ = 2.5;      //!< lamp height above the ground, metres

    bool laserOn = true;       //!< false renders a frame without laser (e.g. the laser is pulsed)
    double laserPower = 330.0; //!< red light added at the stripe centre, grey levels before clipping, >= 0
    double stripeWidth = 3.0;  //!< full width at half maximum of the stripe profile, pixels, > 0
    double whiteCore = 0.0;    //!< gain of the white light added where the red exceeds 255 (saturated core), >= 0
    double bloom = 0.0;        //!< amplitude of a wide halo around the stripe, relative to laserPower, >= 0
    double bloomWidth = 8.0;   //!< full width at half maximum of the halo, pixels, > 0
    /*!
      Exponent p of the stripe's fall-off with the distance d from the laser apex to the lit ground point:
      the light varies as \f$ d^{-p} \f$ (2: inverse square; 0, the default: no fall-off), >= 0.
    */
    double distanceFalloff = 0.0;
    //! true: the stripe is also weighted by the Lambert cosine of the incidence angle of the laser ray on the
    //! ground (grazing rays light less); false (default): no incidence weighting.
    bool lambertIncidence = false;
    /*!
      Fraction of the peak left on the dimmest part of the visible ring, in [0, 1). With 0 (the default) the
      stripe brightness along the ring is the fall-off of distanceFalloff and lambertIncidence, normalised so that
      the brightest visible part of the ring receives laserPower. Otherwise that normalised fall-off g, in (0, 1],
      is raised to the power k with \f$ g_{min}^k \f$ = stripeFarFraction over the visible ring (the image of the
      trace): the near side keeps laserPower, the far side gets this fraction of it, as a ring generator whose
      emission is not uniform and a dark room show (real photographs: 60-150 grey levels of red dominance near,
      14-30 far). It needs a fall-off to shape (distanceFalloff > 0 or lambertIncidence).
    */
    double stripeFarFraction = 0.0;
    /*!
      true: the laser light is scaled by the red reflectance of the surface it falls on (red albedo / 255: the
      floor, texture, chessboard squares, objects), as a camera sees it, laserPower being the light on a white
      (reflectance 1) surface: a near-white saturating core on white paper, a dark red stripe on black squares.
      false (default): the light is added whatever the surface.
    */
    bool reflectanceScaled = false;

    double blur = 0.7;             //!< optical blur, Gaussian standard deviation in pixels, >= 0
    double motionBlurLength = 0.0; //!< length of a linear motion blur, pixels (0: none), >= 0
    double motionBlurAngle = 0.0;  //!< direction of the motion blur in the image, radians from the u axis
    double noise = 2.0;            //!< sensor noise standard deviation, grey levels per channel, >= 0
    //! JPEG quality (1-100) of a compression and decompression of the rendered image (OpenCV's codec, as a
    //! camera that streams JPEG); 0 (default): none. Outside [0, 100]: badValueError.
    int jpegQuality = 0;

    std::vector<vpDistractor> distractors; //!< objects on the ground (drawn over the floor, under the laser)
    unsigned int clutter = 0;   //!< number of small red patches (1-4 cm), fixed on the ground (seed), see clutterRadius
    double clutterRadius = 1.0; //!< the clutter lies within this distance of the ground origin, metres, >= 0
    //! Image polygons (pixels) of dark objects in front of the ground: they hide the floor and the laser.
    std::vector<std::vector<vpImagePoint> > occluders;
    vpRGBa occluderColour = vpRGBa(35, 32, 30, 255); //!< colour of the occluders
  };

  /*!
    Ground truth of a rendered stripe at one cone ray (traceTruth()): where its centre line is and how bright
    the stripe is there, so that a test knows which part of the ring a detector can be asked to find.
  */
  struct vpTraceTruth
  {
    vpImagePoint point;       //!< image point of the exact (distorted) centre line of the stripe, pixels
    double gamma = 0.0;       //!< cone angle of the ray, radians
    double falloff = 1.0;     //!< brightness factor along the ring in (0, 1] (1 on the brightest visible part)
    double reflectance = 1.0; //!< red reflectance of the surface there (1 without reflectanceScaled)
    /*!
      Peak red dominance R - max(G, B) that the stripe adds to the background across the curve, grey levels:
      laserPower x falloff x reflectance x (1 - the laser's green leak) for the stripe and its bloom, times the
      peak loss of the optical blur (\f$ \sigma_s / \sqrt{\sigma_s^2 + \sigma_b^2} \f$ across a straight line),
      before the sensor's noise and clipping (a saturated stripe reads less; motion blur is not counted).
      0 when the laser is off or an occluder hides the point.
    */
    double peakDominance = 0.0;
    //! peakDominance over the sensor noise standard deviation (+inf without noise, 0 when the laser is off).
    double peakOverNoise = 0.0;
    /*!
      How far the stripe stands above the scene beside it, grey levels of red dominance, in the image render()
      draws without sensor noise and JPEG (measureProminence()): the highest dominance of the pixels within half
      the blurred stripe's width (at half maximum) of the centre point, less the higher of the two pixels 3.5
      blurred stripe sigmas away on either side across the curve. Near peakDominance on an even surface; below it, or negative, where
      the ring runs in a dark joint beside a brighter red tile: there the image has a step, not a ridge, however
      much red the stripe adds. 0 where peakDominance is 0; NaN until measured.
    */
    double prominence = std::numeric_limits<double>::quiet_NaN();
    //! prominence over the sensor noise standard deviation (+inf without noise when positive); NaN until measured.
    double prominenceOverNoise = std::numeric_limits<double>::quiet_NaN();
    /*!
      peakOverNoise times the share of the stripe's brightness that the settings' JPEG compression keeps there
      (measureCompression()): what the compressed image still holds of the stripe, in the same units. Equal to
      peakOverNoise without JPEG; NaN until measured.
    */
    double keptOverNoise = std::numeric_limits<double>::quiet_NaN();
  };

  //! Simulator with no camera, a 34 degree laser at the camera centre, ground 1 m in front, seed 0.
  vpLaserConicSimulator();

  /*!
    Camera intrinsics and image size (pixels).
    \exception vpLaserConicException::badCameraError as vpLaserConicPose::setCameraParameters(): on
    non-finite parameters (distortion coefficients included), non-positive focal lengths or a projection model
    other than the two perspective ones, or when the size is zero.
  */
  void setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height);
  /*!
    Laser: full opening angle (rad) and pose of the laser frame in the camera frame.
    \exception vpLaserConicException::badLaserError when the angle is outside (0, pi) or the pose is
    not a finite rigid transformation. An apex at the camera centre is rendered (vpLaserConicPose refuses it:
    its ground plane is unobservable).
  */
  void setLaser(double openingAngle, const vpHomogeneousMatrix &cMl);
  /*!
    Pose of the ground frame (ground plane Z = 0) in the camera frame.
    \exception vpLaserConicException::badValueError when the pose is not a finite rigid transformation
    or the camera centre lies on the ground plane.
  */
  void setGroundPose(const vpHomogeneousMatrix &cMg);
  //! Seed of every random draw; also restarts the random sequence.
  void setSeed(unsigned int seed);

  /*!
    Places a texture on the ground: texel (i, j) covers the ground square
    X in [x0 + j s, x0 + (j + 1) s], Y in [y0 + i s, y0 + (i + 1) s] with s = \e metresPerTexel
    (bilinear interpolation); the floor of the settings is seen around it. An empty image removes it.
    \exception vpLaserConicException::badValueError when \e metresPerTexel is not positive and finite.
  */
  void setGroundTexture(const vpImage<vpRGBa> &texture, double metresPerTexel, double x0 = 0.0, double y0 = 0.0);
  /*!
    Places a printed chessboard on the ground: \e squaresX by \e squaresY squares of side \e squareSize
    metres covering X in [0, squaresX s], Y in [0, squaresY s], the square at the origin black, on white
    paper extending one square beyond the board. Its inner corners are the ground points (k s, l s, 0),
    k = 1..squaresX-1, l = 1..squaresY-1, so cMg gives their camera coordinates. Rendered with 4 samples
    per pixel (anti-aliased edges). squaresX = 0 removes it.
    \exception vpLaserConicException::badValueError when \e squareSize is not positive and finite or a
    single count is zero.
  */
  void setGroundChessboard(unsigned int squaresX, unsigned int squaresY, double squareSize);
  /*!
    The camera \e cam with the \f$ k_{ud} \f$ of vpMeterPixelConversion that best inverts its
    \f$ k_{du} \f$ (the simulator's lens) over an image of \e width x \e height pixels (least squares
    on the radius), as a calibration would estimate both; a camera without distortion is returned as is.
  */
  static vpCameraParameters fitInverseDistortion(const vpCameraParameters &cam, unsigned int width,
                                                 unsigned int height);

  //! The ground plane in the camera frame, unit normal pointing from the plane towards the camera (the
  //! ground truth); its D coefficient is the altitude of the camera centre.
  vpPlane getGroundPlane() const;

  /*!
    \e n image points of the laser trace, sampled uniformly in the cone angle gamma (k 2 pi / n),
    exact (no image noise), keeping only those lit by the forward half of the cone, in front of the
    camera and inside the image; fewer than \e n points may therefore be returned.
    \param n : number of cone rays.
    \param roughness : standard deviation (metres) of a random offset of each ground point along the
    ground normal, to mimic a rough ground (0 for a plane).
    \exception vpLaserConicException when the camera is unset (badCameraError) or \e roughness is negative
    or not finite (badValueError).
  */
  std::vector<vpImagePoint> tracePoints(unsigned int n, double roughness = 0.0);
  /*!
    Adds independent Gaussian noise of standard deviation \e sigma pixels to each coordinate.
    \exception vpLaserConicException::badValueError when \e sigma is negative or not finite.
  */
  std::vector<vpImagePoint> addNoise(const std::vector<vpImagePoint> &points, double sigma);
  /*!
    Replaces round(ratio * size) randomly chosen points by outliers drawn uniformly in the image and
    shuffles the result.
    \param points : input points.
    \param ratio : fraction of outliers, in [0, 1].
    \param isOutlier : when not null, receives the flag of each returned point.
    \exception vpLaserConicException when \e ratio is outside [0, 1] (badValueError) or the camera is unset
    (badCameraError).
  */
  std::vector<vpImagePoint> addOutliers(const std::vector<vpImagePoint> &points, double ratio,
                                        std::vector<bool> *isOutlier = nullptr);

  /*!
    The ground truth of the stripe that render(I, \e settings) draws, at \e n cone rays sampled as in
    tracePoints() (k 2 pi / n, kept when lit, in front of the camera and inside the image): the centre line
    and the peak brightness over the noise there. With \e settings.noise = sigma, the part of the ring a
    detector should find when it finds a stripe at least 3 sigma strong is the points with peakOverNoise >= 3.
    \exception vpLaserConicException on an unset camera (badCameraError) or a setting out of its range
    (badValueError).
  */
  std::vector<vpTraceTruth> traceTruth(unsigned int n, const vpRenderSettings &settings);
  /*!
    Share of the ring's length where the rendered stripe is at least \e minOverNoise times the sensor noise
    (peakOverNoise of \e truth, samples of traceTruth() in their order) that has a point of \e points within
    \e radius pixels: the coverage a detector reaches on what it can be asked to find. Each sample stands for
    half of the chords to its neighbours (samples more than 4 px apart are not joined: the ring leaves the
    image there); 0 when no part of the ring is that strong.
  */
  static double stripeCoverage(const std::vector<vpTraceTruth> &truth, const std::vector<vpImagePoint> &points,
                               double minOverNoise = 3.0, double radius = 1.5);
  /*!
    Fills vpTraceTruth::prominence and prominenceOverNoise of \e truth, the traceTruth() of this simulator with
    the same \e settings: renders the scene once more without sensor noise and JPEG (on a copy: the random
    sequence of this simulator is left as it was) and reads the red dominance across the curve at each sample.
    \exception vpLaserConicException as traceTruth().
  */
  void measureProminence(std::vector<vpTraceTruth> &truth, const vpRenderSettings &settings) const;
  /*!
    stripeCoverage() over the samples where the stripe is also a ridge of the image: it stands at least
    \e minOverNoise times the sensor noise above the scene on both sides (prominenceOverNoise). The part of the
    ring a person sees as a line; what stripeCoverage() adds to it is where the stripe's red only fills a dark
    joint up to the tile beside it.
    \exception vpLaserConicException::badValueError when a sample's prominence was not measured
    (measureProminence()).
  */
  static double ridgeCoverage(const std::vector<vpTraceTruth> &truth, const std::vector<vpImagePoint> &points,
                              double minOverNoise = 3.0, double radius = 1.5);
  /*!
    Fills vpTraceTruth::keptOverNoise of \e truth, the traceTruth() of this simulator with the same \e settings,
    for the image that the next render() with \e settings draws (call it before that render(), or on a copy of
    the simulator made before it): renders that scene four times on copies of this simulator, so with the same
    random draws, with and without the laser, with and without the JPEG compression; at each sample, the
    brightness R + G + B that the laser adds at the centre line, summed over the samples within 4.5 px along
    the ring (the stretch a profile of nine lines averages), compressed over uncompressed, clamped to [0, 1],
    scales peakOverNoise. Brightness, not red dominance: JPEG stores the colour at half resolution and a faint
    stripe's colour is the first thing it drops, while a detector can still follow its brightness.
    \exception vpLaserConicException as traceTruth().
  */
  void measureCompression(std::vector<vpTraceTruth> &truth, const vpRenderSettings &settings) const;
  /*!
    stripeCoverage() over the samples where what the compressed image keeps of the stripe is at least
    \e minOverNoise times the sensor noise (keptOverNoise): the part of the ring that JPEG did not erase.
    \exception vpLaserConicException::badValueError when a sample's keptOverNoise was not measured
    (measureCompression()).
  */
  static double keptCoverage(const std::vector<vpTraceTruth> &truth, const std::vector<vpImagePoint> &points,
                             double minOverNoise = 3.0, double radius = 1.5);

  /*!
    Renders a colour image of the camera's view with the default vpRenderSettings but for the stripe
    width and the noise (the image of the earlier versions of the simulator).

    -# The ground: when \e texture is empty, the procedural floor (FLOOR_DARK_TILES, at ground coordinates,
       depending on the seed only) with the texture and chessboard of setGroundTexture() /
       setGroundChessboard(); otherwise \e texture stretched over a square of the ground that covers the
       camera's footprint (up to 100 altitudes wide when the horizon is in view), so that it is not
       attached to fixed ground coordinates from one pose to the next; what lies beyond is dark grey.
    -# The laser: red light added along the exact (distorted) image of the trace with a Gaussian profile
       across the curve whose full width at half maximum is \e stripeWidth pixels.
    -# Optics and sensor: a Gaussian blur of standard deviation 0.7 pixel, then Gaussian sensor noise
       of standard deviation \e noise grey levels on each channel (seeded).

    \param I : resized to the camera image size.
    \param texture : ground texture (may be empty).
    \param stripeWidth : full width at half maximum of the stripe, pixels, > 0.
    \param noise : sensor noise standard deviation, grey levels, >= 0.
    \exception vpLaserConicException on an unset camera (badCameraError), a stripe width that is not
    positive or a negative noise (badValueError).
  */
  void render(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture = vpImage<vpRGBa>(), double stripeWidth = 3.0,
              double noise = 2.0);
  /*!
    Renders a colour image with the given settings: ground (floor, texture and chessboard of
    setGroundTexture() / setGroundChessboard(), distractors, clutter) lit by the ambient light and the
    lamp, the laser stripe (optional) with its white core and bloom, occluders, optical and motion blur,
    sensor noise, 8-bit clipping. Pixels whose ray misses the ground (sky) are dark grey (20).
    \exception vpLaserConicException on an unset camera (badCameraError) or a setting out of its range
    (badValueError).
  */
  void render(vpImage<vpRGBa> &I, const vpRenderSettings &settings);

private:
  void checkCamera() const;
  //! Normalized undistorted coordinates of every pixel centre (inverse of the projection model), cached.
  void updateRayMap();
  //! Throws vpLaserConicException::badValueError when a render setting is out of its range.
  static void checkSettings(const vpRenderSettings &settings);
  //! Share of the ring's length, over the samples of \e truth that \e counts keeps, with a point of \e points
  //! within \e radius pixels (stripeCoverage(), ridgeCoverage()).
  static double coverageOf(const std::vector<vpTraceTruth> &truth, const std::vector<vpImagePoint> &points,
                           double radius, const std::function<bool(const vpTraceTruth &)> &counts);
  //! Renders the ground (floor, texture, chessboard, distractors, lamp) into a float RGB image; with
  //! \e reflectance not null, the red reflectance of each pixel's surface too.
  void renderGround(float *rgb, const vpRenderSettings &settings, const vpImage<vpRGBa> *stretchedTexture,
                    float *reflectance = nullptr);
  //! Albedo and glossiness of the ground point (X, Y) seen by pixel (i, j): floor, texture, chessboard, objects
  //! (i < 0: the chessboard sampled at the point, not anti-aliased over the pixel).
  void surfaceAlbedo(const vpRenderSettings &settings, uint32_t sceneSeed, const std::vector<vpDistractor> &objects,
                     double X, double Y, int i, int j, const double R[3][3], const double C[3], float albedo[3],
                     float &gloss) const;
  //! Anti-aliased chessboard grey of pixel (i, j) (4 sub-pixel rays; R, C: camera orientation and centre in g).
  float chessboardAlbedo(int i, int j, const double R[3][3], const double C[3]) const;
  //! Normalisation of the stripe's fall-off along the ring over its visible part (stripeFalloff()).
  struct vpFalloffModel
  {
    double maxRaw = 1.0;   //!< largest raw fall-off over the visible ring
    double exponent = 1.0; //!< power applied to the normalised fall-off (stripeFarFraction)
  };
  //! The fall-off normalisation of \e settings over the visible ring (identity without fall-off).
  vpFalloffModel falloffModel(const vpRenderSettings &settings) const;
  //! Brightness factor in (0, 1] of the stripe at cone angle gamma (1 without fall-off or when unlit).
  double stripeFalloff(const vpRenderSettings &settings, const vpFalloffModel &model, double gamma) const;
  //! Unnormalised fall-off at cone angle gamma (distance and incidence), 0 when the ray does not light the ground.
  double rawFalloff(const vpRenderSettings &settings, double gamma) const;
  //! Red reflectance in [0, 1] of the ground point (X, Y) of the ground frame (floor, texture, board, objects).
  float groundReflectance(const vpRenderSettings &settings, double X, double Y) const;
  //! Adds the laser stripe, its white core and bloom (light scaled by \e reflectance when not null).
  void renderLaser(float *rgb, const vpRenderSettings &settings, const float *reflectance) const;
  //! render() with, when not null, a texture stretched over the footprint (historical render(I, texture)).
  void renderImpl(vpImage<vpRGBa> &I, const vpRenderSettings &settings, const vpImage<vpRGBa> *stretchedTexture);
  //! Ground point (camera frame) hit by the cone ray of angle gamma; false when the forward ray misses the ground.
  bool groundPoint(double gamma, double P[3]) const;
  //! Projects a camera-frame point; false when it is not in front of the camera.
  bool project(const double P[3], double &u, double &v) const;
  //! Unit normal \e n (u, v) of the image trace at the cone ray of angle gamma; false where it is not seen.
  bool curveNormal(double gamma, double n[2]) const;
  /*!
    Squared distance of each pixel within \e radius of the exact image trace to that trace (+inf elsewhere);
    with \e falloff not null, the stripe's fall-off at the nearest point of the trace, per pixel.
  */
  void traceDistanceMap(float radius, std::vector<float> &dist2, const vpRenderSettings *settings = nullptr,
                        std::vector<float> *falloff = nullptr) const;
  //! Square of the ground (centre cx, cy and half side in ground coordinates) covering the camera's view.
  void groundFootprint(double &cx, double &cy, double &half) const;

  vpCameraParameters m_cam;
  unsigned int m_width, m_height;
  double m_openingAngle;
  vpHomogeneousMatrix m_cMl, m_cMg;
  unsigned int m_seed;
  std::mt19937 m_rng;
  vpLaserConicImageMember<vpRGBa> m_texture;    //!< texture of setGroundTexture()
  double m_texelSize, m_textureX0, m_textureY0; //!< its placement
  unsigned int m_boardX, m_boardY;              //!< chessboard squares (0: none)
  double m_boardSquare;                         //!< chessboard square size, metres
  std::vector<float> m_rayX, m_rayY;            //!< ray map of updateRayMap()
  vpCameraParameters m_rayCam;                  //!< camera of the ray map
  std::vector<unsigned char> m_rayValid;        //!< 1 where the model has an inverse at that pixel
};

#endif
