/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file laser_sim_sensor.h
  \brief What vpLaserConicSimulator does to the light after the scene: optical and motion blur, sensor noise,
  8-bit rounding and clipping, JPEG compression. Internal header.
*/
#ifndef VP_LASER_SIM_SENSOR_H
#define VP_LASER_SIM_SENSOR_H

#include <cstdint>

#include <opencv2/core.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

namespace vsp::laser_sim_sensor
{
/*!
  Optics and motion on a float RGB image (in place): a Gaussian blur of standard deviation \e blur pixels
  (none at 0), then a linear motion blur of \e motionLength pixels in the direction \e motionAngle (radians
  from the u axis; none below 1 pixel).
*/
void applyOptics(cv::Mat &image, double blur, double motionLength, double motionAngle);

/*!
  The sensor: adds Gaussian noise of standard deviation \e noise grey levels to each channel (random bits
  from \e seed), rounds to the nearest grey level and clips to [0, 255]. \e I is resized to the image.
*/
void expose(const cv::Mat &image, double noise, uint64_t seed, vpImage<vpRGBa> &I);

/*!
  JPEG compression at \e quality (1-100) and decompression of \e I in place (OpenCV's codec, 4:2:0 chroma
  as a camera's encoder).
*/
void compressJpeg(vpImage<vpRGBa> &I, int quality);
} // namespace vsp::laser_sim_sensor

#endif
