# vsp_add_module(): declares a module of this repository, in both builds of it, from one call in
# modules/<name>/CMakeLists.txt (which includes this file first):
#
#   vsp_add_module(<name> [VISP_DEPENDS visp_core ...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...] [TEST_LIBS ...])
#
# - Library visp_<name> from modules/<name>/src/**.cpp; public headers modules/<name>/include/visp3/<name>/*.h.
#   VISP_DEPENDS lists the ViSP modules and this repository's modules whose headers the module's code
#   includes (and nothing else); PUBLIC_LIBS / PRIVATE_LIBS other libraries (Ceres, OpenCV); TEST_LIBS
#   what the tests include beyond that (ViSP modules or targets).
# - Private headers are the .h files of modules/<name>/src/ and its subfolders (never installed, seen
#   only by the module's sources); private files are named in snake_case, public ones vpClassName.h
#   (doc/structure.md).
# - Every modules/<name>/test/*.cpp is a GoogleTest executable <name>-<file> whose cases ctest runs
#   (as <name>-<file>.<Suite>.<Case>), with the same names in both builds.
# - Symbols are hidden unless tagged VISP_EXPORT, as in ViSP's own build: a public class or free
#   function without it fails to link in the standalone build already.
#
# Standalone build (the top-level CMakeLists.txt, against the installed ViSP): an ordinary library,
# exported as VispSensorPose::visp_<name>. Inside ViSP's own build (a contrib module,
# -DVISP_CONTRIB_MODULES_PATH=<repo>/modules, see doc/contrib_build.md) the same call maps onto ViSP's
# vp_add_module, vp_glob_module_sources, vp_module_include_directories and vp_create_module. ViSP reads a
# module's CMakeLists.txt twice; in the first pass vp_add_module() records the dependencies and
# return()s from that file, which is why vsp_add_module is a macro (a function would only return from
# itself) and why the third-party packages are looked for in the second pass only.

get_filename_component(VSP_REPO_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
find_package(GTest QUIET)
if(COMMAND vp_add_module AND NOT VISP_INITIAL_PASS)
  # Inside ViSP's build, the packages of the standalone top-level CMakeLists.txt. Imported targets are
  # local to the directory that finds them: every module includes this file and looks for them itself.
  find_package(Eigen3 3.3 REQUIRED NO_MODULE)
  find_package(Ceres 2.0 REQUIRED)
  find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc calib3d)
endif()

