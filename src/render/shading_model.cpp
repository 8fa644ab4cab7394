#include "render/shading_model.h"

#include <algorithm>

#include "util/error.h"

namespace subdfit::render {

ShadingModel shadingFor(const mesh::PolygonMesh& reference) {
    if (!reference.materials) return ShadingModel::Geometry;
    std::vector<char> used(reference.materials->materials.size(), 0);
    for (int m : reference.faceMaterials) used[size_t(m)] = 1;
    bool allUnlit = true, specular = false;
    for (size_t k = 0; k < used.size(); ++k) {
        if (!used[k]) continue;
        const mesh::Material& m = reference.materials->materials[k];
        allUnlit = allUnlit && m.unlit;
        specular =
            specular ||
            (!m.unlit && (m.metallicFactor > 0.0f || m.roughnessFactor < 1.0f || m.metallicRoughnessTexture.present()));
    }
    if (allUnlit) return ShadingModel::Unlit;
    return specular ? ShadingModel::MetallicRoughness : ShadingModel::Lambert;
}

gl::VariantBits shadingBits(ShadingModel model) {
    switch (model) {
        case ShadingModel::Unlit: return 1u << 0;
        case ShadingModel::Lambert: return 1u << 1;
        case ShadingModel::MetallicRoughness: return 1u << 2;
        case ShadingModel::Geometry: break;
    }
    return 0;
}

}  // namespace subdfit::render
