# Helper included by every tutorial/<name>/CMakeLists.txt.
include_guard(GLOBAL)

# vsp_add_tutorial(<name> LIBS <targets...>)
# Builds tutorial-<name> from tutorial-<name>.cpp of the calling folder, with the shared header
# tutorial/common/vpTutorialCommon.h, the command line and the PNG plots of example/common
# (vsp_text_tools, vsp_plot). When testing is
# enabled, ctest runs it headless as tutorial_<name> (dashes become underscores), writing its pictures
# into <build folder>/output: the program checks its results against the simulation's ground truth
# and exits non-zero when they are off their bounds. Nothing is added when a target is missing (a
# module or a helper left out of the build).
function(vsp_add_tutorial name)
  cmake_parse_arguments(T "" "" "LIBS" ${ARGN})
  foreach(lib ${T_LIBS} vsp_plot vsp_text_tools)
    if(NOT TARGET ${lib})
      message(STATUS "Tutorial ${name} skipped: target ${lib} is not available")
      return()
    endif()
  endforeach()

  set(exe tutorial-${name})
  vsp_add_program(${exe} ${exe}.cpp LIBS ${T_LIBS} vsp_plot vsp_text_tools)
  target_include_directories(${exe} PRIVATE "${PROJECT_SOURCE_DIR}/tutorial/common")

  if(BUILD_TESTING)
    string(REPLACE "-" "_" test_name "tutorial_${name}")
    add_test(NAME ${test_name} COMMAND ${exe} --output "${CMAKE_CURRENT_BINARY_DIR}/output")
    set_tests_properties(${test_name} PROPERTIES TIMEOUT 120)
  endif()
endfunction()
