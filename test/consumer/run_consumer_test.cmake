# Tests of the installed package, run by ctest in steps (-DSTEP=...):
#   install     installs the build tree into ${VSP_WORK_DIR}/prefix (the fixture of the other steps)
#   consumer    configures, builds and runs test/consumer (find_package(VispSensorPose)) against it
#   tutorial    copies ${VSP_TUTORIAL_SOURCE} (a tutorial folder) out of the repository, builds it alone
#               against the prefix and runs it headless: its checks against the ground truth must pass
#   programs    copies the prefix elsewhere (an installed tree must be relocatable) and runs the installed
#               programs from there: vsp-demo finds its data relative to itself, --help names no path of
#               the build machine, the CLIs find their libraries
foreach(var VSP_WORK_DIR STEP)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is not set")
  endif()
endforeach()
if(NOT VSP_BUILD_TYPE)
  set(VSP_BUILD_TYPE Release)
endif()
set(prefix "${VSP_WORK_DIR}/prefix")

function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
  set(step_output "${out}${err}" PARENT_SCOPE)
endfunction()

# A separate project configured and built against the prefix, in ${build}.
function(build_against_prefix source build)
  file(REMOVE_RECURSE "${build}")
  run_step(${CMAKE_COMMAND} -S "${source}" -B "${build}" -DCMAKE_PREFIX_PATH=${prefix}
           -DCMAKE_BUILD_TYPE=${VSP_BUILD_TYPE} "-DCMAKE_CXX_FLAGS=${VSP_CONSUMER_FLAGS}"
           "-DCMAKE_EXE_LINKER_FLAGS=${VSP_CONSUMER_FLAGS}")
  run_step(${CMAKE_COMMAND} --build "${build}" --config ${VSP_BUILD_TYPE})
endfunction()

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE "${prefix}")
  run_step(${CMAKE_COMMAND} --install "${VSP_BUILD_DIR}" --prefix "${prefix}" --config ${VSP_BUILD_TYPE})
  string(REPLACE "|" ";" expected "${VSP_EXPECTED_FILES}")
  foreach(f ${expected})
    if(NOT EXISTS "${prefix}/${f}")
      message(FATAL_ERROR "cmake --install did not install ${f}")
    endif()
  endforeach()

elseif(STEP STREQUAL "consumer")
  build_against_prefix("${VSP_CONSUMER_SOURCE}" "${VSP_WORK_DIR}/consumer-build")
  run_step("${VSP_WORK_DIR}/consumer-build/vsp_consumer")

elseif(STEP STREQUAL "tutorial")
  get_filename_component(name "${VSP_TUTORIAL_SOURCE}" NAME)
  set(copy "${VSP_WORK_DIR}/copied/${name}")
  file(REMOVE_RECURSE "${VSP_WORK_DIR}/copied")
  file(COPY "${VSP_TUTORIAL_SOURCE}" DESTINATION "${VSP_WORK_DIR}/copied")
  build_against_prefix("${copy}" "${copy}/build")
  run_step("${copy}/build/tutorial-${name}" --output "${copy}/output")
  message(STATUS "tutorial-${name} built out of the tree against ${prefix} and passed its checks")

elseif(STEP STREQUAL "programs")
  set(moved "${VSP_WORK_DIR}/moved")
  file(REMOVE_RECURSE "${moved}")
  file(COPY "${prefix}/" DESTINATION "${moved}")
  run_step("${moved}/bin/vsp-demo" --help)
  if(NOT step_output MATCHES "${moved}/bin/../share/VispSensorPose/data|${moved}/share/VispSensorPose/data")
    message(FATAL_ERROR "vsp-demo --help does not name the data next to the moved program:\n${step_output}")
  endif()
  string(FIND "${step_output}" "${VSP_SOURCE_DIR}/data" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "vsp-demo --help names the data of the source tree (${VSP_SOURCE_DIR}/data):\n${step_output}")
  endif()
  run_step("${moved}/bin/vsp-demo" --frames 3 --output "${VSP_WORK_DIR}/demo-output")
  if(NOT step_output MATCHES "Summary of the laser sequence.*Summary of the gravity-aided pose sequence")
    message(FATAL_ERROR "the installed vsp-demo printed no summary:\n${step_output}")
  endif()
  set(data "${moved}/share/VispSensorPose/data/gravity_sequence")
  run_step("${moved}/bin/vsp-gravity-pose" --input "${data}/points.csv" --output "${VSP_WORK_DIR}/poses.csv")
  run_step("${moved}/bin/vsp-compare-poses" --estimate "${VSP_WORK_DIR}/poses.csv" --truth "${data}/groundtruth.csv"
           --max-median-translation 0.01 --max-median-rotation-deg 1.0)
  message(STATUS "installed programs run from a moved prefix")

else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()
