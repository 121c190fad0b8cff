# Given to CMake as CMAKE_PROJECT_INCLUDE by the knoblab recipe's ptest build.
# The tests are compiled with the paths of the programs they run and the data
# they read in the build and source trees; on the device the programs are in
# KNOBLAB_PTEST_BINDIR and the data under KNOBLAB_PTEST_DATADIR. Once every
# directory is configured, this rewrites those compile definitions.

function(knoblab_ptest_paths dir)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(defs ${target} COMPILE_DEFINITIONS)
    if(NOT defs)
      continue()
    endif()
    foreach(program knoblab hapticd knoblab-modbus-sim)
      string(REPLACE "$<TARGET_FILE:${program}>" "${KNOBLAB_PTEST_BINDIR}/${program}" defs "${defs}")
    endforeach()
    string(REPLACE "${CMAKE_SOURCE_DIR}/" "${KNOBLAB_PTEST_DATADIR}/" defs "${defs}")
    set_property(TARGET ${target} PROPERTY COMPILE_DEFINITIONS "${defs}")
  endforeach()
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(subdir IN LISTS subdirs)
    knoblab_ptest_paths("${subdir}")
  endforeach()
endfunction()

cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL knoblab_ptest_paths "${CMAKE_SOURCE_DIR}")
