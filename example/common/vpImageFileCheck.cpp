/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpImageFileCheck.h"

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <jpeglib.h>

#include <visp3/core/vpException.h>
#include <visp3/io/vpImageIo.h>

namespace
{
//! libjpeg error manager that returns to the caller (longjmp) on an error and counts, silently, the warnings.
struct CheckingErrorManager
{
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void exitOnError(j_common_ptr info)
{
  CheckingErrorManager *manager = reinterpret_cast<CheckingErrorManager *>(info->err);
  (*info->err->format_message)(info, manager->message);
  std::longjmp(manager->jump, 1);
}

void keepWarning(j_common_ptr info, int level)
{
  // Level -1 is a warning (corrupt or truncated data); the first one is kept as the reason.
  if (level < 0) {
    CheckingErrorManager *manager = reinterpret_cast<CheckingErrorManager *>(info->err);
    if (info->err->num_warnings == 0)
      (*info->err->format_message)(info, manager->message);
    ++info->err->num_warnings;
  }
}

bool hasJpegExtension(const std::string &path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".jpg" || ext == ".jpeg";
}

//! Decodes the opened file at 1/8 scale; false with \e why on an error or a warning.
bool decodeChecked(std::FILE *file, std::string &why)
{
  jpeg_decompress_struct info;
  CheckingErrorManager manager;
  info.err = jpeg_std_error(&manager.base);
  manager.base.error_exit = exitOnError;
  manager.base.emit_message = keepWarning;
  manager.message[0] = '\0';
  std::vector<JSAMPLE> row;
  if (setjmp(manager.jump)) {
    jpeg_destroy_decompress(&info);
    why = std::string("corrupt JPEG file (") + manager.message + ")";
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file);
  jpeg_read_header(&info, TRUE);
  info.scale_num = 1;
  info.scale_denom = 8;
  jpeg_start_decompress(&info);
  row.resize(static_cast<size_t>(info.output_width) * static_cast<size_t>(info.output_components));
  JSAMPROW rows[1] = {row.data()};
  while (info.output_scanline < info.output_height)
    jpeg_read_scanlines(&info, rows, 1);
  jpeg_finish_decompress(&info);
  const bool clean = manager.base.num_warnings == 0;
  jpeg_destroy_decompress(&info);
  if (!clean)
    why = std::string("truncated or corrupt JPEG file (") + manager.message + ")";
  return clean;
}
} // namespace

bool vpImageFileCheck::checkJpeg(const std::string &path, std::string &why)
{
  std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) {
    why = "cannot be opened";
    return false;
  }
  return decodeChecked(file.get(), why);
}

bool vpImageFileCheck::read(const std::string &path, vpImage<vpRGBa> &I, std::string &why)
{
  if (hasJpegExtension(path) && !checkJpeg(path, why))
    return false;
  why = "empty image";
  try {
    vpImageIo::read(I, path);
  } catch (const vpException &e) {
    why = e.getStringMessage();
    return false;
  }
  return I.getSize() > 0; // a file that is not an image may also read as an empty image
}
