# Runs `subdfit` with arguments that must be refused, and checks how it refuses:
# a non-zero exit (not a crash), exactly one line on stderr naming the culprit, and no output
# folder left behind.
#   cmake -DSUBDFIT=<exe> -DOUT=<dir> -DEXPECT=<text> -DARGS=<a|b|c> -P expect_failure.cmake
# ARGS is '|'-separated (';' would be split by add_test); `--out OUT` is appended.
include(${CMAKE_CURRENT_LIST_DIR}/run_subdfit.cmake)
subdfit_cli_run(expect_failure.cmake 120 SUBDFIT OUT EXPECT ARGS)

set(problems "")
if(NOT rc MATCHES "^[0-9]+$")
  string(APPEND problems "\n  did not exit normally: ${rc}")
elseif(rc EQUAL 0)
  string(APPEND problems "\n  exit code 0, expected failure")
endif()

string(REGEX REPLACE "\n$" "" message "${err}")
string(REGEX MATCHALL "\n" newlines "${message}")
list(LENGTH newlines extraLines)
if(message STREQUAL "")
  string(APPEND problems "\n  nothing on stderr")
elseif(NOT extraLines EQUAL 0 OR NOT err MATCHES "\n$")
  string(APPEND problems "\n  stderr is not exactly one line")
endif()
string(FIND "${message}" "${EXPECT}" at)
if(at EQUAL -1)
  string(APPEND problems "\n  stderr does not name '${EXPECT}'")
endif()

if(EXISTS "${OUT}")
  string(APPEND problems "\n  output folder was created: ${OUT}")
endif()

if(problems)
  list(JOIN args " " shown)
  message(FATAL_ERROR "subdfit ${shown} --out ${OUT}${problems}\n"
                      "exit: ${rc}\nstderr:\n${err}\nstdout:\n${out}")
endif()
message(STATUS "refused as expected (exit ${rc}): ${message}")
