#include "surface/appearance_atlas.h"

#include <glm/common.hpp>

#include <numeric>

#include "util/error.h"

namespace subdfit::surface {

TexelLayout atlasLattice(int size) {
    SUBDFIT_CHECK(size >= 2 && size <= 4096);
    TexelLayout layout;
    layout.resolution = size - 1;
    layout.ptexFaceCount = 1;
    layout.nodeCount = size * size;
    layout.faceNodes.resize(size_t(layout.nodeCount));
    std::iota(layout.faceNodes.begin(), layout.faceNodes.end(), 0);
    layout.halo.assign(4 * size_t(size), -1);
    return layout;
}

int cornerPoint(const TexelLayout& corners, int face, int corner) {
    static constexpr int kI[4] = {0, 1, 1, 0}, kJ[4] = {0, 0, 1, 1};
    return corners.node(face, kI[corner], kJ[corner]);
}

glm::vec2 atlasUvAt(const AppearanceAtlas& atlas, int face, float u, float v) {
    u = glm::clamp(u, 0.0f, 1.0f), v = glm::clamp(v, 0.0f, 1.0f);
    const glm::vec2* c = &atlas.cornerUvs[4 * size_t(face)];
    return glm::mix(glm::mix(c[0], c[1], u), glm::mix(c[3], c[2], u), v);
}

glm::vec2 latticeUv(int size, glm::vec2 atlasUv) {
    return glm::clamp((atlasUv * float(size) - 0.5f) / float(size - 1), 0.0f, 1.0f);
}

}  // namespace subdfit::surface
