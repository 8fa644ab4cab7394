# The web decoder (apps/web, docs/web.md), labelled `web`: built by a fixture (the `web` target),
# then checked in Node against `subdfit decode` and in headless Chromium against three's
# GLTFLoader; and what `subdfit decode` writes for engines, through the Khronos glTF validator. Included by tests/CMakeLists.txt where the web target exists.
set(web_tests ${CMAKE_CURRENT_LIST_DIR})
set(web_scratch ${CMAKE_CURRENT_BINARY_DIR}/web)

add_test(NAME web.build COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target web)
set_tests_properties(web.build PROPERTIES LABELS web FIXTURES_SETUP web_build TIMEOUT 1200)

add_test(NAME web.assets
         COMMAND ${CMAKE_COMMAND} -E env SUBDFIT=$<TARGET_FILE:subdfit>
                 ${SUBDFIT_NODE} ${web_tests}/make_assets.mjs ${PROJECT_SOURCE_DIR} ${web_scratch}/assets)
set_tests_properties(web.assets PROPERTIES LABELS web FIXTURES_SETUP web_assets TIMEOUT 600)

set(web_env WEB=${CMAKE_BINARY_DIR}/web ASSETS=${web_scratch}/assets HOSTILE=${PROJECT_SOURCE_DIR}/tests/data/hostile-subd
            SUBDFIT=$<TARGET_FILE:subdfit> DEMO=${PROJECT_SOURCE_DIR}/out/relief_spot/asset.subd
            NODE_MODULES=${PROJECT_SOURCE_DIR}/apps/web/node_modules)
add_test(NAME web.decode COMMAND ${CMAKE_COMMAND} -E env ${web_env} ${SUBDFIT_NODE} --test ${web_tests}/decode_test.mjs)
set_tests_properties(web.decode PROPERTIES LABELS web FIXTURES_REQUIRED "web_build;web_assets" TIMEOUT 600)
add_test(NAME web.browser COMMAND ${CMAKE_COMMAND} -E env ${web_env} ${SUBDFIT_NODE} --test ${web_tests}/browser_test.mjs)
set_tests_properties(web.browser PROPERTIES LABELS web FIXTURES_REQUIRED "web_build;web_assets" TIMEOUT 600)
add_test(NAME web.validate COMMAND ${CMAKE_COMMAND} -E env ${web_env} ${SUBDFIT_NODE} --test ${web_tests}/validate_test.mjs)
set_tests_properties(web.validate PROPERTIES LABELS web FIXTURES_REQUIRED web_assets TIMEOUT 600)
