# Shows a result folder in subdfit-view under a virtual X server (xvfb-run) and checks the
# screenshots with check_screenshot: side by side, every column the folder has (the reference,
# subdfit, each baseline whose file report.json names) shows an object; one at a time, subdfit's
# asset shows something other than the reference does.
#   cmake -DVIEWER=<exe> -DCHECKER=<exe> -DRESULT=<folder> -DSHOTS=<dir> -P run_result_view.cmake
# Prints "SKIP:" where xvfb-run is not installed.
include(${CMAKE_CURRENT_LIST_DIR}/xvfb_prelude.cmake)
subdfit_view_prelude(run_result_view.cmake VIEWER CHECKER RESULT SHOTS)

# The columns the folder should give.
file(READ "${RESULT}/report.json" report)
set(columns 1)
string(JSON reference GET "${report}" reference path)
if(EXISTS "${reference}")
  math(EXPR columns "${columns} + 1")
endif()
string(JSON baselines LENGTH "${report}" baselines)
math(EXPR last "${baselines} - 1")
foreach(i RANGE ${last})
  string(JSON name MEMBER "${report}" baselines ${i})
  string(JSON path ERROR_VARIABLE missing GET "${report}" baselines ${name} path)
  if(NOT missing AND EXISTS "${RESULT}/${path}")
    math(EXPR columns "${columns} + 1")
  endif()
endforeach()

file(MAKE_DIRECTORY "${SHOTS}")
# view_result(SHOT ARG...): one screenshot of the folder, 360 pixels of panel on the left.
function(view_result shot)
  file(REMOVE "${shot}")
  # Mesa's llvmpipe over GLX: the window needs a 24-bit visual.
  execute_process(
    COMMAND "${XVFB_RUN}" -a -s "-screen 0 1600x1024x24" "${VIEWER}" "${RESULT}" ${ARGN} --screenshot "${shot}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${shot}")
    message(FATAL_ERROR "subdfit-view ${RESULT} ${ARGN} failed (exit ${rc})\nstderr:\n${err}\nstdout:\n${out}")
  endif()
endfunction()
function(check shot)
  execute_process(COMMAND "${CHECKER}" "${shot}" 360 ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "screenshot check failed:\n${err}${out}")
  endif()
  message(STATUS "${out}")
endfunction()

math(EXPR width "360 + ${columns} * 200")
view_result("${SHOTS}/side_by_side.png" --width ${width} --height 360)
check("${SHOTS}/side_by_side.png" --columns ${columns})

view_result("${SHOTS}/subdfit.png" --layout single --show subdfit --width 720 --height 400)
view_result("${SHOTS}/reference.png" --layout single --show reference --width 720 --height 400)
check("${SHOTS}/subdfit.png" --differs "${SHOTS}/reference.png")
