/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicPose.h
  \brief Altitude and attitude of a camera/circular-laser rig over a ground plane.
*/
#ifndef VP_LASER_CONIC_POSE_H
#define VP_LASER_CONIC_POSE_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/laser_conic/vpLaserConicException.h>

struct vpRansacOptions;
namespace vsp::laser_robust_fit
{
struct Settings;
struct Result;
} // namespace vsp::laser_robust_fit

/*!
  \ingroup group_laser_conic
  \brief Ground plane, altitude, roll and pitch from the image of a circular laser trace, modelled on vpPose.

  A laser rigidly attached to the camera projects a cone of light; its trace on the ground is a
  conic whose image is measured. From it the ground plane is recovered in the camera frame
  (Boutteau, Sturm, Vasseur, Demonceaux, "Circular laser/camera-based attitude and altitude
  estimation: minimal and robust solutions", JMIV 2018).

  \code
  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);
  estimator.setLaser(vpMath::rad(34), cMl);  // full opening angle, laser pose in the camera frame
  vpPlane cPlane;
  if (estimator.computePlane(points, vpLaserConicPose::GP3, cPlane))
    std::cout << estimator.getAltitude() << " m" << std::endl;
  \endcode

  Attitude convention: with \f$ \mathbf{g} \f$ the unit downward normal of the ground in the camera
  frame, \f$ \mathbf{g} = R_x(\mathrm{roll}) R_y(\mathrm{pitch})\,(0,0,1)^T \f$; both angles are zero
  when the optical axis is perpendicular to the ground.
*/
class VISP_EXPORT vpLaserConicPose
{
public:
  //! Estimation methods.
  typedef enum {
    PLANE_PAIR, //!< least-squares conic on all points, then the plane pair (Sec. 4, 5.1); no outlier rejection.
    PP5, //!< 5-point RANSAC on the image conic, plane pair on the best conic (Sec. 5.1); see setRansacMaxTrials() among many outliers.
    PP3, //!< 3-point RANSAC with the two epipolar tangency constraints (Sec. 5.2).
    GP3  //!< 3-point RANSAC directly on the ground plane from ray/cone intersections (Sec. 5.3).
  } vpLaserConicMethod;

  //! Outcome of the last computePlane() (getStatusMessage() says it in words).
  typedef enum {
    STATUS_NOT_COMPUTED,     //!< computePlane() not called yet
    STATUS_OK,               //!< a plane was found
    STATUS_COLLINEAR_POINTS, //!< all points lie on one line
    STATUS_NOT_AN_ELLIPSE,   //!< the least-squares conic of the points (or of the trace) is not an ellipse
    STATUS_NO_CONSENSUS, //!< no hypothesis gathers enough inliers, or no more than clutter would, or (PP5) the calibrated cone's consensus refutes it
    STATUS_CAMERA_INSIDE_CONE, //!< PP3 only: no epipolar tangent, the camera centre lies inside the laser cone
    STATUS_NO_PLANE_PAIR,      //!< the plane pair of the conic has no ground plane
    STATUS_PLANE_NOT_FINITE,   //!< the estimated plane is not finite
    STATUS_PLANE_BEHIND, //!< the plane is behind the system, or within a tenth of the baseline of the camera (its trace cannot be seen there)
    STATUS_SHORT_ARC,            //!< the trace found covers too short an arc (setArcCoverageThreshold())
    STATUS_CALIBRATION_MISMATCH, //!< the calibration cannot explain the trace (setCalibrationCheck(), getSuspectedMistake())
    STATUS_WEAK_TRACE, //!< the trace fixes the plane far less than the whole ring would (setMaxAltitudeDilution(), setMaxAttitudeUncertainty())
    STATUS_NO_PARALLAX //!< the trace hardly moves with the plane: its attitude is too uncertain (setMaxAttitudeUncertainty())
  } vpLaserConicStatus;

