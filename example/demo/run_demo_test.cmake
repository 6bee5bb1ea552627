# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
# Runs the demo on a copy of the shipped data into a fresh output folder, with --check, and checks
# the exit status and the files it must leave.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/data")
file(COPY "${DATA}/laser_hard" "${DATA}/gravity_sequence" DESTINATION "${WORK}/data")
# The data is read only: its files must be the same afterwards.
function(hash_data result)
  file(GLOB_RECURSE files "${WORK}/data/*")
  set(hashes "")
  foreach(f ${files})
    file(SHA256 "${f}" h)
    string(APPEND hashes "${f} ${h}\n")
  endforeach()
  set(${result} "${hashes}" PARENT_SCOPE)
endfunction()
hash_data(data_hashes)
execute_process(COMMAND "${PROGRAM}" --data "${WORK}/data" --output "${WORK}/output" --check
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(err)
  message("stderr:\n${err}")
endif()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "vsp-demo exited with status ${status}")
endif()
foreach(f laser_results.csv gravity_results.csv laser_altitude.png laser_roll.png laser_pitch.png
          laser_altitude_error.png gravity_translation_error.png gravity_rotation_error.png)
  if(NOT EXISTS "${WORK}/output/${f}")
    message(FATAL_ERROR "vsp-demo did not write ${f}")
  endif()
endforeach()
file(GLOB overlays "${WORK}/output/*overlay*.png")
list(LENGTH overlays overlay_count)
if(overlay_count LESS 3)
  message(FATAL_ERROR "expected overlays, found ${overlay_count}")
endif()

# An output folder inside the data folder is refused before anything is written.
execute_process(COMMAND "${PROGRAM}" --data "${WORK}/data" --output "${WORK}/data/laser_hard/out" --frames 1
                RESULT_VARIABLE refused_status ERROR_VARIABLE refused_err OUTPUT_QUIET)
if(refused_status EQUAL 0 OR NOT refused_err MATCHES "inside the data folder" OR EXISTS "${WORK}/data/laser_hard/out")
  message(FATAL_ERROR "vsp-demo accepted an output folder inside the data (status ${refused_status}): ${refused_err}")
endif()
hash_data(data_hashes_after)
if(NOT data_hashes STREQUAL data_hashes_after)
  message(FATAL_ERROR "the data folder was modified by the demo")
endif()
message("demo test: exit status 0, CSV, plots and ${overlay_count} overlays present")
