/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpLaserConicImageMember.h
  \brief An image held by a class of the module, safe to copy when empty.
*/
#ifndef VP_LASER_CONIC_IMAGE_MEMBER_H
#define VP_LASER_CONIC_IMAGE_MEMBER_H

#include <visp3/core/vpImage.h>

/*!
  \class vpLaserConicImageMember
  \ingroup group_laser_conic
  \brief A vpImage kept as a member of a copyable class (the detector's mask, the simulator's texture).

  ViSP 3.5 copies a vpImage with memcpy() even when it is empty, from a null pointer (undefined
  behaviour): an empty image is not copied here, the copy is left empty.
*/
template <class Type> struct vpLaserConicImageMember
{
  vpImage<Type> image;                 //!< the image
  vpLaserConicImageMember() = default; //!< empty image
  //! Copies \e other's image when it has pixels.
  vpLaserConicImageMember(const vpLaserConicImageMember &other) : image() { copyFrom(other); }
  //! Copies \e other's image when it has pixels, else empties this one.
  vpLaserConicImageMember &operator=(const vpLaserConicImageMember &other)
  {
    if (this != &other)
      copyFrom(other);
    return *this;
  }
  //! Copies \e other's image when it has pixels, else empties this one.
  void copyFrom(const vpLaserConicImageMember &other)
  {
    if (other.image.getSize() == 0)
      image = vpImage<Type>(); // moved in, nothing copied (vpImage::destroy() would keep the old size)
    else
      image = other.image;
  }
};

#endif
