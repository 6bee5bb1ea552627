/* ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE. */
/*
  Display helpers of vpPoseGravity, like vpPose::display(): display() goes through vpDisplay (a
  window must be attached), draw() writes the same frame into the pixels with vpImageDraw.
*/
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/pose_gravity/vpPoseGravity.h>

void vpPoseGravity::display(vpImage<unsigned char> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                            double size, const vpColor &color, unsigned int thickness)
{
  vpDisplay::displayFrame(I, cMo, cam, size, color, thickness);
}

void vpPoseGravity::display(vpImage<vpRGBa> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                            double size, const vpColor &color, unsigned int thickness)
{
  vpDisplay::displayFrame(I, cMo, cam, size, color, thickness);
}

void vpPoseGravity::draw(vpImage<unsigned char> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                         double size, unsigned char grey, unsigned int thickness)
{
  vpImageDraw::drawFrame(I, cMo, cam, size, grey, thickness);
}

void vpPoseGravity::draw(vpImage<vpRGBa> &I, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam, double size,
                         const vpColor &color, unsigned int thickness)
{
  vpImageDraw::drawFrame(I, cMo, cam, size, color, thickness);
}
