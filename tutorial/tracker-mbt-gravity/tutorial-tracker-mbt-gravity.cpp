/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
//! \example tutorial-tracker-mbt-gravity.cpp
//! Model-based tracking of a box with vpMbGenericTracker (moving edges) on images rendered by
//! vpImageSimulator. vpPoseGravity gives the tracker its initial pose from three image points and the
//! two gravity directions, and re-initialises it when the tracking is lost (the box is pushed while
//! the camera looks at it).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTrackingException.h>
#include <visp3/mbt/vpMbGenericTracker.h>
#include <visp3/me/vpMe.h>
#include <visp3/pose_gravity/vpPoseGravity.h>
#include <visp3/robot/vpImageSimulator.h>

#include "vpPngPlot.h"
#include "vpTutorialCommon.h"

namespace
{
//! [Box]
//! The object: a 20 x 15 x 10 cm box standing on a table. Object frame at a bottom corner, X and Y
//! along the bottom edges, Z pointing down (so the box spans z in [-0.10, 0]): gravity is +Z.
const double kSizeX = 0.20, kSizeY = 0.15, kSizeZ = 0.10;
const vpColVector kGravityInObject{0, 0, 1};

//! Corner i of the box: bit 2 of i selects x, bit 1 y, bit 0 z (0 on the table, -kSizeZ on top).
vpPoint boxCorner(unsigned int i)
{
  return vpPoint((i & 4) ? kSizeX : 0.0, (i & 2) ? kSizeY : 0.0, (i & 1) ? -kSizeZ : 0.0);
}

//! The six faces as corner indices, counter-clockwise seen from outside the box (vpMbGenericTracker's
//! visibility test takes the face normal from this order).
const unsigned int kFaces[6][4] = {{0, 2, 3, 1}, {0, 1, 5, 4}, {0, 4, 6, 2}, {7, 5, 1, 3}, {7, 6, 4, 5}, {7, 3, 2, 6}};
//! Grey level of each face in the rendered images (the top, Z = -kSizeZ, is face 3).
const unsigned char kFaceGrey[6] = {150, 95, 60, 215, 120, 175};
//! [Box]

//! [Model]
//! Writes the box as a CAO model (ViSP's format: 3D points, then faces made of points).
void writeCaoModel(const std::string &filename)
{
  std::ofstream cao(filename);
  cao << "V1\n# 3D points\n8\n";
  for (unsigned int i = 0; i < 8; ++i) {
    const vpPoint P = boxCorner(i);
    cao << P.get_oX() << " " << P.get_oY() << " " << P.get_oZ() << "\n";
  }
  cao << "# 3D lines\n0\n# Faces from 3D lines\n0\n# Faces from 3D points\n6\n";
  for (const auto &face : kFaces)
    cao << "4 " << face[0] << " " << face[1] << " " << face[2] << " " << face[3] << "\n";
  cao << "# 3D cylinders\n0\n# 3D circles\n0\n";
  if (!cao)
    throw vpException(vpException::ioError, "cannot write the model file " + filename);
}
//! [Model]

//! [Simulator]
/*!
  One vpImageSimulator per face, textured with the face's uniform grey. The simulator draws a face only
  when it turns towards the camera, taking the face's orientation from its corners in the opposite
  order to the CAO model's (texture corners: top-left, top-right, bottom-right, bottom-left).
*/
std::vector<vpImageSimulator> makeBoxFaces()
{
  std::vector<vpImageSimulator> faces(6, vpImageSimulator(vpImageSimulator::GRAY_SCALED));
  for (unsigned int f = 0; f < 6; ++f) {
    std::vector<vpPoint> corners;
    for (unsigned int c : kFaces[f])
      corners.insert(corners.begin(), boxCorner(c));
    faces[f].init(vpImage<unsigned char>(16, 16, kFaceGrey[f]), corners);
  }
  return faces;
}

/*!
  Renders the box seen from cMo over a dark background, then adds seeded sensor noise. The box is
  convex: the faces that turn towards the camera never overlap, so they are drawn in any order.
*/
void renderFrame(std::vector<vpImageSimulator> &faces, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                 std::mt19937 &rng, vpImage<unsigned char> &I)
{
  I = 35;
  for (vpImageSimulator &face : faces) {
    face.setCameraPosition(cMo);
    face.getImage(I, cam);
  }
  std::normal_distribution<double> noise(0.0, 2.0);
  for (unsigned int n = 0; n < I.getSize(); ++n)
    I.bitmap[n] = vpMath::saturate<unsigned char>(I.bitmap[n] + noise(rng));
}
//! [Simulator]

//! [Motion]
/*!
  Ground truth at frame k: the camera circles slowly around the box, 0.6 m away and 35 degrees above
  it, looking at its centre with its image rows level (a hand-held camera). From frame \e pushFrame on,
  the box has been pushed along the table: 5 cm and 3 cm along its edges and 25 degrees about the
  vertical, between two frames, far more than the moving edges can follow.
*/
vpHomogeneousMatrix boxPose(int k, int frames, int pushFrame)
{
  const double s = 2 * M_PI * k / frames;
  const double azimuth = vpMath::rad(225 + 20 * std::sin(s)), elevation = vpMath::rad(35 + 5 * std::sin(1.7 * s));
  const double distance = 0.6 + 0.05 * std::sin(0.9 * s);
  const vpColVector centre{kSizeX / 2, kSizeY / 2, -kSizeZ / 2};
  const vpColVector position = centre + distance * vpColVector{std::cos(elevation) * std::cos(azimuth),
                                                               std::cos(elevation) * std::sin(azimuth),
                                                               -std::sin(elevation)};
  // Camera axes in the object frame: z towards the centre, x level (orthogonal to gravity), y down.
  vpColVector z = centre - position;
  z.normalize();
  vpColVector x = vpColVector::crossProd(kGravityInObject, z);
  x.normalize();
  const vpColVector y = vpColVector::crossProd(z, x);
  vpRotationMatrix oRc;
  for (unsigned int r = 0; r < 3; ++r) {
    oRc[r][0] = x[r];
    oRc[r][1] = y[r];
    oRc[r][2] = z[r];
  }
  vpHomogeneousMatrix oMc(vpTranslationVector(position[0], position[1], position[2]), oRc);
  if (k >= pushFrame) // the box moved on the table: a translation and a rotation about the vertical Z
    oMc = vpHomogeneousMatrix(-0.05, -0.03, 0, 0, 0, vpMath::rad(25)) * oMc;
  return oMc.inverse();
}
//! [Motion]

//! Three top corners of the box (one of each pair of opposite corners, never collinear).
const unsigned int kInitCorners[3] = {1, 5, 7};

/*!
  What a user clicking on three top corners (or a keypoint matcher) gives: their image positions,
  here the projections in the true pose with 0.5 px of noise, as normalized coordinates.
*/
std::vector<vpPoint> measureInitPoints(const vpHomogeneousMatrix &cMoTrue, const vpCameraParameters &cam,
                                       std::mt19937 &rng)
{
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<vpPoint> points;
  for (unsigned int c : kInitCorners) {
    vpPoint P = boxCorner(c);
    P.project(cMoTrue);
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(cam, P.get_x(), P.get_y(), ip);
    ip.set_uv(ip.get_u() + noise(rng), ip.get_v() + noise(rng));
    double x = 0, y = 0;
    vpPixelMeterConversion::convertPoint(cam, ip, x, y);
    P.set_x(x);
    P.set_y(y);
    points.push_back(P);
  }
  return points;
}

//! [Gravity pose]
/*!
  The pose of the box from three image points and the gravity measured by an IMU on the camera and
  known in the object frame (the box stands on the table). Returns false when the P3P has no solution.
*/
bool gravityPose(const std::vector<vpPoint> &points, const vpColVector &gravityInCamera, vpHomogeneousMatrix &cMo)
{
  vpPoseGravity pose;
  pose.setCameraGravity(gravityInCamera);
  pose.setObjectGravity(kGravityInObject);
  pose.addPoints(points);
  if (!pose.computePose(vpPoseGravity::P3P, cMo)) {
    std::cerr << "P3P: " << vpPoseGravity::getStatusMessage(pose.getStatus()) << std::endl;
    return false;
  }
  return true;
}
//! [Gravity pose]

//! [Tracker]
//! An edge tracker of the box model, with the settings of ViSP's tutorials for a 640x480 camera.
void setupTracker(vpMbGenericTracker &tracker, const std::string &caoFile, const vpCameraParameters &cam)
{
  vpMe me;
  me.setMaskSize(5);
  me.setMaskNumber(180);
  me.setRange(8);
  me.setThreshold(10000);
  me.setMu1(0.5);
  me.setMu2(0.5);
  me.setSampleStep(4);
  tracker.setMovingEdge(me);
  tracker.setCameraParameters(cam);
  tracker.setAngleAppear(vpMath::rad(70));
  tracker.setAngleDisappear(vpMath::rad(80));
  tracker.setNearClippingDistance(0.1);
  tracker.setFarClippingDistance(2.0);
  tracker.setClipping(tracker.getClipping() | vpPolygon3D::FOV_CLIPPING);
  tracker.setProjectionErrorComputation(true); // getProjectionError(): the loss detector below
  tracker.setDisplayFeatures(false);
  tracker.loadModel(caoFile);
}
//! [Tracker]

//! [Track]
/*!
  Tracks one frame; returns false when the tracking is lost: the tracker throws (no edge found), or
  the projection error (mean angle in degrees between the image gradients and the projected model
  edges, 0 when they are aligned, about 45 for random gradients) exceeds \e maxProjectionErrorDeg.
*/
bool trackFrame(vpMbGenericTracker &tracker, const vpImage<unsigned char> &I, double maxProjectionErrorDeg)
{
  try {
    tracker.track(I);
  } catch (const vpException &) { // vpTrackingException: too few moving edges found
    return false;
  }
  return tracker.getProjectionError() <= maxProjectionErrorDeg;
}
//! [Track]

//! Pixel position of the normalized image coordinates (x, y) of P.
vpImagePoint pixelOf(const vpPoint &P, const vpCameraParameters &cam)
{
  vpImagePoint ip;
  vpMeterPixelConversion::convertPoint(cam, P.get_x(), P.get_y(), ip);
  return ip;
}

//! Draws the visible model edges of the tracker at cMo and the three points into the image pixels.
void drawTracking(vpImage<vpRGBa> &I, vpMbGenericTracker &tracker, const vpHomogeneousMatrix &cMo,
                  const vpCameraParameters &cam, const std::vector<vpPoint> &initPoints, const vpColor &color)
{
  for (const std::vector<double> &line : tracker.getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam))
    if (line.size() == 5 && line[0] == 0) // a segment: 0, i1, j1, i2, j2
      vpImageDraw::drawLine(I, vpImagePoint(line[1], line[2]), vpImagePoint(line[3], line[4]), color, 2);
  vpImageDraw::drawFrame(I, cMo, cam, 0.05, vpColor::none, 2);
  for (const vpPoint &P : initPoints)
    vpImageDraw::drawCross(I, pixelOf(P, cam), 14, vpColor::yellow, 2);
}

