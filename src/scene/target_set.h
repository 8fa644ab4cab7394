#pragma once
// The target images: the reference rendered from every view once, kept on the GPU as a
// texture array that the gradient pass samples. Training and held-out views are separate sets.
// A set may be supersampled: each view rendered at `supersampling` times the resolution and
// box-filtered down on the GPU, the anti-aliased image a viewer shows; whatever is compared with
// it is then drawn the same way (render(), loss()), so outlines score by their coverage, not by
// which single sample each pixel happened to take.
#include <functional>
#include <glm/vec4.hpp>
#include <memory>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace subdfit::scene {

class TargetSet {
public:
    TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference, std::vector<render::Camera> cameras,
              int resolution, int supersampling = 1);
    ~TargetSet();
    TargetSet(TargetSet&&) noexcept;

    int size() const { return int(cameras_.size()); }
    int resolution() const { return resolution_; }
    int supersampling() const { return supersampling_; }
    const render::Camera& camera(int i) const { return cameras_[i]; }
    const gl::Texture& colors() const { return colors_; }
    std::vector<glm::vec4> readColor(int i) const;

    // What `draw` shows from view i, sampled and filtered as the targets were.
    using Draw = std::function<void(const render::Camera&, const render::RenderTarget&)>;
    std::vector<glm::vec4> render(int i, const Draw& draw) const;
    // The mean over view i's pixels of |drawn − target|² (RGB) of what render() would return:
    // computed where the images are, so only a few hundred sums are read back.
    double loss(int i, const Draw& draw) const;

private:
    const render::RenderTarget& drawn(int i, const Draw& draw) const;  // at the supersampled resolution
    void filterInto(const gl::Texture& layers, int layer) const;       // the canvas, as the targets are
    // `spec` (a pass over the canvas, glsl/supersampling.glsl) in use, its canvas and uniforms set.
    const gl::Program& overCanvas(const gl::ProgramSpec& spec, int layer) const;

    gl::ProgramCache& programs_;
    std::vector<render::Camera> cameras_;
    int resolution_, supersampling_;
    gl::Texture colors_;
    // Made on first use: the canvas, render()'s one filtered layer, loss()'s work groups' sums.
    mutable std::unique_ptr<render::RenderTarget> canvas_;
    mutable gl::Texture filtered_;
    mutable gl::Buffer groupSums_;
};

}  // namespace subdfit::scene
