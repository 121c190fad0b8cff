# Given to CMake as CMAKE_PROJECT_INCLUDE by the knoblab recipe's ptest build.
# The tests are compiled with the paths of the programs they run and the data
# they read in the build and source trees; on the device the programs are in
# KNOBLAB_PTEST_BINDIR and the data under KNOBLAB_PTEST_DATADIR. Once every
# directory is configured, this rewrites those paths: compile definitions, and
# the test paths knoblab_test_paths() keeps (cmake/test_paths.cmake).

function(knoblab_ptest_rewrite target property)
  get_target_property(defs ${target} ${property})
  if(NOT defs)
    return()
  endif()
  foreach(program knoblab hapticd knoblab-modbus-sim)
    string(REPLACE "$<TARGET_FILE:${program}>" "${KNOBLAB_PTEST_BINDIR}/${program}" defs "${defs}")
  endforeach()
  string(REPLACE "${CMAKE_SOURCE_DIR}/" "${KNOBLAB_PTEST_DATADIR}/" defs "${defs}")
  set_property(TARGET ${target} PROPERTY ${property} "${defs}")
endfunction()

function(knoblab_ptest_paths dir)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    knoblab_ptest_rewrite(${target} COMPILE_DEFINITIONS)
    knoblab_ptest_rewrite(${target} KNOBLAB_TEST_PATHS)
  endforeach()
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(subdir IN LISTS subdirs)
    knoblab_ptest_paths("${subdir}")
  endforeach()
endfunction()

cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL knoblab_ptest_paths "${CMAKE_SOURCE_DIR}")
