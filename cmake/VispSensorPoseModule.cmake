# Helpers that declare a module of this project in its standalone build.
#
#   vsp_add_module(<name> [VISP_DEPENDS visp_core ...] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
#     Library target visp_<name> from modules/<name>/src/*.cpp, public headers from
#     modules/<name>/include/visp3/<name>/*.h, exported as VispSensorPose::visp_<name>.
#     Every modules/<name>/test/*.cpp becomes a GoogleTest executable <name>-<file> run by ctest.
#
# The same modules/<name>/CMakeLists.txt also works inside ViSP's own build as a contrib module:
# there `vp_add_module` exists and the module uses ViSP's macros instead of these.

find_package(GTest QUIET)

# Directory of the shared test helpers (simulated camera, random poses) usable by every module's tests.
set(VSP_TEST_COMMON_DIR "${CMAKE_CURRENT_LIST_DIR}/../test/common" CACHE INTERNAL "")

function(vsp_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wno-deprecated-copy)
  if(VSP_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

function(vsp_add_module name)
  cmake_parse_arguments(M "" "" "VISP_DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS;TEST_LIBS" ${ARGN})
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
    # Installed modules find each other (e.g. visp_robust) next to themselves: a RUNPATH on the
    # consumer's executable does not apply to indirect dependencies.
    INSTALL_RPATH "\$ORIGIN")
  vsp_set_warnings(${target})

  install(TARGETS ${target} EXPORT VispSensorPoseTargets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES ${hdrs} DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/visp3/${name}")
  set_property(GLOBAL APPEND PROPERTY VSP_MODULE_TARGETS ${target})

  if(BUILD_TESTING)
    file(GLOB tests CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/test/*.cpp")
    foreach(test_src ${tests})
      get_filename_component(test_name ${test_src} NAME_WE)
      vsp_add_gtest(${name}-${test_name} ${test_src} LIBS ${target} ${M_TEST_LIBS})
    endforeach()
  endif()
endfunction()

# vsp_add_gtest(<exe> <sources...> [LIBS ...]): a GoogleTest executable whose cases ctest runs.
function(vsp_add_gtest exe)
  cmake_parse_arguments(T "" "" "LIBS" ${ARGN})
  if(NOT GTest_FOUND)
    message(FATAL_ERROR "GoogleTest (libgtest-dev) is required to build the tests")
  endif()
  add_executable(${exe} ${T_UNPARSED_ARGUMENTS})
  target_include_directories(${exe} PRIVATE "${VSP_TEST_COMMON_DIR}")
  target_link_libraries(${exe} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${exe} PRIVATE VSP_DATA_DIR="${PROJECT_SOURCE_DIR}/data")
  vsp_set_warnings(${exe})
  include(GoogleTest)
  gtest_discover_tests(${exe} TEST_PREFIX "${exe}." DISCOVERY_TIMEOUT 120 PROPERTIES TIMEOUT 600)
endfunction()

# vsp_add_program(<exe> <sources...> [LIBS ...]): an example / tutorial / benchmark program.
function(vsp_add_program exe)
  cmake_parse_arguments(P "" "" "LIBS" ${ARGN})
  add_executable(${exe} ${P_UNPARSED_ARGUMENTS})
  target_link_libraries(${exe} PRIVATE ${P_LIBS})
  target_compile_definitions(${exe} PRIVATE VSP_DATA_DIR="${PROJECT_SOURCE_DIR}/data")
  vsp_set_warnings(${exe})
endfunction()

# Install layout of the programs and of their data, relative to the install prefix. The installed
# programs find their libraries and data from their own location ($ORIGIN), so an installed tree can
# be moved elsewhere; nothing of the build machine is compiled into them.
set(VSP_INSTALL_DATADIR "${CMAKE_INSTALL_DATADIR}/VispSensorPose/data")
file(RELATIVE_PATH VSP_DATA_RELATIVE_TO_PROGRAM "${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}"
     "${CMAKE_INSTALL_PREFIX}/${VSP_INSTALL_DATADIR}")
file(RELATIVE_PATH VSP_LIB_RELATIVE_TO_PROGRAM "${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}"
     "${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}")

# vsp_install_programs(<target>...): installs each program into <prefix>/bin. Their names start with
# "vsp-" (they share bin/ with everything else installed). They are compiled without VSP_DATA_DIR (the
# absolute path of the repository's data) and with VSP_DATA_RELATIVE_TO_PROGRAM, the path from bin/ to
# the installed data (for example "../share/VispSensorPose/data").
function(vsp_install_programs)
  foreach(program ${ARGN})
    if(NOT program MATCHES "^vsp-")
      message(FATAL_ERROR "vsp_install_programs: '${program}' does not start with vsp-")
    endif()
    get_target_property(defs ${program} COMPILE_DEFINITIONS)
    if(defs)
      list(FILTER defs EXCLUDE REGEX "^VSP_DATA_DIR=")
      set_property(TARGET ${program} PROPERTY COMPILE_DEFINITIONS ${defs})
    endif()
    target_compile_definitions(${program} PRIVATE VSP_DATA_RELATIVE_TO_PROGRAM="${VSP_DATA_RELATIVE_TO_PROGRAM}")
    set_target_properties(${program} PROPERTIES INSTALL_RPATH "\$ORIGIN/${VSP_LIB_RELATIVE_TO_PROGRAM}")
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endforeach()
endfunction()

# vsp_link_build_data(<target>): in the build tree, a link to the repository's data/ at the place where
# <target> looks for its installed data (VSP_DATA_RELATIVE_TO_PROGRAM below its folder), so that the
# program runs the same way from the build tree and from an install.
function(vsp_link_build_data target)
  get_target_property(dir ${target} RUNTIME_OUTPUT_DIRECTORY)
  if(NOT dir)
    get_target_property(dir ${target} BINARY_DIR)
  endif()
  get_filename_component(link "${dir}/${VSP_DATA_RELATIVE_TO_PROGRAM}" ABSOLUTE)
  get_filename_component(link_parent "${link}" DIRECTORY)
  file(MAKE_DIRECTORY "${link_parent}")
  if(NOT EXISTS "${link}")
    file(CREATE_LINK "${PROJECT_SOURCE_DIR}/data" "${link}" SYMBOLIC COPY_ON_ERROR)
  endif()
endfunction()