  /*!
    A standard calibration mistake that explains a trace the given calibration does not
    (STATUS_CALIBRATION_MISMATCH): the estimate is run again under each alternative, and the one whose
    constrained fit explains the trace best is named (getMistakeMessage() says it in words).
  */
  typedef enum {
    MISTAKE_UNKNOWN,            //!< no mismatch, or none of the alternatives explains the trace
    MISTAKE_HALF_OPENING_ANGLE, //!< the trace fits twice the opening angle: the half angle was given for the full one
    MISTAKE_DOUBLED_OPENING_ANGLE, //!< the trace fits half the opening angle: twice the full angle was given
    MISTAKE_INVERSE_LASER_POSE,    //!< the trace fits the inverse laser pose: lMc was given for cMl
    MISTAKE_SWAPPED_UV,            //!< the trace fits with u and v exchanged: the image points are (v, u)
    MISTAKE_CAMERA_RESOLUTION      //!< the trace fits intrinsics scaled by 2 or 1/2: intrinsics of another resolution
  } vpLaserConicMistake;

  /*!
    Final fit on the trace, after the RANSAC search (setFinalFit()).
    - FINAL_FIT_FREE: least-squares conic on the trace (5 degrees of freedom: it ignores the
      tangency of the image conic to the two epipolar lines of the rig), then its plane pair. This is
      what PP5 does, and what the paper's PP3 does after its 3-point search: PP3 with this final fit is
      PP5 on PP3's inliers, it optimises the algebraic conic residual, not the rig's constraints.
    - FINAL_FIT_CONSTRAINED: the plane refined on the trace (3 degrees of freedom, Sampson distances
      to the trace it predicts, Huber IRLS): the conic keeps its tangency to the epipolar lines.
    - FINAL_FIT_SELECT: the constrained fit, unless the data reject it against the free fit (F-test
      of the two extra degrees of freedom at 1 %): then the calibration cannot explain the trace
      (getCalibrationHealth()), the constrained fit absorbs the calibration error into the plane, and
      the free fit is used.
    - FINAL_FIT_DEFAULT: FREE for PLANE_PAIR and PP5, SELECT for PP3 and GP3.
  */
  typedef enum {
    FINAL_FIT_DEFAULT,     //!< FREE for PLANE_PAIR and PP5, SELECT for PP3 and GP3
    FINAL_FIT_FREE,        //!< least-squares conic (5 DOF) on the trace, then its plane pair
    FINAL_FIT_CONSTRAINED, //!< plane refined on the trace (3 DOF, tangency to the epipolar lines kept)
    FINAL_FIT_SELECT       //!< CONSTRAINED unless an F-test at 1 % rejects it against FREE
  } vpLaserConicFinalFit;

  //! Estimator with the default settings (2 px threshold, 1000 samples, p = 0.99, scale-adaptive final stage).
  vpLaserConicPose();

  /*!
    Camera intrinsics, with or without radial distortion. Image points are converted to normalized
    (undistorted) coordinates with vpPixelMeterConversion, i.e. with the distorted-to-undistorted
    coefficient kdu when the model is vpCameraParameters::perspectiveProjWithDistortion (the
    conversion vpLaserConicCalibration uses).
    \exception vpLaserConicException::badCameraError on non-finite parameters, non-positive focal
    lengths or a projection model other than the two perspective ones.
  */
  void setCameraParameters(const vpCameraParameters &cam);
  /*!
    Laser cone: \e openingAngle is the full opening angle in radians, in (0, pi); \e cMl the pose of
    the laser frame in the camera frame (apex at its origin, cone axis along +Z).
    \exception vpLaserConicException::badLaserError on a bad angle, a non-finite pose or an apex at
    the camera centre.
  */
  void setLaser(double openingAngle, const vpHomogeneousMatrix &cMl);

