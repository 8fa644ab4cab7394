# The viewer (ctest -L view): a few frames under Xvfb (Mesa llvmpipe over GLX) whose screenshot
# must show the panel and the object; bad input refused with one line before any window opens.
# Included by tests/CMakeLists.txt when subdfit-view is built.
add_executable(subdfit_view_check_screenshot ${CMAKE_CURRENT_LIST_DIR}/check_screenshot.cpp)
target_link_libraries(subdfit_view_check_screenshot PRIVATE subdfit_warnings PkgConfig::OpenImageIO)

set(SUBDFIT_VIEW_OUT ${CMAKE_CURRENT_BINARY_DIR}/view)
set(SUBDFIT_VIEW_CAGE ${PROJECT_SOURCE_DIR}/assets/spot/spot_cage_noised.obj)
set(SUBDFIT_VIEW_REFERENCE ${PROJECT_SOURCE_DIR}/assets/spot/spot_triangulated.obj)
# Small and short: 64² targets, 640×400 window (the panel takes the left 360 pixels).
set(SUBDFIT_VIEW_SMALL --cage ${SUBDFIT_VIEW_CAGE} --reference ${SUBDFIT_VIEW_REFERENCE}
    --res 64 --views 4 --holdout-views 1 --width 640 --height 400)

# subdfit_view_screenshot(NAME [SAVED [SETTINGS key=low:high|...]] ARG...): a screenshot run; with
# SAVED, --save-on-exit too, and report.json's settings checked against SETTINGS.
function(subdfit_view_screenshot name)
  set(saved "")
  set(settings "")
  set(extra ${ARGN})
  if(ARGV1 STREQUAL "SAVED")
    set(saved ${SUBDFIT_VIEW_OUT}/${name}_out)
    list(REMOVE_AT extra 0)
    list(GET extra 0 next)
    if(next STREQUAL "SETTINGS")
      list(GET extra 1 settings)
      list(REMOVE_AT extra 0 1)
    endif()
    list(APPEND extra --save-on-exit --out ${saved})
  endif()
  list(JOIN extra "|" args)
  add_test(NAME view.screenshot.${name}
           COMMAND ${CMAKE_COMMAND} -DVIEWER=$<TARGET_FILE:subdfit-view>
                   -DCHECKER=$<TARGET_FILE:subdfit_view_check_screenshot>
                   -DSHOT=${SUBDFIT_VIEW_OUT}/${name}.png -DVIEW_LEFT=360 -DSAVED=${saved} "-DSETTINGS=${settings}"
                   -DARGS=${args} -P ${CMAKE_CURRENT_LIST_DIR}/run_viewer.cmake)
  set_tests_properties(view.screenshot.${name} PROPERTIES LABELS view TIMEOUT 120 SKIP_REGULAR_EXPRESSION "SKIP:")
endfunction()

# The fit, playing for a few frames (it stops at --steps), then saved as `subdfit fit` would: its
# settings say what the command line said (the vertex rates in fractions of the mean edge).
subdfit_view_screenshot(fit SAVED SETTINGS "epsilon=0.0499:0.0501|learning_rate=0.0999:0.1001"
                        ${SUBDFIT_VIEW_SMALL} --epsilon 0.05 --lr 0.1 --steps 3 --frames 5)
# The map variant of the composite pass, the difference heat map and the cage overlay.
subdfit_view_screenshot(maps_difference ${SUBDFIT_VIEW_SMALL} --maps displacement --steps 2 --frames 3
                        --mode difference --wireframe)

# A reference with a material (a textured box, a cube cage): the base colour group's own view,
# the composite pass's appearance variant.
subdfit_view_screenshot(base_color --cage ${PROJECT_SOURCE_DIR}/assets/osd-shapes/catmark_cube.obj
                        --reference ${PROJECT_SOURCE_DIR}/assets/gltf/BoxTextured/BoxTextured.glb
                        --res 64 --views 4 --holdout-views 1 --width 640 --height 400 --steps 2 --frames 3
                        --mode base_color)

