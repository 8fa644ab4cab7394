#pragma once
#include <map>
#include <string>

namespace subdfit::gl {

// The core's shaders: every file directly in glsl/, embedded at build time
// (cmake/embed_shaders.cmake).
const std::map<std::string, std::string>& embeddedShaderSources();

// Adds an app's own shaders (glsl/view/, glsl/bench/) to the ones programs are built from, by
// file name; called by the app's generated file at start-up. Returns true.
bool addShaderSources(const std::map<std::string, std::string>& sources);

// The text of one shader file with its `#include "name"` lines expanded (each file once).
// "osd_patch_basis" names OpenSubdiv's GLSL patch basis (Osd::GLSLPatchShaderSource).
std::string expandedShaderSource(const std::string& name);

}  // namespace subdfit::gl
