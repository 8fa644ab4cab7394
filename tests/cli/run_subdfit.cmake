# Shared by the expect_*.cmake drivers: checks that every variable named in REQUIRED was given
# with -D, starts from no OUT folder, and runs `SUBDFIT ARGS... --out OUT`, setting rc, out, err.
# ARGS is '|'-separated (';' would be split by add_test).
macro(subdfit_cli_run script timeout)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "${script}: -D${var}=... is required")
    endif()
  endforeach()
  file(REMOVE_RECURSE "${OUT}")
  string(REPLACE "|" ";" args "${ARGS}")
  execute_process(
    COMMAND "${SUBDFIT}" ${args} --out "${OUT}"
    RESULT_VARIABLE rc
    OUTPUT_VARIABLE out
    ERROR_VARIABLE err
    TIMEOUT ${timeout})
endmacro()