//! Error statistics of a range of frames.
struct ErrorRange
{
  double meanMm = 0, meanDeg = 0, maxMm = 0, maxDeg = 0;
  int frames = 0;
  void add(double mm, double deg)
  {
    meanMm += (mm - meanMm) / (frames + 1);
    meanDeg += (deg - meanDeg) / (frames + 1);
    maxMm = std::max(maxMm, mm);
    maxDeg = std::max(maxDeg, deg);
    ++frames;
  }
};

//! The sequence, its images and its checks; true when every check against the ground truth passes.
bool runMbtTutorial(int frames, const std::string &outputDir, bool display)
{
  const vpCameraParameters cam(800, 800, 320, 240);
  const double gravityNoise = 0.003; // IMU: per component of a unit vector, about 0.2 deg of tilt
  const double maxProjectionErrorDeg = 25;
  const int pushFrame = frames / 2;
  std::mt19937 rng(11);

  std::vector<vpImageSimulator> faces = makeBoxFaces();
  const std::string caoFile = vpIoTools::createFilePath(outputDir, "box.cao");
  writeCaoModel(caoFile);
  // Two trackers on the same images: one re-initialised by vpPoseGravity after a loss, one left alone.
  vpMbGenericTracker tracker(vpMbGenericTracker::EDGE_TRACKER), unaided(vpMbGenericTracker::EDGE_TRACKER);
  setupTracker(tracker, caoFile, cam);
  setupTracker(unaided, caoFile, cam);
  vpTutorialViewer viewer(display, "vpMbGenericTracker + vpPoseGravity");

  vpImage<unsigned char> I(480, 640);
  std::vector<double> index, errMm, unaidedMm;
  ErrorRange initError, beforePush, reinitError, afterPush;
  std::vector<int> lossFrames;
  double lostUnaidedMm = 0;
  bool initialised = false;
  for (int k = 0; k < frames; ++k) {
    const vpHomogeneousMatrix cMoTrue = boxPose(k, frames, pushFrame);
    renderFrame(faces, cMoTrue, cam, rng, I);
    const vpColVector gravityInCamera =
        vpTutorialMeasureGravity(vpColVector(cMoTrue.getRotationMatrix() * kGravityInObject), gravityNoise, rng);

    //! [Init and re-init]
    std::vector<vpPoint> initPoints;
    bool reinitialised = false;
    if (!initialised || !trackFrame(tracker, I, maxProjectionErrorDeg)) {
      if (initialised)
        lossFrames.push_back(k);
      initPoints = measureInitPoints(cMoTrue, cam, rng); // three clicked (or matched) corners
      vpHomogeneousMatrix cMoInit;
      if (!gravityPose(initPoints, gravityInCamera, cMoInit))
        return vpTutorialCheck(false, "no P3P pose at frame " + std::to_string(k));
      tracker.initFromPose(I, cMoInit);
      if (!initialised)
        unaided.initFromPose(I, cMoInit);
      reinitialised = initialised;
      double mm = 0, deg = 0;
      vpTutorialPoseError(cMoInit, cMoTrue, mm, deg);
      (initialised ? reinitError : initError).add(mm, deg);
      initialised = true;
    }
    vpHomogeneousMatrix cMo;
    tracker.getPose(cMo);
    //! [Init and re-init]
    if (k > 0)
      trackFrame(unaided, I, maxProjectionErrorDeg); // its loss is not handled
    vpHomogeneousMatrix cMoUnaided;
    unaided.getPose(cMoUnaided);

    double mm = 0, deg = 0, uMm = 0, uDeg = 0;
    vpTutorialPoseError(cMo, cMoTrue, mm, deg);
    vpTutorialPoseError(cMoUnaided, cMoTrue, uMm, uDeg);
    index.push_back(k);
    errMm.push_back(mm);
    unaidedMm.push_back(uMm);
    if (k > 0 && k < pushFrame)
      beforePush.add(mm, deg);
    else if (k > pushFrame + 2) // two frames for the edges to settle after the re-initialisation
      afterPush.add(mm, deg);
    if (k > pushFrame + 2)
      lostUnaidedMm = std::max(lostUnaidedMm, uMm);

    viewer.show(I); // --display: the tracked model, and the three points of a (re-)initialisation
    tracker.display(viewer.image(), cMo, cam, vpColor::red, 2);
    vpDisplay::displayFrame(viewer.image(), cMo, cam, 0.05, vpColor::none, 2);
    for (const vpPoint &P : initPoints)
      vpDisplay::displayCross(viewer.image(), pixelOf(P, cam), 14, vpColor::yellow, 2);
    viewer.flush(initPoints.empty() ? 30 : 1000);

    if (k == 1 || reinitialised || k == frames - 1) {
      vpImage<vpRGBa> overlay;
      vpImageConvert::convert(I, overlay);
      drawTracking(overlay, tracker, cMo, cam, initPoints, reinitialised ? vpColor::green : vpColor::red);
      std::ostringstream caption;
      caption << std::fixed << std::setprecision(1) << "frame " << k << (reinitialised ? " (re-initialised)" : "")
              << ": error " << mm << " mm, " << std::setprecision(2) << deg << " deg";
      char name[64];
      std::snprintf(name, sizeof(name), "tracker-mbt-gravity-frame-%03d.png", k);
      vpTutorialWriteCaptioned(overlay, caption.str(), vpColor::yellow, vpIoTools::createFilePath(outputDir, name));
    }
  }

  vpPngPlot plot("Pose error against ground truth (box pushed at frame " + std::to_string(pushFrame) + ")", "frame",
                 "translation error (mm)", 640, 420);
  plot.setLogY(true);
  plot.addCurve("tracker alone", index, unaidedMm, vpColor::blue);
  plot.addCurve("tracker + vpPoseGravity re-init", index, errMm, vpColor::red);
  plot.write(vpIoTools::createFilePath(outputDir, "tracker-mbt-gravity-errors.png"));

  std::cout << std::fixed << std::setprecision(2) << "Initial P3P pose: " << initError.meanMm << " mm / "
            << initError.meanDeg << " deg\nTracking before the push (" << beforePush.frames << " frames): mean "
            << beforePush.meanMm << " mm / " << beforePush.meanDeg << " deg, max " << beforePush.maxMm << " mm / "
            << beforePush.maxDeg << " deg\nLosses detected at frame(s):";
  for (int f : lossFrames)
    std::cout << " " << f;
  std::cout << " (box pushed at frame " << pushFrame << ")\nRe-initialised P3P pose: " << reinitError.meanMm << " mm / "
            << reinitError.meanDeg << " deg\nTracking after the re-initialisation (" << afterPush.frames
            << " frames): mean " << afterPush.meanMm << " mm / " << afterPush.meanDeg << " deg, max " << afterPush.maxMm
            << " mm / " << afterPush.maxDeg << " deg\nTracker without re-initialisation: "
            << "largest error after the push " << lostUnaidedMm << " mm\nImages written to " << outputDir
            << "/tracker-mbt-gravity-*.png" << std::endl;
  viewer.waitClick();

  // Bounds. The P3P uses 3 corners with 0.5 px of noise, 15-25 cm apart at 0.55-0.65 m (f = 800 px),
  // and IMU tilts of 0.2 deg: measured 0.5-1.0 mm / 0.3-0.4 deg; bound 10 mm / 1.5 deg, i.e. well within
  // what the moving edges (8 px search range) pull in. The tracker then fits ~380 moving edges on grey
  // steps of 35 levels or more under 2 levels of noise: measured mean 0.3-0.4 mm / 0.07 deg, worst frame
  // 1.0 mm / 0.15 deg; bounds mean 1.5 mm, worst 3 mm / 0.5 deg. The push moves the box image by ~100 px:
  // the loss must be seen at once (projection error or too few edges), and the tracker left alone stays
  // off by more than 3 cm (measured 7 cm).
  const bool lossOk = lossFrames.size() == 1 && lossFrames[0] >= pushFrame && lossFrames[0] <= pushFrame + 1;
  return vpTutorialCheck(initError.maxMm < 10 && initError.maxDeg < 1.5, "initial P3P pose off 10 mm / 1.5 deg") &
         vpTutorialCheck(beforePush.meanMm < 1.5 && beforePush.maxMm < 3 && beforePush.maxDeg < 0.5,
                         "tracking error before the push above mean 1.5 mm, max 3 mm / 0.5 deg") &
         vpTutorialCheck(lossOk, "the loss was not detected once, at the push") &
         vpTutorialCheck(reinitError.maxMm < 10 && reinitError.maxDeg < 1.5,
                         "re-initialised P3P pose off 10 mm / 1.5 deg") &
         vpTutorialCheck(afterPush.meanMm < 1.5 && afterPush.maxMm < 3 && afterPush.maxDeg < 0.5,
                         "tracking error after the re-initialisation above mean 1.5 mm, max 3 mm / 0.5 deg") &
         vpTutorialCheck(lostUnaidedMm > 30, "the tracker without re-initialisation was not lost by the push");
}
} // namespace

int main(int argc, char **argv)
{
  vpTutorialProgram program("[--frames N]",
                            "Tracks a rendered box with vpMbGenericTracker, initialised and re-initialised after a "
                            "loss by vpPoseGravity from three points; writes tracker-mbt-gravity-*.png.");
  return program.run(argc, argv, "--frames", 100, 10, "number of frames of the sequence", runMbtTutorial);
}
