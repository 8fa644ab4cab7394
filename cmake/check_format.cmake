# Every C++ source of src/, apps/ and tests/ (the generated GL loader aside) is laid out as
# .clang-format says: clang-format-14 --dry-run --Werror over all of them, the offending lines
# printed. Run by the `format.clang_format` test:
#   cmake -DSOURCE=<repository> -DCLANG_FORMAT=<clang-format-14> -P check_format.cmake
# To lay a file out: clang-format-14 -i FILE.
cmake_policy(VERSION 3.25)
if(NOT CLANG_FORMAT OR NOT EXISTS "${CLANG_FORMAT}")
  message(FATAL_ERROR "clang-format-14 not found: run .ci/setup --tests")
endif()
file(GLOB_RECURSE files ${SOURCE}/src/*.cpp ${SOURCE}/src/*.h ${SOURCE}/apps/*.cpp ${SOURCE}/apps/*.h
     ${SOURCE}/tests/*.cpp ${SOURCE}/tests/*.h)
list(FILTER files EXCLUDE REGEX "/src/glad/|/node_modules/")
execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${files} RESULT_VARIABLE result ERROR_VARIABLE problems)
if(NOT result EQUAL 0)
  string(REGEX MATCHALL "[^\n]*: error: code should be clang-formatted[^\n]*" lines "${problems}")
  list(LENGTH lines count)
  string(REPLACE ";" "\n" lines "${lines}")
  message(FATAL_ERROR "${lines}\n${count} places not laid out as .clang-format says: clang-format-14 -i the files named")
endif()
