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

#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpPlane.h>
#include <visp3/core/vpRGBa.h>

/*!
  \ingroup group_laser_conic
  \brief Simulates what the camera of a camera/circular-laser rig sees over a ground plane.

  The ground plane is the plane Z = 0 of a ground frame g whose pose in the camera frame is cMg
  (the camera must lie on the side Z > 0 or Z < 0, not on the plane). The laser is given as for
  vpLaserConicPose::setLaser(). All random draws use the seed given to setSeed().
*/
class VISP_EXPORT vpLaserConicSimulator
{
public:
  vpLaserConicSimulator();

  //! Camera intrinsics and image size (pixels).
  void setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height);
  //! Laser: full opening angle (rad) and pose of the laser frame in the camera frame.
  void setLaser(double openingAngle, const vpHomogeneousMatrix &cMl);
  //! Pose of the ground frame (ground plane Z = 0) in the camera frame.
  void setGroundPose(const vpHomogeneousMatrix &cMg);
  //! Seed of every random draw.
  void setSeed(unsigned int seed);

  //! The ground plane in the camera frame, unit normal pointing towards the camera (the ground truth).
  vpPlane getGroundPlane() const;

  /*!
    \e n image points of the laser trace, sampled uniformly in the cone angle, exact (no noise),
    keeping only those in front of the camera and inside the image.
    \param roughness : standard deviation (metres) of a random offset of each ground point along the
    ground normal, to mimic a rough ground (0 for a plane).
  */
  std::vector<vpImagePoint> tracePoints(unsigned int n, double roughness = 0.0);
  //! Adds Gaussian noise of standard deviation \e sigma pixels to each coordinate.
  std::vector<vpImagePoint> addNoise(const std::vector<vpImagePoint> &points, double sigma);
  /*!
    Replaces a fraction \e ratio of the points by outliers drawn uniformly in the image and shuffles
    the result; \e isOutlier (optional) receives the flag of each returned point.
  */
  std::vector<vpImagePoint> addOutliers(const std::vector<vpImagePoint> &points, double ratio,
                                        std::vector<bool> *isOutlier = nullptr);

  /*!
    Renders a colour image: a textured ground (vpImageSimulator with \e texture, or a procedural
    texture when empty), the red laser ellipse of \e stripeWidth pixels, Gaussian blur and sensor noise
    (standard deviation \e noise in grey levels).
  */
  void render(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture = vpImage<vpRGBa>(), double stripeWidth = 3.0,
              double noise = 2.0);

private:
  vpCameraParameters m_cam;
  unsigned int m_width, m_height;
  double m_openingAngle;
  vpHomogeneousMatrix m_cMl, m_cMg;
  unsigned int m_seed;
  unsigned long m_draws;
};

#endif
