# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
# vsp-laser-altimeter on a folder holding three images of data/laser_hard and a file with an image
# extension that is not an image, and a truncated JPEG (libjpeg would decode it with a warning only,
# the missing part grey): exit status 0, a failure row "unreadable_image" for each of these two files
# (stderr names them) with no standard deviations (nan), and a plane (status ok) for each of the three
# images with the standard deviations of its altitude (0.5-20 mm; 2.1-2.3 mm measured) and of its roll
# and pitch (0.5-50 mrad; 2.4-5.4 measured), the square roots of the covariance's diagonal.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/images")
foreach(k 000 001 002)
  file(COPY "${DATA}/images/frame_${k}.jpg" DESTINATION "${WORK}/images")
endforeach()
file(WRITE "${WORK}/images/frame_001b.png" "this is not a PNG file\n")
file(COPY "${TRUNCATED}" DESTINATION "${WORK}/images")
execute_process(COMMAND "${PROGRAM}" --camera "${DATA}/camera.xml" --laser "${DATA}/laser.txt"
                        --images "${WORK}/images" --output "${WORK}/results.csv"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "vsp-laser-altimeter exited with status ${status}")
endif()
file(STRINGS "${WORK}/results.csv" rows)
list(LENGTH rows count)
if(NOT count EQUAL 6)
  message(FATAL_ERROR "expected a header and 5 rows, got ${count} lines")
endif()
set(ok 0)
set(unreadable 0)
list(GET rows 0 header)
if(NOT header STREQUAL "frame,image,points,altitude_m,roll_rad,pitch_rad,inliers,status,sd_altitude_m,sd_roll_rad,sd_pitch_rad")
  message(FATAL_ERROR "unexpected header: ${header}")
endif()
set(number "[0-9.]+(e-?[0-9]+)?")
foreach(row ${rows})
  if(row MATCHES "(frame_001b\\.png|truncated_frame\\.jpg),0,nan,nan,nan,0,unreadable_image,nan,nan,nan$")
    math(EXPR unreadable "${unreadable} + 1")
  elseif(row MATCHES "frame_00[0-2]\\.jpg,[0-9]+,[0-9.]+,[-0-9.e]+,[-0-9.e]+,[0-9]+,ok,(${number}),(${number}),(${number})$")
    # The standard deviations: an altitude's in metres, then roll's and pitch's in radians (CMake compares
    # decimal numbers as doubles).
    set(altitude_sd "${CMAKE_MATCH_1}")
    set(roll_sd "${CMAKE_MATCH_3}")
    set(pitch_sd "${CMAKE_MATCH_5}")
    if(altitude_sd LESS 0.0005 OR altitude_sd GREATER 0.02 OR roll_sd LESS 0.0005 OR roll_sd GREATER 0.05 OR
       pitch_sd LESS 0.0005 OR pitch_sd GREATER 0.05)
      message(FATAL_ERROR "standard deviations out of range (altitude 0.5-20 mm, angles 0.5-50 mrad): ${row}")
    endif()
    math(EXPR ok "${ok} + 1")
  endif()
endforeach()
if(NOT ok EQUAL 3 OR NOT unreadable EQUAL 2)
  message(FATAL_ERROR "expected 3 frames with a plane and 2 unreadable images, got ${ok} and ${unreadable}:\n${rows}")
endif()
if(NOT err MATCHES "truncated_frame\\.jpg: cannot be read as an image \\(truncated or corrupt JPEG file")
  message(FATAL_ERROR "stderr does not name the truncated JPEG file")
endif()
message("laser unreadable-image test: 3 planes, 2 failure rows, exit status 0")
