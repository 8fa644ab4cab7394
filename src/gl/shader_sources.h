#pragma once
#include <map>
#include <string>

namespace subdfit::gl {

// Every file of glsl/, embedded at build time (cmake/embed_shaders.cmake).
const std::map<std::string, std::string>& embeddedShaderSources();

// The text of one shader file with its `#include "name"` lines expanded (each file once).
// "osd_patch_basis" names OpenSubdiv's GLSL patch basis (Osd::GLSLPatchShaderSource).
std::string expandedShaderSource(const std::string& name);

}  // namespace subdfit::gl
