# vsp_add_tutorial(<name> LIBS <targets>...), used by every tutorial/<name>/CMakeLists.txt: the program
# tutorial-<name> from tutorial-<name>.cpp of the calling folder, linked with <targets>,
# VispSensorPose::vsp_tutorial_common (the tutorial frame, installed with the package) and the ViSP
# libraries the caller found (VISP_LIBRARIES, VISP_INCLUDE_DIRS). When testing is enabled, ctest runs it
# headless as tutorial_<name> (dashes become underscores), writing its pictures into
# <build folder>/output: the program checks its results against the simulation's ground truth and
# exits non-zero when they are off their bounds.
#
# Included by the repository's CMakeLists.txt and by the installed VispSensorPoseConfig.cmake, so that a
# tutorial folder builds the same way in the tree and copied out of it.
include_guard(GLOBAL)

function(vsp_add_tutorial name)
  cmake_parse_arguments(T "" "" "LIBS" ${ARGN})
  set(exe tutorial-${name})
  add_executable(${exe} ${exe}.cpp)
  target_compile_features(${exe} PRIVATE cxx_std_17)
  target_include_directories(${exe} SYSTEM PRIVATE ${VISP_INCLUDE_DIRS})
  target_link_libraries(${exe} PRIVATE ${T_LIBS} VispSensorPose::vsp_tutorial_common ${VISP_LIBRARIES})
  if(COMMAND vsp_set_warnings) # in the repository's build: its warning flags
    vsp_set_warnings(${exe})
  endif()
  if(BUILD_TESTING)
    string(REPLACE "-" "_" test_name "tutorial_${name}")
    add_test(NAME ${test_name} COMMAND ${exe} --output "${CMAKE_CURRENT_BINARY_DIR}/output")
    set_tests_properties(${test_name} PROPERTIES TIMEOUT 120)
  endif()
endfunction()
