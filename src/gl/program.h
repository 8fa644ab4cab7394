#pragma once
// GLSL programs built in a fixed order (OpenSubdiv style): `#version 450 core`, the variant's
// #define block, then the stage file with its includes expanded. Compile errors name the stage
// file and list the defines, since a variant that fails usually fails because of one.
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "gl/gl_handle.h"

namespace subdfit::gl {

// Name -> value ("" for a bare flag). Sorted, so equal sets give equal cache keys.
using Defines = std::map<std::string, std::string>;

struct ShaderStage {
    GLenum type;       // GL_VERTEX_SHADER, GL_COMPUTE_SHADER, ...
    std::string file;  // under glsl/
};

class Program {
public:
    Program() = default;
    Program(const std::vector<ShaderStage>& stages, const Defines& defines);

    GLuint id() const { return handle_.id(); }
    void use() const { glUseProgram(id()); }
    // Looked up once per name: the fit sets a dozen uniforms a pass, thousands of passes a run.
    GLint location(const char* name) const;

    void set(const char* name, int value) const;
    void set(const char* name, unsigned value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::mat3& value) const;
    void set(const char* name, const glm::mat4& value) const;

    void set(const char* name, const glm::vec4& value) const;

private:
    GlHandle<ProgramTraits> handle_;
    mutable std::unordered_map<std::string, GLint> locations_;
};

std::string defineBlock(const Defines& defines);

}  // namespace subdfit::gl