  /*!
    RANSAC inlier threshold, in pixels; default 2. Residuals are measured in the undistorted image:
    the geometric (Sampson) distance of a point to the conic in normalized coordinates, multiplied
    by the mean focal length (px + py) / 2. Without distortion this is the distance in pixels; with
    distortion it is the distance in the undistorted image, which differs from the distorted one by
    the local magnification of the distortion, 1 + kdu r^2 to first order.
  */
  void setRansacThreshold(double pixels);
  /*!
    Maximum number of RANSAC samples; default 1000. PP5 draws five points a sample: at 15 % of inliers, 99 %
    confidence needs about 60000 samples, and a thousand may all hold clutter. Its best conic then runs through
    part of the trace and clutter besides, and its plane pair lay up to 1.4 m off (a ring of 360 points among
    2000 random ones, 18 of 30 scenes). So when PP5 stops short of the samples its consensus's inlier ratio needs,
    the calibrated cone's three-point consensus (GP3) is sought too: if it finds a trace that the calibration
    explains and PP5's conic misses, the status is STATUS_NO_CONSENSUS, the details giving both consensuses.
  */
  void setRansacMaxTrials(int trials);
  //! Confidence of the adaptive stop (eq. 28); default 0.99.
  void setRansacProbability(double p);
  //! Seed of the RANSAC sampler; default 0.
  void setRansacSeed(unsigned int seed);
  /*!
    Smallest number of inliers a consensus needs (default 0: getMinimumPointCount(), 5 for every method);
    fewer gives STATUS_NO_CONSENSUS. Whatever this number, a consensus among points off it that holds no more of
    them than points spread at random over the same area would (the expected number of such conics over 0.01)
    is no trace: STATUS_NO_CONSENSUS, the details giving that number (PP5, PP3, GP3; PLANE_PAIR has no consensus).
  */
  void setRansacNbInliersToReachConsensus(unsigned int n) { m_nbInliersToReachConsensus = n; }
  /*!
    Scale-adaptive final stage (default true). The RANSAC threshold separates gross outliers; then
    the trace is collected around the least-squares conic of the consensus at max(threshold, 3 sigma),
    sigma being the residual scale of the consensus (MAD, pixels), repeatedly while it grows, and the
    final fit (setFinalFit()) runs on that trace. Unlike a fixed threshold around the model, this keeps
    the whole trace when the calibration is imperfect. false: the RANSAC inliers and a plain
    least-squares final fit.
  */
  void setScaleAdaptive(bool enable) { m_scaleAdaptive = enable; }
  /*!
    Smallest arc of the trace, in radians around the fitted ellipse (its centre, in the frame where it
    is a circle), a consensus must cover (default pi/2; 0 disables the test): a short arc leaves the
    tilt weakly constrained. Fewer gives STATUS_SHORT_ARC.
    \exception vpLaserConicException::badValueError outside [0, 2 pi].
  */
  void setArcCoverageThreshold(double radians);
  /*!
    Largest dilution of the altitude an estimate may have (default 5; 0 disables the test): how many times
    its standard deviation (first order, from the trace's points and scatter about the final fit) exceeds
    the one as many points spread over the plane's whole ring would give at the same scatter. It measures
    the trace's geometry alone, whatever the noise, the number of points and the distance. Beyond it the
    status is STATUS_WEAK_TRACE: the points found do not fix the plane, whatever plane they gave. The arc
    test (setArcCoverageThreshold()) reads the arc around the free conic of the trace, which on a short
    noisy arc curves with the noise: on a rendered faint ring 87 points of its top, 6 % of it, read as 180
    degrees and gave a plane 1.75 m off. Measured: 25 degrees of a ring at 0.5 px, 59 of 200 GP3 estimates
    accepted over 5 % off without the test, 7 with it; on 13 renderings of the hard sequence
    (make-laser-sequence --hard: the shipped seed and seeds 1-12, the latter at the program's default JPEG
    quality 60, harder than the shipped 80; 692 frames with a trace) the test refuses
    6 more GP3 estimates, 5 of them 0.38-1.75 m off and one 19 mm off (118 points), and leaves 4 over 10 cm
    (three pieces of a curve of the floor taken for the trace, 0.34-0.91 m off, and a red distractor,
    0.14 m); the shipped sequence's estimates are unchanged, as are the random scenes of the tests (100
    points, whole rings, 0.5-1 px). The dilution is that of the constrained fit's three parameters
    (computed on at most 48 points of the trace and as many of the whole ring: a few microseconds).
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setMaxAltitudeDilution(double factor);
  //! The limit set with setMaxAltitudeDilution().
  double getMaxAltitudeDilution() const { return m_maxAltitudeDilution; }
  /*!
    Largest standard deviation of the attitude an estimate may have, in radians (default 5 degrees; 0
    disables the test): first order, in the worst direction of tilt, of the rig-constrained plane (3
    parameters) through the trace's points, each taken as uncertain by its scatter about the free conic but
    by no less than half a pixel (the detector's regularised centres scatter by hundredths of a pixel while
    they lie tenths from the true line, and through JPEG whole stretches of the ring move together). The
    free conic of PP5 and PLANE_PAIR is less certain than that (getCovarianceMatrix() gives its own).
    Beyond it the status is STATUS_NO_PARALLAX, or STATUS_WEAK_TRACE when as many points spread over the whole
    ring would stay within it (a short arc, not the parallax, leaves the attitude uncertain). The plane is seen through the parallax
    between the camera and the laser's apex: the ring moves by about focal x baseline / altitude pixels
    between this ground and one at infinity. When that is a few pixels (an apex next to the lens, a baseline
    given in the wrong unit, a ground far beyond the rig's range), the trace hardly moves with the plane and
    planes tilted by tens of degrees fit it as well as the true one. Measured at 0.5 px on 500 points of the
    whole ring (focal 800 px, 20 grounds tilted up to 10 degrees): a 1 mm baseline at 1 m gave attitudes up to
    34 degrees off with a standard deviation of 11-15 degrees, 2 mm 17 degrees off (6-8), 1 cm at 3 m
    10 degrees off (3.8-4.7), 3 cm at 1 m 1 degree off (0.4-0.5). Through the detector (640 x 480 frames,
    JPEG 60): 1 mm at 1 m 10-15 degrees off, read as 8.6 degrees uncertain (rms over 20 frames); 2 mm 3.6
    degrees off, 4.4 uncertain; 3 cm 0.56 off, 0.28 uncertain. Computed with the altitude's dilution
    (setMaxAltitudeDilution()), which is tested first.
    \exception vpLaserConicException::badValueError when negative or not finite.
  */
  void setMaxAttitudeUncertainty(double radians);
  //! The limit set with setMaxAttitudeUncertainty() (radians).
  double getMaxAttitudeUncertainty() const { return m_maxAttitudeUncertainty; }
  /*!
    Calibration check of each estimate (default true). The constrained fit (the trace a plane
    predicts through the rig's calibration, 3 DOF) and the free conic fit (5 DOF) run on the same
    trace; with a right calibration the misfit the constraint adds, sqrt(rms_c^2 - rms_f^2) (pixels),
    is a small fraction of the noise (about 0.07 sigma for 1000 points at a 1e-6 false-alarm rate; at
    most 0.3 sigma on the shipped image sequences, where the detector adds its bias); an imperfect
    calibration, which the estimators tolerate, adds more (intrinsics off by 5 px: 24 sigma at most
    at 0.5 px noise). A misfit above 30 times the noise scale (max(getResidualScale(), getFreeRms()))
    and above 3 px is refused with STATUS_CALIBRATION_MISMATCH: the usual mistakes (half opening angle,
    lMc for cMl, u and v swapped, intrinsics of another camera or resolution) leave tens of pixels, and
    the free fit would then give a confidently wrong plane. A misfit above one noise scale is refused
    too when a standard mistake explains the trace with less than half of it (lMc for cMl on a
    fading ring: 14 px at 0.6 px noise, within the tolerance). The standard mistakes are tried
    (getSuspectedMistake()). false: no check,
    the behaviour of FINAL_FIT_SELECT alone (the free fit is used when the constrained one is rejected).
  */
  void setCalibrationCheck(bool enable) { m_calibrationCheck = enable; }
  //! Final fit on the trace (see vpLaserConicFinalFit); default FINAL_FIT_DEFAULT.
  void setFinalFit(vpLaserConicFinalFit fit) { m_finalFit = fit; }
  /*!
    Compute the covariance of the estimate (default false): getCovarianceMatrix() and
    getPlaneCovarianceMatrix(), first order, from the Jacobian of the final fit's residuals and their
    scale (RMS residual with the fit's degrees of freedom removed).
  */
  void setCovarianceComputation(bool enable) { m_computeCovariance = enable; }
  /*!
    Variance scale of getCovarianceMatrix() and getPlaneCovarianceMatrix() (default 1): an error model
    of the detector. The first-order covariance takes the trace points' errors as independent; the
    points of a detected stripe are not (blur, JPEG blocks, the stripe-width and sampling errors of the
    ridge are shared by neighbours along the trace), and hundreds of them in a frame then average far
    less than independent errors would; its guided pass moreover regularises its centres along the curve
    over 80 px on each side, which shrinks the residuals the scale is measured from. On frames rendered by
    vpLaserConicSimulator and read back as JPEG, found by vpLaserConicDetector at its default settings
    (testLaserConicCovarianceRendered, seeds 101-104), the mean NEES of (altitude, roll, pitch) is 88-105
    instead of 3 (median 72-86 instead of 2.37); recommendedDetectorInflation(), 32, brings it to 2.7-3.3
    (median 2.3-2.7). A frame
    whose ring the detector's sample of rows cannot locate goes through its full search, whose centres are
    mostly not regularised: its covariance is then about 4 times too large (conservative). It is too small,
    on the other hand, for rings that fade along their length through strong JPEG compression (the hard
    sequence rendered with other seeds, `make-laser-sequence --hard --seed N`, at its default quality 60):
    there the dim side's centres are off by a fraction of a pixel along whole stretches of the ring that keep
    one phase to the 16 px blocks of the compressed colour, an error hundreds of points share and the
    residuals do not show (seed 4, frame 51: the whole ring found, the plane 65 mm off, `vsp-laser-altimeter
    --truth`). `vsp-laser-altimeter --truth` prints the median NEES of a sequence with a ground truth (and
    `--max-nees` bounds it): the covariance holds the trace's noise, not a calibration's error. Keep 1 for
    independent point noise (e.g. points from another front-end).
    \exception vpLaserConicException::badValueError unless finite and > 0.
  */
  void setCovarianceInflation(double varianceScale);
  //! Variance scale set with setCovarianceInflation().
  double getCovarianceInflation() const { return m_covarianceInflation; }
  //! The variance scale measured for vpLaserConicDetector's traces (see setCovarianceInflation()).
  static double recommendedDetectorInflation() { return 32.0; }

