# CTest fixture: configures and builds tests/fuzz with clang (libFuzzer + ASan/UBSan) or with gcc
# (replay binaries + GCC's ASan/UBSan).
#   cmake -DSOURCE=<tests/fuzz> -DBINARY=<dir> -DCOMPILER=<clang++ or g++> -P build_fuzzers.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE} -B ${BINARY} -G Ninja -DCMAKE_CXX_COMPILER=${COMPILER}
                        -DCMAKE_BUILD_TYPE=RelWithDebInfo
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the fuzzers failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the fuzzers failed:\n${out}\n${err}")
endif()
