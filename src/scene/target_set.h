#pragma once
// The target images: the reference rendered from every view once, kept on the GPU as a
// texture array that the gradient pass samples. Training and held-out views are separate sets.
// A set may be supersampled: each view rendered at `supersampling` times the resolution and
// box-filtered down, the anti-aliased image a viewer shows; whatever is compared with it is
// then drawn the same way (render()), so outlines score by their coverage, not by which single
// sample each pixel happened to take.
#include <functional>
#include <glm/vec4.hpp>
#include <memory>
#include <vector>

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

private:
    std::vector<render::Camera> cameras_;
    int resolution_, supersampling_;
    gl::Texture colors_;
    mutable std::unique_ptr<render::RenderTarget> canvas_;  // at the supersampled resolution, made on first use
};

}  // namespace subdfit::scene
