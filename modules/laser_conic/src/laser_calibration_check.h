/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*
  The calibration check of vpLaserConicPose: a trace that the plane-constrained fit (3 DOF, the
  rig's calibration) misses far beyond what the free conic fit (5 DOF, the image alone) leaves is
  not a noisy trace but a wrong calibration. Both fits run on the same trace; with a right
  calibration and noise sigma, n (rms_c^2 - rms_f^2) / sigma^2 follows a chi-square law of 2 degrees
  of freedom, so the misfit the calibration adds, sqrt(rms_c^2 - rms_f^2), is a small fraction of
  sigma for the hundreds of points of a trace (about 0.07 sigma at 1e-6 for 1000 points); detector
  bias adds a little (at most 0.3 sigma on the 144 shipped frames). An imperfect calibration adds
  more, and the estimators tolerate it: intrinsics off by 5 px (the paper's Fig. 9 protocol, 0.5 px
  noise) leave a misfit of 4.7 sigma at the median, 21 sigma at the 99th percentile, 24 at most
  (300 scenes). The check refuses a misfit above 30 times the noise scale and above 3 px. The usual
  mistakes leave tens of pixels, 45 to 300 times the noise on the shipped frames. Not always: with
  lMc given for cMl, a fading ring of laser_hard left 14 px at 0.6 px noise (24 sigma), and a cluttered
  frame a partial trace whose noise scale the wrong fit inflated to 1.8 px (2.6 sigma). So a misfit
  above one noise scale, which a right calibration never reaches, has the standard mistakes tried, and
  is refused when one of them explains the whole trace (as many points) within the noise with less
  than half of the misfit: an imperfect calibration is not explained better by a gross mistake
  (intrinsics off by 5 px: none of 900 estimates refused this way).
*/
#ifndef VP_LASER_CALIBRATION_CHECK_H
#define VP_LASER_CALIBRATION_CHECK_H

#include <functional>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/laser_conic/vpLaserConicPose.h>

#include "laser_estimators.h"
#include "laser_robust_fit.h"

namespace vsp::laser_calibration_check
{
//! Misfit allowed, in multiples of the noise scale of the trace (above the 24 of intrinsics off by 5 px).
constexpr double kNoiseFactor = 30.0;
//! Misfit always allowed (pixels): small calibration errors on near-exact points.
constexpr double kFloorPixels = 3.0;

/*!
  Misfit above which the calibration is suspect, in multiples of the noise scale: a right calibration
  adds about 0.07 sigma (noise) and at most 0.3 sigma (detector bias, 157 shipped frames); above one
  noise scale the calibration adds as much error as the noise, and the standard mistakes are tried.
  An imperfect calibration (up to kNoiseFactor) is still accepted unless a mistake fits markedly better.
*/
constexpr double kSuspectFactor = 1.0;
//! Misfit (pixels) below which no calibration is suspected, whatever the noise scale.
constexpr double kSuspectFloorPixels = 0.5;
/*!
  An alternative calibration fits markedly better when it leaves less than this fraction of the
  misfit (a quarter of the added squared error).
*/
constexpr double kBetterFraction = 0.5;

//! Misfit (pixels) the calibration adds to the free fit, sqrt(max(0, rms_c^2 - rms_f^2)); NaN without constrained fit.
double misfit(const vsp::laser_robust_fit::Result &result);
//! Largest misfit the noise explains: max(kNoiseFactor max(sigma, rms_f), kFloorPixels).
double tolerance(const vsp::laser_robust_fit::Result &result);
//! True unless the misfit is beyond the tolerance (a missing constrained fit cannot be judged: true).
bool explained(const vsp::laser_robust_fit::Result &result);
//! True when the misfit exceeds kSuspectFactor noise scales (and kSuspectFloorPixels): the mistakes are worth trying.
bool suspect(const vsp::laser_robust_fit::Result &result);

/*!
  The fit's noise scale is inflated by a model error, not by noise, when the trace is this many times
  smoother locally than the fit says (see localNoise()).
*/
constexpr double kInflatedScale = 4.0;

/*!
  Noise (pixels) of the trace measured along it, without any model: the points of \e indices ordered
  around the centre of the ellipse \e conic, the distance of each to the chord of its two neighbours
  when both lie within \e spacing (normalised units), robust spread (1.4826 MAD) over sqrt(3/2), as for
  independent noise on the three points. A wrong calibration's fit can take as inliers pieces of a clean
  trace where it crosses it and clutter besides: its own residual scale then explains any misfit (u and v
  swapped on a cluttered frame: a scale of 2.8 px where the right calibration's fit has 0.21 px). 0 when fewer than 20 triples.
*/
double localNoise(const vsp::laser_estimators::PointList &points, const std::vector<int> &indices,
                  const Eigen::Matrix3d &conic, double focal, double spacing);

/*!
  The fit's noise scale is inflated (kInflatedScale times the trace's localNoise() or more) and the misfit
  exceeds kSuspectFactor times that local noise: suspect() on the trace's own noise. \e points: the
  normalised points of the fit; \e focal: pixels per normalised unit. The caller checks first that the
  misfit exceeds kSuspectFloorPixels (this function orders the trace, the points need converting).
*/
bool suspectAtLocalNoise(const vsp::laser_estimators::PointList &points, const vsp::laser_robust_fit::Result &result,
                         double focal);

//! A calibration the user may have meant, one standard mistake away from the one given.
struct Alternative
{
  vpLaserConicPose::vpLaserConicMistake mistake;
  double openingAngle;     //!< full opening angle (rad)
  vpHomogeneousMatrix cMl; //!< laser pose
  vpCameraParameters cam;  //!< intrinsics
  bool swapUV;             //!< image points with u and v exchanged
};

/*!
  The standard mistake that explains the trace: \e fits runs the estimation under an alternative
  calibration and returns its misfit when it is explained (a negative number otherwise); the
  alternative of smallest misfit wins, and \e bestMisfit (when given) receives its misfit (infinity
  when none fits). MISTAKE_UNKNOWN when none fits.
*/
vpLaserConicPose::vpLaserConicMistake diagnose(double openingAngle, const vpHomogeneousMatrix &cMl,
                                               const vpCameraParameters &cam,
                                               const std::function<double(const Alternative &)> &fits,
                                               double *bestMisfit = nullptr);
} // namespace vsp::laser_calibration_check

#endif
