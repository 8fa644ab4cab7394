#pragma once
// The target images: the reference rendered from every view once, kept on the GPU as a
// texture array that the gradient pass samples. Training and held-out views are separate sets.
#include <glm/vec4.hpp>
#include <vector>

#include "gl/program_cache.h"
#include "gl/texture.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"

namespace subdfit::scene {

class TargetSet {
public:
    TargetSet(gl::ProgramCache& programs, const render::MeshRenderer& reference,
              std::vector<render::Camera> cameras, int resolution);

    int size() const { return int(cameras_.size()); }
    int resolution() const { return resolution_; }
    const render::Camera& camera(int i) const { return cameras_[i]; }
    const gl::Texture& colors() const { return colors_; }
    std::vector<glm::vec4> readColor(int i) const;

private:
    std::vector<render::Camera> cameras_;
    int resolution_;
    gl::Texture colors_;
};

}  // namespace subdfit::scene