  /*!
    Refit the best model on its inliers (default true), during the RANSAC loop (kept when it scores
    better) and, without the scale-adaptive stage (setScaleAdaptive(false)), after it (kept unless
    it loses more than a tenth of the inliers; refitted again, a few rounds at most, while it gathers
    more inliers): PP5 and PP3 refit a least-squares ellipse,
    GP3 refines the plane geometrically (refinePlane(), 3 degrees of freedom, Sampson distances to
    the predicted trace; inside the loop on at most 64 evenly spread inliers, again on the consensus
    set of a refit that gathers more inliers, 3 refits at most).
  */
  void setLocalOptimisation(bool enable);

  /*!
    Estimates the ground plane from image points (pixels) with the given method.
    \param points : image points (pixels) of the laser trace; every method but PLANE_PAIR rejects outliers.
    \param method : PLANE_PAIR, PP5, PP3 or GP3.
    \param cPlane : the ground plane in the camera frame, unit normal pointing from the plane towards the camera.
    \return false, with getStatus() telling why, when no plane was found; cPlane is then untouched.
    The reasons: all points collinear; the least-squares conic is not an ellipse; no consensus (no
    hypothesis with enough inliers, no more than clutter would give, or for PP5 one the calibrated cone's
    refutes, see setRansacMaxTrials()); a trace covering too short an arc (setArcCoverageThreshold());
    one that fixes the plane too weakly (setMaxAltitudeDilution(), setMaxAttitudeUncertainty()); a
    calibration that cannot explain the trace (setCalibrationCheck());
    the camera centre inside the laser cone, where no
    epipolar tangent exists (PP3 only); no plane of the plane pair has both optical centres on its side;
    the plane is behind the system (the inliers' rays do not meet it ahead of the camera on the lit
    nappe of the laser cone).
    \exception vpLaserConicException when the camera or laser is unset, too few points are given for
    the method, or a point is not finite.
  */
  bool computePlane(const std::vector<vpImagePoint> &points, vpLaserConicMethod method, vpPlane &cPlane);

