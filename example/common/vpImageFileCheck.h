/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpImageFileCheck.h
  \brief Images read whole or refused: a truncated or corrupt file is an error naming it, never a partly grey image.
*/
#ifndef VP_IMAGE_FILE_CHECK_H
#define VP_IMAGE_FILE_CHECK_H

#include <string>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

namespace vpImageFileCheck
{
/*!
  Whether the JPEG file \e path decodes without error nor warning. libjpeg decodes a truncated or
  corrupt file with a warning only ("Premature end of JPEG file", "Corrupt JPEG data"), filling
  the missing part with grey; here every warning is an error. The check decodes the entropy-coded
  data at 1/8 scale (each block's DC term), which reads every byte of it at a fraction of a full
  decoding's cost. \return false with \e why saying what is wrong.
*/
bool checkJpeg(const std::string &path, std::string &why);

/*!
  Reads an image with vpImageIo::read(), refusing a JPEG file that checkJpeg() refuses, a file that
  reads as an empty image and one vpImageIo cannot read. \return false with \e why set (the file
  name is not repeated in it).
*/
bool read(const std::string &path, vpImage<vpRGBa> &I, std::string &why);
} // namespace vpImageFileCheck

#endif
