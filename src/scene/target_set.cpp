#include "scene/target_set.h"

#include "bindings.h"
#include "gl/dispatch.h"
#include "render/render_target.h"
#include "util/interrupt.h"

namespace subdfit::scene {

namespace {

const gl::ProgramSpec kDownsample{"downsample", {{GL_COMPUTE_SHADER, "downsample.comp"}}};
const gl::ProgramSpec kViewLoss{"view_loss", {{GL_COMPUTE_SHADER, "view_loss.comp"}}};
constexpr int kTile = 16;  // both passes' work groups are kTile × kTile pixels

}  // namespace

TargetSet::TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference,
                     std::vector<render::Camera> cameras, int resolution, int supersampling)
    : programs_(programs),
      cameras_(std::move(cameras)),
      resolution_(resolution),
      supersampling_(std::max(1, supersampling)),
      colors_(GL_RGBA32F, resolution, resolution, std::max(1, int(cameras_.size()))) {
    for (int i = 0; i < size(); ++i) {
        // GL queues the draws: without waiting for each, the loop would be over long before
        // the renders are, and a stop request would only be seen after all of them.
        glFinish();
        throwIfStopRequested();
        drawn(i, [&](const render::Camera& camera, const render::RenderTarget& canvas) {
            reference.draw(programs, camera, canvas);
        });
        filterInto(colors_, i);
    }
}

TargetSet::~TargetSet() = default;
TargetSet::TargetSet(TargetSet&&) noexcept = default;

const render::RenderTarget& TargetSet::drawn(int i, const Draw& draw) const {
    const int fine = resolution_ * supersampling_;
    if (!canvas_) canvas_ = std::make_unique<render::RenderTarget>(fine, fine);
    draw(cameras_[size_t(i)], *canvas_);
    return *canvas_;
}

const gl::Program& TargetSet::overCanvas(const gl::ProgramSpec& spec, int layer) const {
    const gl::Program& program = programs_.get(spec);
    program.use();
    program.set("uFactor", supersampling_);
    program.set("uResolution", resolution_);
    program.set("uLayer", layer);
    canvas_->color().bindImageForReading(SUBDFIT_IMAGE_FINE);
    return program;
}

void TargetSet::filterInto(const gl::Texture& layers, int layer) const {
    overCanvas(kDownsample, layer);
    layers.bindImage(SUBDFIT_IMAGE_FILTERED, GL_WRITE_ONLY);
    glDispatchCompute(gl::groupsOf(resolution_, kTile), gl::groupsOf(resolution_, kTile), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

std::vector<glm::vec4> TargetSet::render(int i, const Draw& draw) const {
    drawn(i, draw);
    if (supersampling_ == 1) return canvas_->readColor();
    if (!filtered_.id()) filtered_ = gl::Texture(GL_RGBA32F, resolution_, resolution_, 1);
    filterInto(filtered_, 0);
    std::vector<glm::vec4> pixels(size_t(resolution_) * size_t(resolution_));
    glGetTextureImage(filtered_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

double TargetSet::loss(int i, const Draw& draw) const {
    drawn(i, draw);
    const GLuint groups = gl::groupsOf(resolution_, kTile);
    if (!groupSums_.id()) groupSums_ = gl::Buffer(GLsizeiptr(groups * groups * sizeof(float)));
    overCanvas(kViewLoss, i);
    colors_.bindImageForReading(SUBDFIT_IMAGE_TARGET);
    groupSums_.bindStorage(SUBDFIT_SSBO_VIEW_LOSS);
    glDispatchCompute(groups, groups, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    double sum = 0.0;
    for (float s : groupSums_.read<float>()) sum += double(s);
    return sum / (double(resolution_) * double(resolution_));
}

std::vector<glm::vec4> TargetSet::readColor(int i) const {
    std::vector<glm::vec4> pixels(size_t(resolution_) * resolution_);
    glGetTextureSubImage(colors_.id(), 0, 0, 0, i, resolution_, resolution_, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

}  // namespace subdfit::scene