  //! Altitude of the camera centre over the last plane, in metres; NaN when the last computePlane() failed.
  double getAltitude() const { return m_altitude; }
  //! Roll of the last estimate, in radians (see the class convention); NaN when it failed.
  double getRoll() const { return m_roll; }
  //! Pitch of the last estimate, in radians (see the class convention); NaN when it failed.
  double getPitch() const { return m_pitch; }
  /*!
    Indices of the inliers (the points of the trace) of the last estimate (all points for PLANE_PAIR); after
    STATUS_CALIBRATION_MISMATCH, those of the refused estimate; empty after any other failure.
  */
  std::vector<unsigned int> getRansacInlierIndex() const { return m_inliers; }
  //! The inlier points of the last estimate (pixels, as given), as getRansacInlierIndex().
  std::vector<vpImagePoint> getRansacInliers() const;
  //! Number of inliers of the last estimate, as getRansacInlierIndex().
  unsigned int getRansacNbInliers() const { return static_cast<unsigned int>(m_inliers.size()); }
  //! \deprecated Use getRansacInlierIndex().
  std::vector<unsigned int> getInliers() const { return m_inliers; }
  //! Number of RANSAC samples drawn by the last estimate.
  int getRansacTrials() const { return m_trials; }

  /*!
    Covariance (3x3) of (altitude [m], roll [rad], pitch [rad]) of the last estimate, in that order,
    computed with setCovarianceComputation(true), as vpPoseGravity::getCovarianceMatrix(). First order:
    sigma^2 (J^T J)^-1 of the final fit (3 plane parameters for a constrained fit; for a free fit the
    covariance of the 5 conic parameters propagated through the plane pair), sigma^2 the residual
    variance of the fit. NaN entries when it cannot be computed (e.g. a plane pair without a derivative
    at the estimate).
    \exception vpLaserConicException::notComputedError when the last estimate computed no covariance
    (not requested, or computePlane() failed).
  */
  vpMatrix getCovarianceMatrix() const;
  /*! Covariance (4x4) of the plane (a, b, c, d) of the last estimate (unit normal), as getCovarianceMatrix().
      \exception vpLaserConicException::notComputedError as getCovarianceMatrix(). */
  vpMatrix getPlaneCovarianceMatrix() const;

