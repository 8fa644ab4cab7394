# What every viewer test script starts with: its -D variables checked, and xvfb-run found.
#   subdfit_view_prelude(SCRIPT VAR...): a missing VAR is a fatal error; without xvfb-run it prints
#   "SKIP:" (the tests' SKIP_REGULAR_EXPRESSION) and the calling script returns. Sets XVFB_RUN.
macro(subdfit_view_prelude script)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${script}: -D${var}=... is required")
    endif()
  endforeach()
  find_program(XVFB_RUN xvfb-run)
  if(NOT XVFB_RUN)
    message(STATUS "SKIP: xvfb-run not found (Debian: apt-get install xvfb xauth)")
    return()
  endif()
endmacro()
