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

#include <random>
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
  vpLaserConicPose::setLaser(): full opening angle A and pose cMl of the laser frame, whose origin is
  the cone apex and whose +Z axis is the cone axis. A ray of the cone has the direction
  \f$ {}^c\mathbf{R}_l (\sin\frac{A}{2}\cos\gamma, \sin\frac{A}{2}\sin\gamma, \cos\frac{A}{2})^T \f$ from
  the apex; only the forward half-line lights the ground.

  Image points follow ViSP's conventions (vpMeterPixelConversion with the model of the given
  vpCameraParameters; the rest of the module assumes a model without distortion).

  Errors are reported with vpLaserConicException (declared in vpLaserConicPose.h), a vpException.

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
  //! Simulator with no camera, a 34 degree laser at the camera centre, ground 1 m in front, seed 0.
  vpLaserConicSimulator();

  /*!
    Camera intrinsics and image size (pixels).
    \exception vpLaserConicException::badCameraError when a focal length is not positive or finite or the
    size is zero.
  */
  void setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height);
  /*!
    Laser: full opening angle (rad) and pose of the laser frame in the camera frame.
    \exception vpLaserConicException::badLaserError when the angle is outside (0, pi) or the pose is
    not a finite rigid transformation.
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
    Renders a colour image of the camera's view.

    -# The ground: \e texture mapped by vpImageSimulator on a square of the ground plane that covers the
       camera's footprint (up to 100 altitudes wide when the horizon is in view), so the texture is not
       attached to fixed ground coordinates from one pose to the next (the laser methods do not use it).
       When \e texture is empty, a procedural dark tiled floor that depends on the seed only is used;
       what lies beyond the square is dark grey.
    -# The laser: red light added along the exact image of the trace with a Gaussian profile across the
       curve whose full width at half maximum is \e stripeWidth pixels.
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

private:
  void checkCamera() const;
  //! Ground point (camera frame) hit by the cone ray of angle gamma; false when the forward ray misses the ground.
  bool groundPoint(double gamma, double P[3]) const;
  //! Projects a camera-frame point; false when it is not in front of the camera.
  bool project(const double P[3], double &u, double &v) const;
  //! Renders the textured ground into I (resized to the image size).
  void renderGround(vpImage<vpRGBa> &I, const vpImage<vpRGBa> &texture);
  //! Squared distance of each pixel within \e radius of the exact image trace to that trace (+inf elsewhere).
  void traceDistanceMap(float radius, std::vector<float> &dist2) const;
  //! Square of the ground (centre cx, cy and half side in ground coordinates) covering the camera's view.
  void groundFootprint(double &cx, double &cy, double &half) const;
  //! Dark tiled floor texture drawn from the seed (cached).
  const vpImage<vpRGBa> &proceduralTexture();

  vpCameraParameters m_cam;
  unsigned int m_width, m_height;
  double m_openingAngle;
  vpHomogeneousMatrix m_cMl, m_cMg;
  unsigned int m_seed;
  std::mt19937 m_rng;
  vpImage<vpRGBa> m_texture;
  unsigned int m_textureSeed;
};

#endif
