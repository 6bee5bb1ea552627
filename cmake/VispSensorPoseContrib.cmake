# vsp_add_module() for ViSP's own build, where this repository's modules are ViSP contrib modules:
#
#   cmake <visp-source> -DVISP_CONTRIB_MODULES_PATH=<repo>/modules   (scripts/build_as_visp_contrib.sh)
#
# A modules/<name>/CMakeLists.txt includes this file when ViSP's vp_add_module exists, and then makes
# the same vsp_add_module() call as in the standalone build (cmake/VispSensorPoseModule.cmake), so each
# module states its dependencies once. Here the call maps onto ViSP's macros: vp_add_module,
# vp_glob_module_sources, vp_module_include_directories, vp_create_module and vp_add_tests.
#
# ViSP reads each module's CMakeLists.txt twice. In the first pass vp_add_module() only records the
# dependencies and then return()s from the module's CMakeLists.txt; that is why vsp_add_module is a
# macro here (a function would only return from itself) and why the packages are looked for in the
# second pass only.

if(NOT VISP_INITIAL_PASS)
  # The third-party packages of the standalone top-level CMakeLists.txt. Imported targets are local to
  # the directory that finds them, so every module looks for them itself.
  find_package(Eigen3 3.3 REQUIRED NO_MODULE)
  find_package(Ceres 2.0 REQUIRED)
  find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs calib3d)
  find_package(GTest QUIET)
endif()

# vsp_add_module(<name> [VISP_DEPENDS visp_core ...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...] [TEST_LIBS ...])
#   Same arguments as the standalone version. VISP_DEPENDS may name ViSP modules and this repository's
#   modules alike (ViSP orders the modules by these dependencies); TEST_LIBS must be ViSP modules or
#   targets, as vp_add_tests takes them.
macro(vsp_add_module vsp_name)
  cmake_parse_arguments(VSP_MOD "" "" "VISP_DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS;TEST_LIBS" ${ARGN})
  vp_add_module(${vsp_name} ${VSP_MOD_VISP_DEPENDS})  # first pass: leaves the module's CMakeLists here
  vp_glob_module_sources()
  vp_module_include_directories()
  vp_create_module(Eigen3::Eigen ${VSP_MOD_PUBLIC_LIBS})
  # ViSP links with the plain target_link_libraries signature (vp_target_link_libraries): keep to it.
  if(VSP_MOD_PRIVATE_LIBS)
    target_link_libraries(${the_module} LINK_PRIVATE ${VSP_MOD_PRIVATE_LIBS})
  endif()
  _vsp_contrib_module_settings(${the_module})
  if(BUILD_TESTS)
    if(GTest_FOUND)
      # Each test/*.cpp becomes a GoogleTest executable named after its file, one ctest test each.
      vp_add_tests(DEPENDS_ON ${VSP_MOD_TEST_LIBS} GTest::gtest GTest::gtest_main)
      _vsp_contrib_test_settings("${CMAKE_CURRENT_LIST_DIR}")
    else()
      message(STATUS "${the_module}: GoogleTest not found, tests not built")
    endif()
  endif()
endmacro()

function(_vsp_contrib_module_settings target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  # ViSP compiles with -fvisibility=hidden and exports only what is tagged VISP_EXPORT; the solver
  # functions (vpGravitySolvers.h, vpLaserConicSolvers.h, vpRansac.h) are public API too, called by the
  # tests and benchmarks, so export everything as the standalone build does.
  target_compile_options(${target} PRIVATE -fvisibility=default)
endfunction()

# Gives the tests of the module in <module_dir> what the standalone build gives them.
function(_vsp_contrib_test_settings module_dir)
  get_filename_component(repo_dir "${module_dir}/../.." ABSOLUTE)
  file(GLOB test_sources "${module_dir}/test/*.cpp")
  foreach(test_source ${test_sources})
    get_filename_component(test_target "${test_source}" NAME_WE)
    if(TARGET ${test_target})
      target_compile_definitions(${test_target} PRIVATE VSP_DATA_DIR="${repo_dir}/data")
      target_compile_features(${test_target} PRIVATE cxx_std_17)
    endif()
  endforeach()
endfunction()
