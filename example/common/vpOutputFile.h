/*
 * ViSP sensor-aided pose estimation.
 * Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
 */
/*!
  \file vpOutputFile.h
  \brief Output files of the command-line programs: checked before any work, written completely or not at all.
*/
#ifndef VP_OUTPUT_FILE_H
#define VP_OUTPUT_FILE_H

#include <fstream>
#include <functional>
#include <string>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

/*!
  An output file that is never left half written. The content goes to a temporary file in the
  folder of the target, which commit() flushes, closes and renames over the target once complete:
  a run that fails (error, exception, no commit()) removes the temporary file and leaves an
  existing target untouched. A target that exists and is not a regular file (/dev/stdout,
  /dev/full, a FIFO) is written directly, and commit() reports its write errors.

  \code
  std::string error;
  if (!vpOutputFile::checkWritable(path, error)) { std::cerr << error; return EXIT_FAILURE; } // before any work
  vpOutputFile out(path);
  if (!out.open(error)) ...
  out.stream() << "frame,status\n";
  if (!out.commit(error)) { std::cerr << error; return EXIT_FAILURE; }
  \endcode
*/
class vpOutputFile
{
public:
  //! An output file for \e path; nothing is created before open().
  explicit vpOutputFile(const std::string &path);
  //! Removes the temporary file of an uncommitted output.
  ~vpOutputFile();
  vpOutputFile(const vpOutputFile &) = delete;
  vpOutputFile &operator=(const vpOutputFile &) = delete;

  /*!
    Whether \e path can receive an output: not a folder, in an existing folder that can be written
    (or, for an existing special file, writable itself). Call it for every output before any work.
    \return false with \e error naming the path and the reason.
  */
  static bool checkWritable(const std::string &path, std::string &error);

  /*!
    For writers that take a file name (vpImageIo::write(), vpPoseVector::saveYAML()): \e writer
    writes a temporary file of the same extension, whose bytes then go to \e path as by commit().
    \return false, with \e error naming \e path, when the writer returns false or throws, or when
    the copy fails; an existing \e path is then left as it was.
  */
  static bool writeThrough(const std::string &path, const std::function<bool(const std::string &file)> &writer,
                           std::string &error);

  /*!
    vpImageIo::write() of \e I to \e path through writeThrough(): a write that fails (libpng's "Write Error" on a
    full disk, which vpImageIo::write() reports on the console only) returns false with \e error set.
  */
  static bool writeImage(const std::string &path, const vpImage<vpRGBa> &I, std::string &error);

  /*!
    Writes \e text to \e path as open(), the stream and commit() do. \return false with \e error set when any of
    them failed (a full disk: commit() names it).
  */
  static bool writeText(const std::string &path, const std::string &text, std::string &error);

  //! Creates the temporary file (or opens the special file). \return false with \e error set.
  bool open(std::string &error);
  //! The stream to write to (valid after a successful open()).
  std::ostream &stream() { return m_stream; }
  /*!
    Flushes and closes the content, then renames the temporary file over the target.
    \return false, with \e error naming the path, when any write failed (disk full, folder gone);
    the target is then left as it was.
  */
  bool commit(std::string &error);
  //! The target path.
  const std::string &path() const { return m_path; }

private:
  std::string m_path;
  std::string m_temporary; //!< empty for a special file written directly
  std::ofstream m_stream;
  bool m_committed;
};

#endif
