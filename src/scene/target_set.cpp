#include "scene/target_set.h"

#include "render/render_target.h"
#include "util/interrupt.h"

namespace subdfit::scene {

TargetSet::TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference,
                     std::vector<render::Camera> cameras, int resolution)
    : cameras_(std::move(cameras)),
      resolution_(resolution),
      colors_(GL_RGBA32F, resolution, resolution, std::max(1, int(cameras_.size()))) {
    render::RenderTarget target(resolution, resolution);
    for (int i = 0; i < size(); ++i) {
        // GL queues the draws: without waiting for each, the loop would be over long before
        // the renders are, and a stop request would only be seen after all of them.
        glFinish();
        throwIfStopRequested();
        reference.draw(programs, cameras_[i], target);
        glCopyImageSubData(target.color().id(), GL_TEXTURE_2D, 0, 0, 0, 0, colors_.id(), GL_TEXTURE_2D_ARRAY,
                           0, 0, 0, i, resolution, resolution, 1);
    }
}

std::vector<glm::vec4> TargetSet::readColor(int i) const {
    std::vector<glm::vec4> pixels(size_t(resolution_) * resolution_);
    glGetTextureSubImage(colors_.id(), 0, 0, 0, i, resolution_, resolution_, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

}  // namespace subdfit::scene
