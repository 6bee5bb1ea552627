/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_selfcal_steps.h
  \brief Private: the steps of vpLaserConicSelfCalibration::compute(): initial planes, scale, frame
  selection by information, robust rounds of the joint problem, covariance and observability.
*/
#ifndef VP_LASER_SELFCAL_STEPS_H
#define VP_LASER_SELFCAL_STEPS_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpPlane.h>
#include <visp3/laser_conic/vpLaserConicSelfCalibration.h>

#include "laser_selfcal_problem.h"

namespace vpLaserSelfCal
{
//! A frame as given to the facade.
struct InputFrame
{
  const std::vector<vpImagePoint> *points = nullptr;
  bool hasPlane = false;
  vpPlane plane;
  double knownAltitude = 0.0; //!< 0: unknown
};

//! Settings of the facade that the steps use.
struct StepsSettings
{
  double apexDistance = 0.0; //!< 0: the scale comes from known altitudes
  bool estimateAngle = false;
  bool holdApex = false; //!< the apex held at the initial laser's
  unsigned int maxFrames = 40;
  double maxStd = 0.0; //!< observability limit (rad) on the axis; twice it on the apex direction
};

//! What the steps produce: the facade's figures (copied as a whole) and the result.
struct StepsOutcome : vpLaserConicSelfCalibration::Figures
{
  vpLaserConicSelfCalibration::vpSelfCalibrationStatus status = vpLaserConicSelfCalibration::STATUS_NOT_COMPUTED;
  std::string details;
  vpHomogeneousMatrix cMl;
  double openingAngle = 0.0;
};

//! The steps of one self-calibration.
class Steps
{
public:
  Steps(const vpCameraParameters &cam, double openingAngle, const vpHomogeneousMatrix &cMl);
  StepsOutcome run(const std::vector<InputFrame> &inputs, const StepsSettings &settings);

private:
  //! One run of the steps from the initial laser (m_cone0).
  StepsOutcome attempt(const std::vector<InputFrame> &inputs, const StepsSettings &settings);
  bool initialPlanes(const std::vector<InputFrame> &inputs, StepsOutcome &out);
  //! initialPlanes(), applyScale(), selectFrames() and robustRounds(): false, with out's status, on a failure.
  bool solveFromTheInitialLaser(const std::vector<InputFrame> &inputs, const StepsSettings &settings,
                                StepsOutcome &out);
  /*!
    Replaces the initial laser by its axis tilted by up to 12 degrees on a grid, the one under which GP-3 explains
    the most points of a few frames within its RANSAC threshold; false when the initial axis does best.
  */
  bool searchInitialAxis(const std::vector<InputFrame> &inputs);
  void applyScale(const std::vector<InputFrame> &inputs, const StepsSettings &settings);
  std::vector<size_t> selectFrames(const std::vector<InputFrame> &inputs, unsigned int maxFrames) const;
  bool robustRounds(StepsOutcome &out);
  //! The planes of the frames out of the joint problem: GP-3's with the calibrated laser (out.cMl), zero without.
  void planesOfFramesLeftOut(const std::vector<InputFrame> &inputs, StepsOutcome &out) const;
  void analyse(StepsOutcome &out) const;
  void attitudeSpread(StepsOutcome &out) const;
  std::string degeneracyDetails(const StepsOutcome &out, const LaserVector &weakest) const;
  std::vector<double> residuals(const Frame &f) const;

  vpCameraParameters m_cam;
  double m_focal;
  vpLaserSolvers::LaserCone m_cone0;
  ApexChart m_chart;
  LaserVector m_L;
  SolveSettings m_solve;
  std::vector<Frame> m_all;    //!< one per input frame (empty points when unusable)
  std::vector<size_t> m_index; //!< input index of each frame of m_frames
  std::vector<Frame> m_frames; //!< the frames of the joint problem
};
} // namespace vpLaserSelfCal

#endif
