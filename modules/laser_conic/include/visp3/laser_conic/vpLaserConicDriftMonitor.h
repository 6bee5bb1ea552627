/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicDriftMonitor.h
  \brief Detection, in use, of a laser/camera calibration that no longer fits the images (a knocked mount,
  a re-assembly): a sliding-window test on the per-frame calibration-health figures.
*/
#ifndef VP_LASER_CONIC_DRIFT_MONITOR_H
#define VP_LASER_CONIC_DRIFT_MONITOR_H

#include <string>
#include <vector>

#include <visp3/core/vpConfig.h>
#include <visp3/laser_conic/vpLaserConicException.h>

class vpLaserConicPose;

/*!
  \ingroup group_laser_conic
  \brief Tells a calibration error from image noise over a sliding window of frames.

  Each frame estimated by vpLaserConicPose (constrained final fit: FINAL_FIT_SELECT, the default of GP3
  and PP3, or FINAL_FIT_CONSTRAINED) fits its trace twice: with the plane the calibrated laser predicts (3
  degrees of freedom) and with a free conic (5). With a correct calibration both fit to the noise and
  the two extra degrees of freedom of the free conic gain only noise: the frame's statistic
  \f[ s = (n - 5) \left( \frac{\mathrm{RMS}_{c}^2}{\mathrm{RMS}_{f}^2} - 1 \right) \f]
  (n inliers; RMS_c / RMS_f is vpLaserConicPose::getCalibrationHealth()) is then close to a
  \f$ \chi^2_2 \f$ variable (F-test of nested models). A calibration error leaves the free fit at the noise
  level but not the constrained one, and s grows with the number of points. The monitor sums s over the
  last setWindow() frames and compares the sum with a threshold derived from the \f$ \chi^2_{2W} \f$
  quantile (Wilson-Hilferty) at the nominal false-alarm rate setFalseAlarmRate() (default 0.1 %). Under a
  correct calibration the frame statistic is close to a \f$ \chi^2_2 \f$ (measured below: mean 2.09 and
  variance 3.8 against 2 and 4); its mean 4.6 % too large makes the actual rate a few times the nominal one.

  Measured (tests, simulated flights: 34 degree laser 10 cm from a 1000 px camera with barrel distortion,
  roll and pitch within +-15 degrees, altitude 0.8-1.3 m, 300 points per frame, 0.5 px noise, GP3):
  - correct calibration, 2000 frames (1981 sliding windows of 20 frames): 0.4 % of the windows over the
    threshold at the default rate (0.1 %), 2.7 % at a nominal 1 % (testLaserConicDriftMonitor);
  - axis knocked by 1 degree (about either axis), apex moved by 5 mm (across or along the optical axis):
    detected at the first frame after the knock (one such frame's statistic, several hundred to thousands,
    exceeds the window's threshold alone);
  - the monitor sees what the images see: an apex moved along its own direction is a change of scale, which
    the images show only through the small altitude dependence (see vpLaserConicSelfCalibration).
  - a knock large enough that the estimator refuses every frame (STATUS_CALIBRATION_MISMATCH; 5 degrees):
    detected at the first frame after it. Such a frame counts with the figures of the refused estimate:
    add every frame, whether computePlane() succeeded or not.
  Frames without a health figure (an estimate that failed before its final fit, no constrained fit: NaN)
  are skipped. The cost of addFrame() is a few additions (a ring buffer): well under a microsecond.

  \code
  vpLaserConicDriftMonitor monitor;     // 20 frames, 0.1 % false alarms
  for (;;) {
    const bool ok = estimator.computePlane(points, vpLaserConicPose::GP3, plane);
    if (monitor.addFrame(estimator) == vpLaserConicDriftMonitor::DRIFT_SUSPECTED) // refused frames count too
      std::cerr << monitor.getStatusMessage(monitor.getStatus()) << std::endl; // recalibrate
    if (ok) {
      // use plane
    }
  }
  \endcode
*/
class VISP_EXPORT vpLaserConicDriftMonitor
{
public:
  //! Outcome of the last addFrame().
  typedef enum {
    DRIFT_WARMING_UP, //!< fewer frames with a health figure than the window since the start or reset()
    DRIFT_OK,         //!< the window's statistic is within the threshold: the calibration fits the images
    DRIFT_SUSPECTED   //!< the window's statistic exceeds the threshold: calibration drift suspected
  } vpDriftStatus;

  //! Monitor of 20 frames at a 0.1 % false-alarm rate.
  vpLaserConicDriftMonitor();

  /*!
    Window length in frames (default 20); restarts the monitor.
    \exception vpLaserConicException::badValueError when 0 or over 100000.
  */
  void setWindow(unsigned int frames);
  /*!
    False-alarm rate per window in (0, 0.5) (default 0.001); restarts the monitor. Rates down to the smallest
    double give a finite threshold.
    \exception vpLaserConicException::badValueError outside (0, 0.5).
  */
  void setFalseAlarmRate(double rate);
  //! Forgets every frame (e.g. after a recalibration).
  void reset();

  /*!
    Adds the last estimate of \e estimator (its health figure and number of inliers), a success or one refused
    as STATUS_CALIBRATION_MISMATCH (the refused estimate's figures).
    \return the status after this frame; a frame with any other status, whose health is not finite or with
    fewer than 6 inliers is skipped (the status is unchanged).
  */
  vpDriftStatus addFrame(const vpLaserConicPose &estimator);
  /*!
    Adds a frame from its constrained and free RMS residuals (pixels) and number of inliers, as
    vpLaserConicPose::getConstrainedRms(), getFreeRms(), getRansacNbInliers() give them. Skipped (status
    unchanged) when they are not finite and positive or n < 6. A frame adds at most 1e9 to the window's sum
    (getStatistic()), more than any threshold: a nearly exact free fit (s of 1e20 or infinite) does not
    upset the running sum when it leaves the window.
  */
  vpDriftStatus addFrame(double constrainedRms, double freeRms, unsigned int nbInliers);

  //! Status after the last addFrame().
  vpDriftStatus getStatus() const { return m_status; }
  //! What a status means, in words ("calibration drift suspected: ...").
  static std::string getStatusMessage(vpDriftStatus status);
  //! Sum of the per-frame statistics over the window (see the class description).
  double getStatistic() const { return m_sum; }
  //! Threshold of the window's statistic.
  double getThreshold() const { return m_threshold; }
  //! Number of frames in the window (at most setWindow()).
  unsigned int getNbFramesInWindow() const { return m_count; }
  //! Frames skipped since the start or reset() (no health figure).
  unsigned int getNbSkipped() const { return m_skipped; }
  //! Frame statistic s of the last frame added (NaN when skipped).
  double getLastFrameStatistic() const { return m_last; }

private:
  void updateThreshold();

  unsigned int m_window;
  double m_rate, m_threshold;
  std::vector<double> m_values;
  unsigned int m_next, m_count, m_skipped;
  double m_sum, m_last;
  vpDriftStatus m_status;
};

#endif
