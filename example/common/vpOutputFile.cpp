/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
#include "vpOutputFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <random>

#include <visp3/core/vpException.h>
#include <visp3/io/vpImageIo.h>

#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
//! The folder an output path lies in ("." for a bare file name).
fs::path folderOf(const std::string &path)
{
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

//! True when \e path exists and is neither a regular file nor a folder (a device, a FIFO).
bool isSpecialFile(const std::string &path)
{
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  return !ec && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
}
} // namespace

vpOutputFile::vpOutputFile(const std::string &path) : m_path(path), m_temporary(), m_stream(), m_committed(false) {}

vpOutputFile::~vpOutputFile()
{
  if (m_stream.is_open())
    m_stream.close();
  if (!m_committed && !m_temporary.empty())
    std::remove(m_temporary.c_str());
}

bool vpOutputFile::checkWritable(const std::string &path, std::string &error)
{
  if (path.empty()) {
    error = "an output path is empty";
    return false;
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = path + ": is a folder, not an output file";
    return false;
  }
  if (isSpecialFile(path)) {
    if (access(path.c_str(), W_OK) != 0) {
      error = path + ": cannot be written (" + std::strerror(errno) + ")";
      return false;
    }
    return true;
  }
  const fs::path folder = folderOf(path);
  if (!fs::is_directory(folder, ec)) {
    error = path + ": the folder '" + folder.string() + "' does not exist";
    return false;
  }
  if (access(folder.c_str(), W_OK) != 0) {
    error = path + ": the folder '" + folder.string() + "' cannot be written (" + std::strerror(errno) + ")";
    return false;
  }
  if (fs::exists(path, ec) && access(path.c_str(), W_OK) != 0) {
    error = path + ": cannot be overwritten (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

bool vpOutputFile::open(std::string &error)
{
  if (!checkWritable(m_path, error))
    return false;
  if (isSpecialFile(m_path)) {
    m_temporary.clear();
    m_stream.open(m_path, std::ios::out | std::ios::binary);
  } else {
    // A name of its own in the target's folder, so that the rename stays on one file system.
    std::random_device device;
    const fs::path target(m_path);
    for (int attempt = 0; attempt < 16 && !m_stream.is_open(); ++attempt) {
      const fs::path candidate =
          folderOf(m_path) / ("." + target.filename().string() + ".tmp" + std::to_string(device() % 1000000u));
      std::error_code ec;
      if (fs::exists(candidate, ec))
        continue;
      m_temporary = candidate.string();
      m_stream.open(m_temporary, std::ios::out | std::ios::binary | std::ios::trunc);
    }
  }
  if (!m_stream.is_open()) {
    error = m_path + ": cannot be written (" + std::strerror(errno) + ")";
    m_temporary.clear();
    return false;
  }
  return true;
}

bool vpOutputFile::commit(std::string &error)
{
  if (!m_stream.is_open()) {
    error = m_path + ": not open";
    return false;
  }
  m_stream.flush();
  const bool written = static_cast<bool>(m_stream);
  m_stream.close();
  if (!written || m_stream.fail()) {
    error = m_path + ": write error (disk full, or the file system refused the data)";
    return false;
  }
  if (!m_temporary.empty() && std::rename(m_temporary.c_str(), m_path.c_str()) != 0) {
    error = m_path + ": cannot be replaced (" + std::strerror(errno) + ")";
    return false;
  }
  m_committed = true;
  return true;
}

bool vpOutputFile::writeImage(const std::string &path, const vpImage<vpRGBa> &I, std::string &error)
{
  return writeThrough(
      path,
      [&I](const std::string &scratch) {
        vpImageIo::write(I, scratch);
        return true;
      },
      error);
}

bool vpOutputFile::writeText(const std::string &path, const std::string &text, std::string &error)
{
  vpOutputFile out(path);
  if (!out.open(error))
    return false;
  out.stream() << text; // a failed write is commit()'s to report, with its message
  return out.commit(error);
}

bool vpOutputFile::writeThrough(const std::string &path, const std::function<bool(const std::string &file)> &writer,
                                std::string &error)
{
  if (!checkWritable(path, error))
    return false;
  std::error_code ec;
  std::random_device device;
  const fs::path scratch = fs::temp_directory_path(ec) / ("vsp-output-" + std::to_string(device() % 100000000u) +
                                                          fs::path(path).extension().string());
  bool written = false;
  try {
    written = writer(scratch.string());
  } catch (const vpException &e) {
    error = path + ": " + e.getStringMessage();
    fs::remove(scratch, ec);
    return false;
  }
  std::ifstream in(scratch, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  fs::remove(scratch, ec);
  if (!written || bytes.empty()) {
    error = path + ": could not be written";
    return false;
  }
  vpOutputFile out(path);
  if (!out.open(error))
    return false;
  out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return out.commit(error);
}
