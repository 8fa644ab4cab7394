# Runs one libFuzzer target for SECONDS on a scratch copy of its seed corpus (libFuzzer adds the
# inputs it finds to the corpus folder it is given; the committed seeds stay as they are). An
# input that makes one allocation of more than MALLOC_MB, or the process use more than RSS_MB,
# fails the run: what a small input may cost is bounded, not only whether it crashes.
#   cmake -DFUZZER=<exe> -DSEEDS=<dir> -DWORK=<dir> -DSECONDS=<n> -DMALLOC_MB=<n> -DRSS_MB=<n> -P run_fuzzer.cmake
file(REMOVE_RECURSE ${WORK})
file(COPY ${SEEDS}/ DESTINATION ${WORK}/corpus)
execute_process(COMMAND ${FUZZER} -max_total_time=${SECONDS} -malloc_limit_mb=${MALLOC_MB} -rss_limit_mb=${RSS_MB}
                        -print_final_stats=1
                        -artifact_prefix=${WORK}/ ${WORK}/corpus
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "stat::number_of_executed_units: *[0-9]+" runs "${err}")
message(STATUS "${FUZZER}: ${runs}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzzer found a problem (artifact in ${WORK}):\n${err}")
endif()
