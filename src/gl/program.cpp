#include "gl/program.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl/shader_sources.h"
#include "util/error.h"

namespace subdfit::gl {

std::string defineBlock(const Defines& defines) {
    std::string block;
    for (const auto& [name, value] : defines) block += "#define " + name + " " + value + "\n";
    return block;
}

namespace {

std::string infoLog(GLuint object, bool isProgram) {
    GLint length = 0;
    isProgram ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
              : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::max(length, 1), '\0');
    isProgram ? glGetProgramInfoLog(object, length, nullptr, log.data())
              : glGetShaderInfoLog(object, length, nullptr, log.data());
    return log.c_str();
}

GlHandle<ShaderTraits> compile(const ShaderStage& stage, const Defines& defines) {
    // The extension line must precede any non-preprocessor token, so it goes right after
    // #version; shaders test SUBDFIT_ATOMIC_FLOAT before using it.
    std::string source = "#version 450 core\n";
    if (defines.count("SUBDFIT_ATOMIC_FLOAT")) source += "#extension GL_NV_shader_atomic_float : require\n";
    source += defineBlock(defines) + "#line 1\n" + expandedShaderSource(stage.file);
    GlHandle<ShaderTraits> shader(glCreateShader(stage.type));
    const char* text = source.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok)
        throw Error("shader " + stage.file + " failed to compile with defines {" + defineBlock(defines) +
                    "}: " + infoLog(shader.id(), false));
    return shader;
}

}  // namespace

Program::Program(const std::vector<ShaderStage>& stages, const Defines& defines) {
    std::vector<GlHandle<ShaderTraits>> shaders;
    for (const auto& stage : stages) shaders.push_back(compile(stage, defines));
    handle_ = GlHandle<ProgramTraits>(glCreateProgram());
    for (const auto& shader : shaders) glAttachShader(id(), shader.id());
    glLinkProgram(id());
    GLint ok = 0;
    glGetProgramiv(id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        std::string files;
        for (const auto& stage : stages) files += stage.file + " ";
        throw Error("program [" + files + "] failed to link: " + infoLog(id(), true));
    }
}

GLint Program::location(const char* name) const {
    const auto [it, fresh] = locations_.try_emplace(name, -1);
    if (fresh) it->second = glGetUniformLocation(id(), name);
    return it->second;
}

void Program::set(const char* name, int value) const { glProgramUniform1i(id(), location(name), value); }
void Program::set(const char* name, unsigned value) const { glProgramUniform1ui(id(), location(name), value); }
void Program::set(const char* name, float value) const { glProgramUniform1f(id(), location(name), value); }
void Program::set(const char* name, const glm::vec2& value) const {
    glProgramUniform2fv(id(), location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::vec3& value) const {
    glProgramUniform3fv(id(), location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::vec4& value) const {
    glProgramUniform4fv(id(), location(name), 1, glm::value_ptr(value));
}
void Program::set(const char* name, const glm::mat3& value) const {
    glProgramUniformMatrix3fv(id(), location(name), 1, GL_FALSE, glm::value_ptr(value));
}

void Program::set(const char* name, const glm::mat4& value) const {
    glProgramUniformMatrix4fv(id(), location(name), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace subdfit::gl