  /*!
    Calibration-health figure of the last estimate: RMS residual (pixels) of the constrained fit (the
    trace a plane predicts, 3 DOF) over that of a free conic fit (5 DOF) on the same inliers. Both are
    the noise level, and the ratio near 1, when the rig is well calibrated; a calibration error leaves
    the free fit at the noise level but not the constrained one (e.g. 0.5 px noise: ratio ~1.0 exact,
    several with intrinsics off by 5 px). NaN when no constrained fit could be made, and when the last
    computePlane() failed before its final fit (refused as a calibration mismatch after that fit, it is the
    refused estimate's).
  */
  double getCalibrationHealth() const;
  //! RMS residual (pixels) of the constrained fit on the inliers of the last estimate.
  double getConstrainedRms() const { return m_rmsConstrained; }
  //! RMS residual (pixels) of the free conic fit on the inliers of the last estimate.
  double getFreeRms() const { return m_rmsFree; }
  //! Residual scale (pixels, MAD) of the free conic fit on the trace of the last estimate.
  double getResidualScale() const { return m_sigma; }
  //! Arc of the trace covered by the inliers of the last estimate (radians around the ellipse).
  double getArcCoverage() const { return m_coverage; }
  //! True when the last plane comes from the constrained fit (see vpLaserConicFinalFit).
  bool isConstrainedFit() const { return m_constrainedChosen; }
  /*! Image conic (pixel coordinates, x^T C x = 0 with x = (u, v, 1)) of the last estimate, for display:
      the fitted ellipse for PLANE_PAIR, PP5 and PP3, the image of the trace on the estimated plane for GP3.
      With a distorted camera it is the conic in the undistorted pixel image (x = K x_n). The zero matrix
      (no conic) when the last computePlane() failed or none was made. */
  vpMatrix getImageConic() const { return m_conic; }
  //! Outcome of the last computePlane().
  vpLaserConicStatus getStatus() const { return m_status; }
  //! What a status means, in words.
  static std::string getStatusMessage(vpLaserConicStatus status);
  /*!
    The name of a method as its enumerator spells it: "PLANE_PAIR", "PP5", "PP3" or "GP3" ("unknown" for
    a value outside the enumeration), as the error messages of computePlane() name it.
  */
  static std::string getMethodName(vpLaserConicMethod method);
  /*!
    The fewest points computePlane() takes for a method: 5 for every method. PP3 and GP3 draw 3 points per
    RANSAC sample, but every method's final fit starts from the free conic of the trace (5 parameters): with 3
    or 4 points none could succeed.
  */
  static unsigned int getMinimumPointCount(vpLaserConicMethod method);
  /*!
    After STATUS_CALIBRATION_MISMATCH, the standard mistake that explains the trace (MISTAKE_UNKNOWN
    when none does, or after any other status). getCalibrationHealth(), getConstrainedRms(), getFreeRms()
    and getRansacNbInliers() then give the figures of the refused estimate (vpLaserConicDriftMonitor reads
    them).
  */
  vpLaserConicMistake getSuspectedMistake() const { return m_mistake; }
  //! What a suspected mistake means, in words, with the setting to check.
  static std::string getMistakeMessage(vpLaserConicMistake mistake);
  /*!
    \deprecated Use getStatus() and getStatusMessage(). Why the last computePlane() returned false
    (the status message, with details; empty after a success).
  */
  std::string getFailureReason() const { return m_failure; }

