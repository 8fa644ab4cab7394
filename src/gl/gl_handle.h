#pragma once
// Move-only ownership of one GL object name (Magnum style). The context must outlive it;
// a moved-from or default handle holds 0 and deletes nothing.
#include <glad/gl.h>

#include <utility>

namespace subdfit::gl {

template <class Traits>
class GlHandle {
public:
    GlHandle() = default;
    explicit GlHandle(GLuint id) noexcept : id_(id) {}
    ~GlHandle() { reset(); }
    GlHandle(GlHandle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlHandle& operator=(GlHandle&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;

    GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }

private:
    void reset() noexcept {
        if (id_) Traits::destroy(id_);
        id_ = 0;
    }
    GLuint id_ = 0;
};

struct BufferTraits {
    static void destroy(GLuint id) noexcept { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
    static void destroy(GLuint id) noexcept { glDeleteTextures(1, &id); }
};
struct SamplerTraits {
    static void destroy(GLuint id) noexcept { glDeleteSamplers(1, &id); }
};
struct FramebufferTraits {
    static void destroy(GLuint id) noexcept { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
    static void destroy(GLuint id) noexcept { glDeleteVertexArrays(1, &id); }
};
struct ProgramTraits {
    static void destroy(GLuint id) noexcept { glDeleteProgram(id); }
};
struct ShaderTraits {
    static void destroy(GLuint id) noexcept { glDeleteShader(id); }
};
struct QueryTraits {
    static void destroy(GLuint id) noexcept { glDeleteQueries(1, &id); }
};

}  // namespace subdfit::gl