# A result folder (the short simplify of tests/cli: Spot, its baselines): every column side by
# side; subdfit's asset on its own is not the reference.
set(SUBDFIT_VIEW_RESULT ${SUBDFIT_CLI_OUT}/simplify_spot)
add_test(NAME view.result.columns
         COMMAND ${CMAKE_COMMAND} -DVIEWER=$<TARGET_FILE:subdfit-view> -DCHECKER=$<TARGET_FILE:subdfit_view_check_screenshot>
                 -DRESULT=${SUBDFIT_VIEW_RESULT} -DSHOTS=${SUBDFIT_VIEW_OUT}/result
                 -P ${CMAKE_CURRENT_LIST_DIR}/run_result_view.cmake)
set_tests_properties(view.result.columns PROPERTIES LABELS view TIMEOUT 180 SKIP_REGULAR_EXPRESSION "SKIP:"
                     FIXTURES_REQUIRED simplify_spot)
# The result refined: a fit from its asset and maps against its reference, saved as `fit` would.
subdfit_view_screenshot(refine SAVED ${SUBDFIT_VIEW_RESULT} --refine --res 48 --views 2 --holdout-views 1 --steps 2
                        --frames 3 --width 640 --height 400)
set_tests_properties(view.screenshot.refine PROPERTIES FIXTURES_REQUIRED simplify_spot)

# Its asset.subd with its prefixes as levels (each decoded as the file loads: half the bytes, a
# quarter ... down to the cage alone), the whole file drawn first.
subdfit_view_screenshot(prefixes ${SUBDFIT_VIEW_RESULT}/asset.subd --prefixes --width 640 --height 400)
set_tests_properties(view.screenshot.prefixes PROPERTIES FIXTURES_REQUIRED simplify_spot)

# Refused with one stderr line naming the culprit (tests/cli/expect_failure.cmake), no window needed.
function(subdfit_view_refuses name expect)
  list(JOIN ARGN "|" args)
  add_test(NAME view.refuses.${name}
           COMMAND ${CMAKE_COMMAND} -DSUBDFIT=$<TARGET_FILE:subdfit-view> -DOUT=${SUBDFIT_VIEW_OUT}/${name}
                   -DEXPECT=${expect} -DARGS=${args} -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_failure.cmake)
  set_tests_properties(view.refuses.${name} PROPERTIES LABELS view TIMEOUT 60)
endfunction()

subdfit_view_refuses(missing_cage ${SUBDFIT_VIEW_OUT}/does_not_exist.obj
                     --cage ${SUBDFIT_VIEW_OUT}/does_not_exist.obj --reference ${SUBDFIT_VIEW_REFERENCE})
subdfit_view_refuses(map_mode_without_maps --mode --cage ${SUBDFIT_VIEW_CAGE} --reference ${SUBDFIT_VIEW_REFERENCE}
                     --mode displacement)
# A result that cannot be shown: a damaged asset.subd, a folder that holds no result.
subdfit_view_refuses(damaged_subd "damaged.subd: checksum mismatch" ${PROJECT_SOURCE_DIR}/tests/data/damaged.subd)
subdfit_view_refuses(folder_without_result "data: not a subdfit result: no report.json" ${PROJECT_SOURCE_DIR}/tests/data)
subdfit_view_refuses(neither_result_nor_fit "give a RESULT" --width 640)
subdfit_view_refuses(appearance_mode_without_material "needs a reference whose material" --cage ${SUBDFIT_VIEW_CAGE}
                     --reference ${SUBDFIT_VIEW_REFERENCE} --mode metallic_roughness)
# First bytes that end before the cage does: refused as `decode --bytes` refuses them.
subdfit_view_refuses(bytes_before_the_cage "end before the cage does" ${SUBDFIT_VIEW_RESULT}/asset.subd --bytes 20)
set_tests_properties(view.refuses.bytes_before_the_cage PROPERTIES FIXTURES_REQUIRED simplify_spot)
