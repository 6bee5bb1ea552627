# Installs the build tree into a scratch prefix, then configures, builds and runs a separate
# project that does find_package(VispSensorPose) against that prefix.
foreach(var VSP_BUILD_DIR VSP_CONSUMER_SOURCE VSP_WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is not set")
  endif()
endforeach()
if(NOT VSP_BUILD_TYPE)
  set(VSP_BUILD_TYPE Release)
endif()
set(prefix "${VSP_WORK_DIR}/prefix")
set(build "${VSP_WORK_DIR}/build")
file(REMOVE_RECURSE "${VSP_WORK_DIR}")

function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "step failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

run_step(${CMAKE_COMMAND} --install "${VSP_BUILD_DIR}" --prefix "${prefix}" --config ${VSP_BUILD_TYPE})
run_step(${CMAKE_COMMAND} -S "${VSP_CONSUMER_SOURCE}" -B "${build}" -DCMAKE_PREFIX_PATH=${prefix}
         -DCMAKE_BUILD_TYPE=${VSP_BUILD_TYPE} "-DCMAKE_CXX_FLAGS=${VSP_CONSUMER_FLAGS}"
         "-DCMAKE_EXE_LINKER_FLAGS=${VSP_CONSUMER_FLAGS}")
run_step(${CMAKE_COMMAND} --build "${build}" --config ${VSP_BUILD_TYPE})
run_step("${build}/vsp_consumer")
