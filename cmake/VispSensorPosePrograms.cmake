# Helpers of the standalone build for the programs (examples, tutorials, benchmarks, CLIs) and their
# install layout. The modules themselves are declared with vsp_add_module (VispSensorPoseModule.cmake).

# vsp_add_program(<exe> <sources...> [LIBS ...]): an example / tutorial / benchmark program.
function(vsp_add_program exe)
  cmake_parse_arguments(P "" "" "LIBS" ${ARGN})
  add_executable(${exe} ${P_UNPARSED_ARGUMENTS})
  target_link_libraries(${exe} PRIVATE ${P_LIBS})
  target_compile_definitions(${exe} PRIVATE VSP_DATA_DIR="${VSP_REPO_DIR}/data")
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