  //! Camera parameters set with setCameraParameters().
  vpCameraParameters getCameraParameters() const { return m_cam; }

  /*!
    Displays an estimate with vpDisplay (the image must be shown in a window): the detected \e points
    (those given to computePlane()) as crosses, inliers green and outliers red, the fitted conic in
    yellow (through the camera model, distortion included) and an altitude / roll / pitch caption
    (the status message when computePlane() failed). Call vpDisplay::flush() afterwards.
  */
  static void display(const vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                      const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  //! display() on a colour image.
  static void display(const vpImage<vpRGBa> &I, const vpLaserConicPose &estimator,
                      const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  /*!
    Draws the same overlay as display() into the pixels of \e I with vpImageDraw (no window needed:
    headless overlays, files). In a gray image inliers, conic and caption are white and outliers gray.
  */
  static void draw(vpImage<unsigned char> &I, const vpLaserConicPose &estimator,
                   const std::vector<vpImagePoint> &points, unsigned int thickness = 1);
  //! draw() on a colour image (inliers green, outliers red, conic yellow).
  static void draw(vpImage<vpRGBa> &I, const vpLaserConicPose &estimator, const std::vector<vpImagePoint> &points,
                   unsigned int thickness = 1);
  /*!
    Draws a trace without an estimator (e.g. results kept from several estimates): the \e points as
    crosses, those of \e inlierIndex green and the others red, and \e imageConic (3x3, the undistorted
    pixel image of \e cam, as getImageConic() gives it; empty for none) in yellow through the camera
    model, so that it lies on the distorted trace. Any conic is drawn: an ellipse, or the part near the
    image of a hyperbola or parabola (the trace with the horizon in view). No caption.
  */
  static void draw(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                   const vpCameraParameters &cam, unsigned int thickness = 1);
  //! The trace draw() above on a gray image: inliers and conic white, outliers gray.
  static void draw(vpImage<unsigned char> &I, const std::vector<vpImagePoint> &points,
                   const std::vector<unsigned int> &inlierIndex, const vpMatrix &imageConic,
                   const vpCameraParameters &cam, unsigned int thickness = 1);

  /*! Altitude, roll and pitch of a plane given in the camera frame (normal towards the camera).
      \exception vpLaserConicException::badValueError on a zero normal. */
  static void computeAltitudeRollPitch(const vpPlane &cPlane, double &altitude, double &roll, double &pitch);

private:
  vpCameraParameters m_cam;
  bool m_hasCam, m_hasLaser;
  double m_openingAngle;
  vpHomogeneousMatrix m_cMl;
  double m_threshold;
  int m_maxTrials;
  double m_probability;
  unsigned int m_seed;
  bool m_localOptimisation;
  double m_altitude, m_roll, m_pitch;
  std::vector<unsigned int> m_inliers;
  int m_trials;
  vpMatrix m_conic;
  std::string m_failure;
  vpLaserConicStatus m_status;
  unsigned int m_nbInliersToReachConsensus;
  bool m_scaleAdaptive;
  double m_minCoverage;
  double m_maxAltitudeDilution;
  double m_maxAttitudeUncertainty; //!< see setMaxAttitudeUncertainty()
  vpLaserConicFinalFit m_finalFit;
  bool m_computeCovariance;
  vpMatrix m_covariance, m_planeCovariance;
  double m_rmsConstrained, m_rmsFree, m_sigma, m_coverage;
  bool m_fitted = false; //!< the last computePlane() reached its final fit (the figures above are its)
  bool m_constrainedChosen;
  std::vector<vpImagePoint> m_points;
  bool m_calibrationCheck;
  vpLaserConicMistake m_mistake;
  double m_covarianceInflation = 1.0; //!< setCovarianceInflation()

  //! Records a failure (status and message with \e details) and returns false.
  bool fail(vpLaserConicStatus status, const std::string &details = std::string());
  //! The details of STATUS_NO_PARALLAX: the attitude's uncertainty, and the baseline, altitude and parallax.
  std::string parallaxDetails(const vsp::laser_robust_fit::Result &result) const;
  //! The details of STATUS_WEAK_TRACE: the altitude's dilution, or the attitude's uncertainty against the whole ring's.
  std::string weakTraceDetails(const vsp::laser_robust_fit::Result &result) const;
  //! The exceptions of computePlane(): estimator not configured, unknown method, too few points.
  void checkInput(const std::vector<vpImagePoint> &points, vpLaserConicMethod method) const;
  //! Clears the previous estimate; \e points become those of the new one.
  void resetEstimate(const std::vector<vpImagePoint> &points);
  //! RANSAC settings of the estimator, the threshold converted to normalized units with \e focal (pixels).
  vpRansacOptions ransacOptions(double focal) const;
  //! Settings of the final fit (laser_robust_fit.h) of \e method.
  vsp::laser_robust_fit::Settings finalFitSettings(vpLaserConicMethod method, double focal) const;
  //! STATUS_CALIBRATION_MISMATCH naming \e mistake (the alternative left \e alternativeMisfit pixels).
  bool failCalibration(vpLaserConicMistake mistake, const vsp::laser_robust_fit::Result &result,
                       double alternativeMisfit);
  /*!
    The calibration check of a final fit (setCalibrationCheck()): false, with
    STATUS_CALIBRATION_MISMATCH, when the misfit is beyond the tolerance, or beyond the noise with a
    standard mistake explaining the trace markedly better.
  */
  bool checkCalibration(const std::vector<vpImagePoint> &points, vpLaserConicMethod method,
                        const vsp::laser_robust_fit::Result &result);
  /*!
    A failure of the given calibration (no consensus, no plane, short arc, plane behind): reported as
    STATUS_CALIBRATION_MISMATCH when a standard mistake explains the trace, as \e status otherwise.
  */
  bool failOrMismatch(vpLaserConicStatus status, const std::string &details, const std::vector<vpImagePoint> &points,
                      vpLaserConicMethod method);
  /*!
    The standard mistake under which \e method explains \e points (setCalibrationCheck()); \e misfit
    receives its misfit. \e strict: only an alternative whose trace has \e minTrace points at least
    and whose misfit is within the noise (as a right calibration's) counts.
  */
  vpLaserConicMistake suspectedMistake(const std::vector<vpImagePoint> &points, vpLaserConicMethod method,
                                       double *misfit = nullptr, bool strict = false, size_t minTrace = 0) const;
  //! Keeps a successful final fit: plane, attitude, inliers, fit statistics, covariances, pixel conic.
  void storeEstimate(const vsp::laser_robust_fit::Result &result, vpPlane &cPlane);
};

#endif