function(vsp_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-deprecated-copy)
  if(VSP_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

macro(vsp_add_module vsp_name)
  cmake_parse_arguments(VSP_MOD "" "" "VISP_DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS;TEST_LIBS" ${ARGN})
  if(COMMAND vp_add_module)
    vp_add_module(${vsp_name} ${VSP_MOD_VISP_DEPENDS}) # first pass: leaves the module's CMakeLists here
    vp_glob_module_sources()
    vp_module_include_directories()
    vp_create_module(Eigen3::Eigen ${VSP_MOD_PUBLIC_LIBS})
    # ViSP links its modules with the plain target_link_libraries signature: keep to it.
    if(VSP_MOD_PRIVATE_LIBS)
      target_link_libraries(${the_module} LINK_PRIVATE ${VSP_MOD_PRIVATE_LIBS})
    endif()
    target_compile_features(${the_module} PUBLIC cxx_std_17)
    set(vsp_module_test_libs ${the_module} ${VISP_MODULE_${the_module}_DEPS} ${VSP_MOD_TEST_LIBS})
  else()
    _vsp_add_standalone_module(${vsp_name} VISP_DEPENDS ${VSP_MOD_VISP_DEPENDS}
                               PUBLIC_LIBS ${VSP_MOD_PUBLIC_LIBS} PRIVATE_LIBS ${VSP_MOD_PRIVATE_LIBS})
    set(vsp_module_test_libs visp_${vsp_name} ${VSP_MOD_TEST_LIBS})
  endif()
  if(BUILD_TESTING OR BUILD_TESTS)
    file(GLOB vsp_module_tests CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/test/*.cpp")
    foreach(vsp_test_src ${vsp_module_tests})
      get_filename_component(vsp_test_name ${vsp_test_src} NAME_WE)
      vsp_add_gtest(${vsp_name}-${vsp_test_name} ${vsp_test_src} LIBS ${vsp_module_test_libs})
      if(COMMAND vp_target_include_modules)
        vp_target_include_modules(${vsp_name}-${vsp_test_name} ${vsp_module_test_libs})
      endif()
    endforeach()
  endif()
endmacro()

function(_vsp_add_standalone_module name)
  cmake_parse_arguments(M "" "" "VISP_DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(target visp_${name})
  # Recursive, as ViSP's vp_glob_module_sources: a module may group its private files in src/ subfolders.
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp")
  file(GLOB hdrs CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/include/visp3/${name}/*.h")
  file(GLOB_RECURSE private_hdrs CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/src/*.h")
  add_library(${target} ${srcs} ${hdrs} ${private_hdrs})
  add_library(VispSensorPose::${target} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_include_directories(${target} SYSTEM PUBLIC "$<BUILD_INTERFACE:${VISP_INCLUDE_DIRS}>")
  target_include_directories(${target} PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}/src")
  target_link_libraries(${target} PUBLIC ${M_VISP_DEPENDS} Eigen3::Eigen ${M_PUBLIC_LIBS}
                                  PRIVATE ${M_PRIVATE_LIBS})
  set_target_properties(${target} PROPERTIES
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    EXPORT_NAME ${target}
    CXX_VISIBILITY_PRESET hidden
    # Installed modules find each other (e.g. visp_robust) next to themselves: a RUNPATH on the
    # consumer's executable does not apply to indirect dependencies.
    INSTALL_RPATH "\$ORIGIN")
  # A symbol the library uses and nothing defines fails its link, not the first program that calls it:
  # determinant() of Eigen without <Eigen/LU> left one that only a test's run found. Not with the sanitizers,
  # whose runtime the programs bring.
  if(BUILD_SHARED_LIBS AND NOT VSP_ENABLE_SANITIZERS AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND NOT APPLE)
    target_link_options(${target} PRIVATE "LINKER:--no-undefined")
  endif()
  vsp_set_warnings(${target})

  install(TARGETS ${target} EXPORT VispSensorPoseTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES ${hdrs} DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/visp3/${name}")
  set_property(GLOBAL APPEND PROPERTY VSP_MODULE_TARGETS ${target})
endfunction()

# vsp_add_gtest(<exe> <sources...> [LIBS ...]): a GoogleTest executable whose cases ctest runs.
function(vsp_add_gtest exe)
  cmake_parse_arguments(T "" "" "LIBS" ${ARGN})
  if(NOT TARGET GTest::gtest)
    message(FATAL_ERROR "GoogleTest (libgtest-dev) is required to build the tests")
  endif()
  add_executable(${exe} ${T_UNPARSED_ARGUMENTS})
  target_link_libraries(${exe} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${exe} PRIVATE VSP_DATA_DIR="${VSP_REPO_DIR}/data")
  target_compile_features(${exe} PRIVATE cxx_std_17)
  vsp_set_warnings(${exe})
  if(VSP_TESTS_PER_EXECUTABLE)
    # An executable listed in VSP_GTEST_SHARDS as <exe>=<count> is split into that many ctest tests, each running
    # a share of its cases (GoogleTest's GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX): the longest one would otherwise
    # run alone on one core at the end of the suite.
    set(shards 1)
    foreach(item IN LISTS VSP_GTEST_SHARDS)
      if(item MATCHES "^${exe}=([0-9]+)$")
        set(shards ${CMAKE_MATCH_1})
      endif()
    endforeach()
    if(shards GREATER 1)
      math(EXPR last "${shards} - 1")
      foreach(index RANGE ${last})
        add_test(NAME ${exe}-shard${index} COMMAND ${exe})
        set_tests_properties(${exe}-shard${index} PROPERTIES TIMEOUT 1800 ENVIRONMENT
                             "GTEST_TOTAL_SHARDS=${shards};GTEST_SHARD_INDEX=${index}")
      endforeach()
    else()
      add_test(NAME ${exe} COMMAND ${exe})
      set_tests_properties(${exe} PROPERTIES TIMEOUT 1800)
    endif()
  else()
    include(GoogleTest)
    gtest_discover_tests(${exe} TEST_PREFIX "${exe}." DISCOVERY_TIMEOUT 120 PROPERTIES TIMEOUT 600)
  endif()
endfunction()
