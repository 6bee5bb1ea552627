# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
# Runs COMMAND (arguments joined with '|') on an existing OUTPUT file: the command must exit non-zero
# with a message matching EXPECT, and leave OUTPUT as it was (a failed run never truncates a result
# file) with no temporary file beside it.
string(REPLACE "|" ";" command "${COMMAND}")
file(WRITE "${OUTPUT}" "results of an earlier run\n")
execute_process(COMMAND ${command} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit status: ${status}\nstdout:\n${out}\nstderr:\n${err}")
if(status EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit status")
endif()
if(NOT "${err}" MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected an error message matching '${EXPECT}'")
endif()
file(READ "${OUTPUT}" content)
if(NOT content STREQUAL "results of an earlier run\n")
  message(FATAL_ERROR "${OUTPUT} was changed by the failed run:\n${content}")
endif()
get_filename_component(folder "${OUTPUT}" DIRECTORY)
get_filename_component(name "${OUTPUT}" NAME)
file(GLOB leftovers "${folder}/.${name}.tmp*")
if(leftovers)
  message(FATAL_ERROR "temporary files left: ${leftovers}")
endif()
