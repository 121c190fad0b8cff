# Writes OUT (version.cpp) from IN with KNOBLAB_VERSION_STRING: VERSION, then
# "+g" and the commit's first 12 hex digits, ".dirty" when tracked files differ
# from it. Run at every build (a commit needs no reconfigure); configure_file
# leaves OUT untouched when nothing changed, so nothing recompiles then.
# COMMIT, when given (a Yocto recipe's SRCREV), stands in for git's answer.
# safe.directory: ./run builds as root in the SDK, whoever owns the checkout.
set(commit "${COMMIT}")
set(dirty "")
if(commit STREQUAL "")
  execute_process(COMMAND git -c safe.directory=* -C "${SOURCE_DIR}" rev-parse HEAD
                  OUTPUT_VARIABLE commit ERROR_QUIET RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    set(commit "")
  else()
    execute_process(COMMAND git -c safe.directory=* -C "${SOURCE_DIR}" diff --quiet HEAD --
                    RESULT_VARIABLE rc ERROR_QUIET)
    if(NOT rc EQUAL 0)
      set(dirty ".dirty")
    endif()
  endif()
endif()
if(commit STREQUAL "")
  set(KNOBLAB_VERSION_STRING "${VERSION}+unknown")
else()
  string(SUBSTRING "${commit}" 0 12 short)
  set(KNOBLAB_VERSION_STRING "${VERSION}+g${short}${dirty}")
endif()
configure_file("${IN}" "${OUT}" @ONLY)
