# Runs a short `subdfit fit` that must succeed, then checks the output folder: every result
# file there and non-empty, report.json readable and finite, no temporary file left behind
# (atomic writes go through hidden '.name.tmp' files that must all have been renamed).
#   cmake -DSUBDFIT=<exe> -DOUT=<dir> -DARGS=<a|b|c> -DSTEPS=<n> -P expect_success.cmake
foreach(var SUBDFIT OUT ARGS STEPS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "expect_success.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${OUT}")
string(REPLACE "|" ";" args "${ARGS}")
execute_process(
  COMMAND "${SUBDFIT}" ${args} --out "${OUT}"
  RESULT_VARIABLE rc
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 600)
if(NOT rc EQUAL 0)
  list(JOIN args " " shown)
  message(FATAL_ERROR "subdfit ${shown} --out ${OUT}\nexit: ${rc}\nstderr:\n${err}\nstdout:\n${out}")
endif()

set(problems "")
foreach(name cage.obj report.json before.png after.png target.png)
  if(NOT EXISTS "${OUT}/${name}")
    string(APPEND problems "\n  missing ${name}")
  else()
    file(SIZE "${OUT}/${name}" size)
    if(size EQUAL 0)
      string(APPEND problems "\n  empty ${name}")
    endif()
  endif()
endforeach()

file(GLOB_RECURSE entries LIST_DIRECTORIES true RELATIVE "${OUT}" "${OUT}/*")
foreach(entry IN LISTS entries)
  get_filename_component(leaf "${entry}" NAME)
  if(leaf MATCHES "^\\." OR leaf MATCHES "(\\.tmp|~)$")
    string(APPEND problems "\n  leftover temporary file ${entry}")
  endif()
endforeach()

if(EXISTS "${OUT}/report.json")
  file(READ "${OUT}/report.json" report)
  string(JSON steps ERROR_VARIABLE jsonError GET "${report}" steps)
  if(jsonError)
    string(APPEND problems "\n  report.json: ${jsonError}")
  else()
    string(JSON finite GET "${report}" finite)
    if(NOT steps EQUAL STEPS)
      string(APPEND problems "\n  report.json says ${steps} steps, expected ${STEPS}")
    endif()
    if(NOT finite)
      string(APPEND problems "\n  report.json: fitted cage is not finite")
    endif()
  endif()
endif()

string(FIND "${out}" "report.json" at)
if(at EQUAL -1)
  string(APPEND problems "\n  stdout does not print the report path")
endif()

if(problems)
  list(JOIN args " " shown)
  message(FATAL_ERROR "subdfit ${shown} --out ${OUT}${problems}\nfiles: ${entries}\nstderr:\n${err}")
endif()
message(STATUS "fit succeeded: ${entries}")
