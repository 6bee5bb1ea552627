/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
//! \example tutorial-laser-landing.cpp
//! A circular laser used as an altimeter during a simulated landing: every frame is rendered by
//! vpLaserConicSimulator, the red trace is found by vpLaserConicDetector and vpLaserConicPose (GP-3)
//! gives altitude, roll and pitch, compared with the truth.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRxyzVector.h>
#include <visp3/laser_conic/vpLaserConicDetector.h>
#include <visp3/laser_conic/vpLaserConicPose.h>
#include <visp3/laser_conic/vpLaserConicSimulator.h>

#include "vpPngPlot.h"
#include "vpTutorialCommon.h"

namespace
{
//! Truth of one frame of the descent.
struct FlightState
{
  double altitude;       //!< metres
  double roll;           //!< rad
  double pitch;          //!< rad
  double driftX, driftY; //!< horizontal position over the ground, metres
};

//! [Descent]
//! From 2 m down to 0.3 m, slowing down near the ground, with small roll/pitch oscillations.
FlightState descent(int k, int frames)
{
  const double s = static_cast<double>(k) / (frames - 1);
  FlightState f;
  f.altitude = 0.3 + 1.7 * vpMath::sqr(1.0 - s);
  f.roll = vpMath::rad(6.0 * std::sin(2 * M_PI * 2.0 * s));
  f.pitch = vpMath::rad(4.0 * std::cos(2 * M_PI * 1.5 * s));
  f.driftX = 0.06 * s;
  f.driftY = -0.04 * s;
  return f;
}

//! Ground frame (plane Z = 0) in the camera frame for a flight state. With w the level frame of the
//! camera (z along gravity), the downward direction in the camera is
//! g = Rx(roll) Ry(pitch) e_z, the attitude convention of vpLaserConicPose.
vpHomogeneousMatrix groundPose(const FlightState &f)
{
  const vpRotationMatrix cRw =
      vpRotationMatrix(vpRxyzVector(f.roll, 0, 0)) * vpRotationMatrix(vpRxyzVector(0, f.pitch, 0));
  const vpTranslationVector wTg(f.driftX, f.driftY, f.altitude); // ground origin below the camera
  return vpHomogeneousMatrix(cRw * wTg, cRw);
}
//! [Descent]

//! [Marker]
//! Paints the red cross of the landing pad (0.4 m arms around the ground origin) into the image: red
//! pixels the detector takes for laser light, which GP-3 has to reject as outliers.
void paintLandingMarker(vpImage<vpRGBa> &I, const vpHomogeneousMatrix &cMg, const vpCameraParameters &cam)
{
  const double arm = 0.2;
  const double ends[2][2][2] = {{{-arm, 0}, {arm, 0}}, {{0, -arm}, {0, arm}}};
  for (const auto &segment : ends) {
    vpImagePoint ip[2];
    for (int k = 0; k < 2; ++k) {
      vpPoint P(segment[k][0], segment[k][1], 0);
      P.project(cMg);
      vpMeterPixelConversion::convertPoint(cam, P.get_x(), P.get_y(), ip[k]);
    }
    vpImageDraw::drawLine(I, ip[0], ip[1], vpColor(210, 25, 25), 3);
  }
}
//! [Marker]

//! [Draw conic]
//! Draws the ellipse x^T C x = 0 (x = (u, v, 1), pixels) with vpImageDraw; nothing when it is not an ellipse.
void drawImageConic(vpImage<vpRGBa> &I, const vpMatrix &C, const vpColor &color, unsigned int thickness)
{
  if (C.getRows() != 3 || C.getCols() != 3)
    return;
  // Centre p0 = -M^-1 b, then (p - p0)^T M (p - p0) = k with M the quadratic part.
  const double a = C[0][0], b = 0.5 * (C[0][1] + C[1][0]), c = C[1][1];
  const double d = 0.5 * (C[0][2] + C[2][0]), e = 0.5 * (C[1][2] + C[2][1]), f = C[2][2];
  const double det = a * c - b * b;
  if (det <= 0)
    return;
  const double u0 = (b * e - c * d) / det, v0 = (b * d - a * e) / det;
  const double k = -(d * u0 + e * v0 + f);
  // Eigen decomposition of the symmetric 2x2 quadratic part.
  const double mean = 0.5 * (a + c), diff = std::sqrt(vpMath::sqr(0.5 * (a - c)) + b * b);
  const double l1 = mean + diff, l2 = mean - diff;
  if (k / l1 <= 0 || k / l2 <= 0)
    return;
  const double phi = 0.5 * std::atan2(2 * b, a - c); // direction of the l1 eigenvector
  // vpImageDraw takes the ellipse as centre, semi-axes and the angle of the first axis with u.
  vpImageDraw::drawEllipse(I, vpImagePoint(v0, u0), std::sqrt(k / l1), std::sqrt(k / l2), phi, false, color, 0,
                           2 * M_PI, thickness);
}
//! [Draw conic]

//! [Overlay]
//! Detected points (outliers in yellow, inliers in green) and the fitted conic (blue) over the frame.
void writeOverlay(const vpImage<vpRGBa> &frame, const std::vector<vpImagePoint> &points,
                  const std::vector<unsigned int> &inliers, const vpMatrix &conic, const std::string &caption,
                  const std::string &filename)
{
  vpImage<vpRGBa> I = frame;
  std::vector<bool> isInlier(points.size(), false);
  for (unsigned int i : inliers)
    if (i < points.size())
      isInlier[i] = true;
  for (size_t i = 0; i < points.size(); ++i)
    vpImageDraw::drawPoint(I, points[i] - vpImagePoint(0.5, 0.5), isInlier[i] ? vpColor::green : vpColor::yellow, 3);
  drawImageConic(I, conic, vpColor::blue, 1); // over the points, thin, to show how well it fits
  vpTutorialWriteCaptioned(I, caption, vpColor::white, filename);
}
//! [Overlay]

//! The descent, its figures and its checks; true when altitude and attitude errors are within the bounds.
bool runLandingTutorial(int frames, const std::string &outputDir, bool display)
{
  //! [Rig]
  const unsigned int width = 640, height = 480;
  const vpCameraParameters cam(500, 500, 320, 240);
  const double openingAngle = vpMath::rad(34);                     // full opening angle of the laser
  const vpHomogeneousMatrix cMl(0.08, 0, 0, 0, vpMath::rad(2), 0); // laser 8 cm beside the camera, slightly tilted

  vpLaserConicSimulator simulator;
  simulator.setCamera(cam, width, height);
  simulator.setLaser(openingAngle, cMl);
  simulator.setSeed(3);

  vpLaserConicDetector detector;
  vpLaserConicPose estimator;
  estimator.setCameraParameters(cam);
  estimator.setLaser(openingAngle, cMl);
  estimator.setRansacSeed(5);
  //! [Rig]

  std::vector<double> frameIndex, altTrue, altEst, rollTrue, rollEst, pitchTrue, pitchEst;
  double sumAltRel = 0, sumRollDeg = 0, sumPitchDeg = 0, maxAltRel = 0;
  int failures = 0;
  const int overlayFrame = frames / 2;
  vpTutorialViewer viewer(display, "Laser landing: detected trace (GP-3 inliers in green)");
  for (int k = 0; k < frames; ++k) {
    const FlightState truth = descent(k, frames);
    //! [Frame]
    simulator.setGroundPose(groundPose(truth));
    vpImage<vpRGBa> I;
    simulator.render(I); // procedural ground texture, 3 px stripe, sensor noise
    paintLandingMarker(I, groundPose(truth), cam);
    const std::vector<vpImagePoint> points = detector.detect(I);
    vpPlane cPlane;
    const bool found = points.size() >= 3 && estimator.computePlane(points, vpLaserConicPose::GP3, cPlane);
    //! [Frame]
    viewer.show(I); // --display: the frame and the inliers of GP-3
    if (found)
      for (unsigned int i : estimator.getInliers())
        vpDisplay::displayPoint(viewer.image(), points[i], vpColor::green, 2);
    viewer.flush();
    if (!found) {
      std::cerr << "frame " << k << ": no plane (" << points.size() << " points) " << estimator.getFailureReason()
                << std::endl;
      ++failures;
      continue;
    }
    frameIndex.push_back(k);
    altTrue.push_back(truth.altitude);
    altEst.push_back(estimator.getAltitude());
    rollTrue.push_back(vpMath::deg(truth.roll));
    rollEst.push_back(vpMath::deg(estimator.getRoll()));
    pitchTrue.push_back(vpMath::deg(truth.pitch));
    pitchEst.push_back(vpMath::deg(estimator.getPitch()));
    const double altRel = std::fabs(estimator.getAltitude() - truth.altitude) / truth.altitude;
    sumAltRel += altRel;
    maxAltRel = std::max(maxAltRel, altRel);
    sumRollDeg += std::fabs(rollEst.back() - rollTrue.back());
    sumPitchDeg += std::fabs(pitchEst.back() - pitchTrue.back());

    if (k == overlayFrame) {
      std::ostringstream caption;
      caption << std::fixed << std::setprecision(3) << "altitude " << estimator.getAltitude() << " m (truth "
              << truth.altitude << "), " << estimator.getInliers().size() << "/" << points.size() << " inliers";
      writeOverlay(I, points, estimator.getInliers(), estimator.getImageConic(), caption.str(),
                   vpIoTools::createFilePath(outputDir, "laser-landing-overlay.png"));
    }
  }

  viewer.waitClick();

  //! [Plots]
  vpPngPlot altitude("Altitude during the descent", "frame", "altitude (m)", 640, 420);
  altitude.addCurve("truth", frameIndex, altTrue, vpColor::black);
  altitude.addPoints("GP-3", frameIndex, altEst, vpColor::red);
  altitude.write(vpIoTools::createFilePath(outputDir, "laser-landing-altitude.png"));

  vpPngPlot attitude("Attitude during the descent", "frame", "angle (deg)", 640, 420);
  attitude.addCurve("roll, truth", frameIndex, rollTrue, vpColor::black);
  attitude.addPoints("roll, GP-3", frameIndex, rollEst, vpColor::red);
  attitude.addCurve("pitch, truth", frameIndex, pitchTrue, vpColor::gray);
  attitude.addPoints("pitch, GP-3", frameIndex, pitchEst, vpColor::blue);
  attitude.write(vpIoTools::createFilePath(outputDir, "laser-landing-attitude.png"));
  //! [Plots]

  const int n = static_cast<int>(frameIndex.size());
  const double meanAltRel = n ? sumAltRel / n : 1.0, meanRoll = n ? sumRollDeg / n : 90.0,
               meanPitch = n ? sumPitchDeg / n : 90.0;
  std::cout << std::fixed << std::setprecision(3) << frames << " frames, " << failures
            << " without estimate. Mean errors: altitude " << 100 * meanAltRel << " % (max " << 100 * maxAltRel
            << " %), roll " << meanRoll << " deg, pitch " << meanPitch << " deg" << std::endl;
  std::cout << "Images written to " << outputDir << "/laser-landing-{altitude,attitude,overlay}.png" << std::endl;

  // Bounds: the detector locates the 3 px stripe to about a tenth of a pixel and GP-3 refits the plane
  // on its ~1000 inliers, which averages that noise down: measured mean 0.02 % of altitude (worst frame
  // 0.08 %) and 0.05 deg. A wrong model, a marker pixel kept as inlier or a mismatched convention
  // costs at least several tenths of a percent or of a degree; the bounds (mean 0.1 %, worst frame
  // 0.5 %, roll and pitch 0.2 deg, every frame estimated) catch that with a margin over the noise.
  return vpTutorialCheck(failures == 0 && meanAltRel < 0.001 && maxAltRel < 0.005 && meanRoll < 0.2 && meanPitch < 0.2,
                         "errors above the bounds (mean altitude 0.1 %, max 0.5 %, roll/pitch 0.2 deg) or frames "
                         "without estimate");
}
} // namespace

int main(int argc, char **argv)
{
  vpTutorialProgram program("[--frames N]", "Simulated landing measured by a camera and a circular laser (GP-3); "
                                            "writes laser-landing-*.png.");
  return program.run(argc, argv, "--frames", 40, 2, "number of frames of the descent", runLandingTutorial);
}
