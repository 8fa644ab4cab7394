# Runs subdfit-view under a virtual X server (xvfb-run) for a few frames and checks its
# screenshot with check_screenshot; with SAVED, also the results it saved on exit.
#   cmake -DVIEWER=<exe> -DCHECKER=<exe> -DSHOT=<png> -DVIEW_LEFT=<px> -DARGS=<a|b|c>
#         [-DSAVED=<dir> [-DSETTINGS=<key=low:high|...>]] -P run_viewer.cmake
# SETTINGS: report.json's settings.<key> must lie in [low, high].
# Prints "SKIP:" (the test's SKIP_REGULAR_EXPRESSION) where xvfb-run is not installed.
include(${CMAKE_CURRENT_LIST_DIR}/xvfb_prelude.cmake)
subdfit_view_prelude(run_viewer.cmake VIEWER CHECKER SHOT VIEW_LEFT ARGS)

get_filename_component(shotFolder "${SHOT}" DIRECTORY)
file(MAKE_DIRECTORY "${shotFolder}")
file(REMOVE "${SHOT}")
if(SAVED)
  file(REMOVE_RECURSE "${SAVED}")
endif()
string(REPLACE "|" ";" args "${ARGS}")
# Mesa's llvmpipe over GLX: the window needs a 24-bit visual.
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 1280x1024x24" "${VIEWER}" ${args} --screenshot "${SHOT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0 OR NOT EXISTS "${SHOT}")
  message(FATAL_ERROR "subdfit-view ${args} failed (exit ${rc})\nstderr:\n${err}\nstdout:\n${out}")
endif()

execute_process(COMMAND "${CHECKER}" "${SHOT}" ${VIEW_LEFT} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "screenshot check failed:\n${err}${out}")
endif()
message(STATUS "${out}")

if(SAVED)
  foreach(name cage.obj report.json after.png target.png checkpoint.bin)
    if(NOT EXISTS "${SAVED}/${name}")
      message(FATAL_ERROR "Save wrote no ${name} into ${SAVED}")
    endif()
  endforeach()
  file(READ "${SAVED}/report.json" report)
  string(JSON finite GET "${report}" finite)
  if(NOT finite)
    message(FATAL_ERROR "${SAVED}/report.json: the saved cage is not finite")
  endif()
  string(REPLACE "|" ";" settings "${SETTINGS}")
  foreach(setting IN LISTS settings)
    string(REGEX MATCH "^([a-z_]+)=([^:]+):(.+)$" parsed "${setting}")
    set(key ${CMAKE_MATCH_1})
    set(low ${CMAKE_MATCH_2})
    set(high ${CMAKE_MATCH_3})
    string(JSON value GET "${report}" settings ${key})
    if(value LESS low OR value GREATER high)
      message(FATAL_ERROR "${SAVED}/report.json: settings.${key} is ${value}, expected ${low}..${high}")
    endif()
  endforeach()
endif()
