# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# make-laser-sequence --hard into a folder where conditions.csv cannot be written (a folder of that name is in
# its way): the program must exit with a failure and name the file, not report the sequence written.
#   cmake -DPROGRAM=<make-laser-sequence> -DWORK=<folder> -P run_conditions_unwritable.cmake
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/conditions.csv")
execute_process(COMMAND "${PROGRAM}" --hard --frames 1 --output "${WORK}" RESULT_VARIABLE status
                OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(status EQUAL 0)
  message(FATAL_ERROR "make-laser-sequence exited 0 although conditions.csv could not be written: ${output}")
endif()
if(NOT errors MATCHES "Cannot write .*conditions.csv")
  message(FATAL_ERROR "make-laser-sequence failed without naming conditions.csv: ${errors}")
endif()
if(output MATCHES "Wrote ")
  message(FATAL_ERROR "make-laser-sequence reported the sequence written: ${output}")
endif()
message(STATUS "make-laser-sequence refuses an unwritable conditions.csv: ${errors}")
