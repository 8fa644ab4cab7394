#include "scene/target_set.h"

#include "render/render_target.h"

#include <algorithm>
#include "util/interrupt.h"

namespace subdfit::scene {

namespace {

// The mean of each factor × factor block of a (resolution · factor)² image.
std::vector<glm::vec4> boxFiltered(const std::vector<glm::vec4>& fine, int resolution, int factor) {
    std::vector<glm::vec4> coarse(size_t(resolution) * size_t(resolution), glm::vec4(0.0f));
    const int fineWidth = resolution * factor;
    const float weight = 1.0f / float(factor * factor);
    for (int y = 0; y < fineWidth; ++y)
        for (int x = 0; x < fineWidth; ++x)
            coarse[size_t(y / factor) * size_t(resolution) + size_t(x / factor)] +=
                weight * fine[size_t(y) * size_t(fineWidth) + size_t(x)];
    return coarse;
}

}  // namespace

TargetSet::TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference,
                     std::vector<render::Camera> cameras, int resolution, int supersampling)
    : cameras_(std::move(cameras)),
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
            glCopyImageSubData(target.color().id(), GL_TEXTURE_2D, 0, 0, 0, 0, colors_.id(), GL_TEXTURE_2D_ARRAY, 0, 0,
                               0, i, resolution, resolution, 1);
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
    const auto pixels = canvas_->readColor();
    return supersampling_ == 1 ? pixels : boxFiltered(pixels, resolution_, supersampling_);
}

std::vector<glm::vec4> TargetSet::readColor(int i) const {
    std::vector<glm::vec4> pixels(size_t(resolution_) * resolution_);
    glGetTextureSubImage(colors_.id(), 0, 0, 0, i, resolution_, resolution_, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

}  // namespace subdfit::scene
