# The web decoder (apps/web, docs/web.md), labelled `web`: built by a fixture (the `web` target),
# then checked in Node against `subdfit decode` and in headless Chromium against three's
# GLTFLoader. Included by tests/CMakeLists.txt where the web target exists.
set(web_tests ${CMAKE_CURRENT_LIST_DIR})
set(web_scratch ${CMAKE_CURRENT_BINARY_DIR}/web)

add_test(NAME web.build COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target web)
set_tests_properties(web.build PROPERTIES LABELS web FIXTURES_SETUP web_build TIMEOUT 1200)

add_executable(subdfit_hostile_subd ${web_tests}/hostile_subd.cpp)
target_link_libraries(subdfit_hostile_subd PRIVATE subdfit_export subdfit_warnings PkgConfig::zstd)

add_test(NAME web.assets
         COMMAND ${CMAKE_COMMAND} -E env SUBDFIT=$<TARGET_FILE:subdfit>
                 ${SUBDFIT_NODE} ${web_tests}/make_assets.mjs ${PROJECT_SOURCE_DIR} ${web_scratch}/assets)
set_tests_properties(web.assets PROPERTIES LABELS web FIXTURES_SETUP web_assets TIMEOUT 600)
add_test(NAME web.hostile COMMAND subdfit_hostile_subd ${web_scratch}/hostile)
set_tests_properties(web.hostile PROPERTIES LABELS web FIXTURES_SETUP web_hostile)

set(web_env WEB=${CMAKE_BINARY_DIR}/web ASSETS=${web_scratch}/assets HOSTILE=${web_scratch}/hostile
            SUBDFIT=$<TARGET_FILE:subdfit> DEMO=${PROJECT_SOURCE_DIR}/out/relief_spot/asset.subd
            NODE_MODULES=${PROJECT_SOURCE_DIR}/apps/web/node_modules)
add_test(NAME web.decode COMMAND ${CMAKE_COMMAND} -E env ${web_env} ${SUBDFIT_NODE} --test ${web_tests}/decode_test.mjs)
set_tests_properties(web.decode PROPERTIES LABELS web FIXTURES_REQUIRED "web_build;web_assets;web_hostile" TIMEOUT 600)
add_test(NAME web.browser COMMAND ${CMAKE_COMMAND} -E env ${web_env} ${SUBDFIT_NODE} --test ${web_tests}/browser_test.mjs)
set_tests_properties(web.browser PROPERTIES LABELS web FIXTURES_REQUIRED "web_build;web_assets" TIMEOUT 600)
