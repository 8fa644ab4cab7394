#include "scene/target_set.h"

#include <algorithm>

#include "bindings.h"
#include "gl/dispatch.h"
#include "render/render_target.h"
#include "util/interrupt.h"

namespace subdfit::scene {

namespace {

const gl::ProgramSpec kBoxFilter{"box_filter", {{GL_COMPUTE_SHADER, "box_filter.comp"}}};

// The mean of each factor × factor block of `fine` ((resolution · factor)²), filtered on the GPU
// into `filtered` (resolution² vec4s) and read back.
std::vector<glm::vec4> boxFiltered(gl::ProgramCache& programs, const gl::Texture& fine, int resolution, int factor,
                                   const gl::Buffer& filtered) {
    const auto& program = programs.get(kBoxFilter);
    program.use();
    program.set("uResolution", resolution);
    program.set("uFactor", factor);
    glBindTextureUnit(SUBDFIT_UNIT_SUPERSAMPLED, fine.id());
    filtered.bindStorage(SUBDFIT_SSBO_FILTERED);
    glDispatchCompute(gl::groupsOf(resolution, 16), gl::groupsOf(resolution, 16), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return filtered.read<glm::vec4>();
}

}  // namespace

TargetSet::TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference,
                     std::vector<render::Camera> cameras, int resolution, int supersampling)
    : programs_(&programs),
      cameras_(std::move(cameras)),
      resolution_(resolution),
      supersampling_(std::max(1, supersampling)),
      colors_(GL_RGBA32F, resolution, resolution, std::max(1, int(cameras_.size()))) {
    render::RenderTarget target(resolution, resolution);
    for (int i = 0; i < size(); ++i) {
        // GL queues the draws: without waiting for each, the loop would be over long before
        // the renders are, and a stop request would only be seen after all of them.
        glFinish();
        throwIfStopRequested();
        if (supersampling_ == 1) {
            reference.draw(programs, cameras_[i], target);
            glCopyImageSubData(target.color().id(), GL_TEXTURE_2D, 0, 0, 0, 0, colors_.id(), GL_TEXTURE_2D_ARRAY,
                               0, 0, 0, i, resolution, resolution, 1);
        } else {
            const auto pixels = render(i, [&](const render::Camera& camera, const render::RenderTarget& canvas) {
                reference.draw(programs, camera, canvas);
            });
            glTextureSubImage3D(colors_.id(), 0, 0, 0, i, resolution, resolution, 1, GL_RGBA, GL_FLOAT, pixels.data());
        }
    }
}

TargetSet::~TargetSet() = default;
TargetSet::TargetSet(TargetSet&&) noexcept = default;

std::vector<glm::vec4> TargetSet::render(int i, const Draw& draw) const {
    const int fine = resolution_ * supersampling_;
    if (!canvas_) canvas_ = std::make_unique<render::RenderTarget>(fine, fine);
    draw(cameras_[size_t(i)], *canvas_);
    if (supersampling_ == 1) return canvas_->readColor();
    if (!filtered_) filtered_ = std::make_unique<gl::Buffer>(GLsizeiptr(resolution_) * resolution_ * sizeof(glm::vec4));
    return boxFiltered(*programs_, canvas_->color(), resolution_, supersampling_, *filtered_);
}

std::vector<glm::vec4> TargetSet::readColor(int i) const {
    std::vector<glm::vec4> pixels(size_t(resolution_) * resolution_);
    glGetTextureSubImage(colors_.id(), 0, 0, 0, i, resolution_, resolution_, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

}  // namespace subdfit::scene
