# subdfit_embed_shaders(TARGET <target> DIR <folder> MODE core|register): the shader files of
# <folder> (not its subfolders) compiled into <target>. Shaders live by owner: glsl/ is the
# core's, glsl/view/ the viewer's, glsl/bench/ the benchmarks'; each is embedded where it is used.
function(subdfit_embed_shaders)
  cmake_parse_arguments(E "" "TARGET;DIR;MODE" "" ${ARGN})
  file(GLOB shaders LIST_DIRECTORIES false CONFIGURE_DEPENDS "${E_DIR}/*")
  set(output "${CMAKE_CURRENT_BINARY_DIR}/generated/${E_TARGET}_shaders.cpp")
  add_custom_command(
    OUTPUT "${output}"
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${E_DIR} -DOUTPUT=${output} -DMODE=${E_MODE}
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    DEPENDS ${shaders} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake
    COMMENT "Embedding the shaders of ${E_DIR}")
  target_sources(${E_TARGET} PRIVATE "${output}")
  target_include_directories(${E_TARGET} PRIVATE ${E_DIR})  # their shared headers, for C++ too
endfunction()
