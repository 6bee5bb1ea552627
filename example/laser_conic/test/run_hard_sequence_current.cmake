# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# Regenerates the hard sequence (make-laser-sequence --hard --quality 80) into WORK and checks that what
# data/laser_hard ships is what the programs give today: the same images and ground truth, and the same
# conditions.csv, whose last columns are the default detector's coverage and accuracy on each frame. Not
# compared: laser.txt, the output of a calibration (Ceres) whose last digits depend on the machine's BLAS.
# Then, on the regenerated conditions.csv, that the default detector finds at least 95 % of the ring where
# the stripe is 3 times the noise or more (detector_coverage_3sigma) on every frame with a laser.
#   cmake -DPROGRAM=<make-laser-sequence> -DDATA=<data/laser_hard> -DWORK=<folder> -P run_hard_sequence_current.cmake
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${PROGRAM}" --hard --quality 80 --output "${WORK}" RESULT_VARIABLE status
                OUTPUT_QUIET ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "make-laser-sequence failed (${status}): ${errors}")
endif()
file(GLOB shipped RELATIVE "${DATA}" "${DATA}/images/*.jpg")
list(LENGTH shipped count)
if(count EQUAL 0)
  message(FATAL_ERROR "no image in ${DATA}/images")
endif()
set(stale "")
foreach(name conditions.csv groundtruth.csv camera.xml ${shipped})
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${DATA}/${name}" "${WORK}/${name}" RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    list(APPEND stale "${name}")
  endif()
endforeach()
# The detector's coverage of the ring at 3 sigma (detector_coverage_3sigma) on every frame with a laser ("nan" without).
file(STRINGS "${WORK}/conditions.csv" rows)
list(REMOVE_AT rows 0)
set(short "")
foreach(row ${rows})
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 0 frame)
  list(GET fields 2 condition)
  list(GET fields 6 coverage)
  if(NOT coverage STREQUAL "nan" AND coverage LESS 0.95)
    list(APPEND short "frame ${frame} (${condition}) ${coverage}")
  endif()
endforeach()
if(short)
  message(FATAL_ERROR "the default detector finds less than 95 % of the ring at 3 sigma on: ${short}")
endif()
if(stale)
  message(FATAL_ERROR "data/laser_hard differs from what make-laser-sequence --hard --quality 80 writes today: "
                      "${stale} (regenerate it and keep its laser.txt, see data/laser_hard/README.md)")
endif()
message(STATUS "data/laser_hard is current: conditions.csv, groundtruth.csv, camera.xml and ${count} images")
