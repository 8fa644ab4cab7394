#include "simplify/atlas_bake.h"
#include "simplify/atlas_corners.h"

#include <glm/geometric.hpp>

#include <algorithm>

#include "mesh/material_sampling.h"
#include "mesh/mesh_geometry.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

// Coordinates this far outside [0, 1] still read the edge texels as the reference renders them
// (a clamped or a repeated texture agree there only to within a texel).
constexpr float kUvSlack = 1e-3f;

const mesh::Material* atlasMaterial(const mesh::PolygonMesh& reference) {
    if (!reference.materials || reference.faceMaterials.empty()) return nullptr;
    return &reference.materials->materials[size_t(reference.faceMaterials.front())];
}

}  // namespace

std::string atlasUnsuitability(const mesh::PolygonMesh& reference) {
    const mesh::Material* m = atlasMaterial(reference);
    if (!m) return "it has no material";
    if (reference.uvs.empty()) return "it has no texture coordinates";
    if (!reference.colors.empty()) return "it has vertex colours";
    if (std::any_of(reference.faceMaterials.begin(), reference.faceMaterials.end(),
                    [&](int k) { return k != reference.faceMaterials.front(); }))
        return "it has several materials";
    if (!m->baseColorTexture.present() && !m->metallicRoughnessTexture.present()) return "its material has no texture";
    for (const mesh::TextureRef* t : {&m->baseColorTexture, &m->metallicRoughnessTexture})
        if (t->present() && t->uvTransform != glm::mat3(1.0f)) return "its textures are transformed (KHR_texture_transform)";
    for (const glm::vec2& uv : reference.uvs)
        if (!(uv.x >= -kUvSlack && uv.y >= -kUvSlack && uv.x <= 1.0f + kUvSlack && uv.y <= 1.0f + kUvSlack))
            return "its texture coordinates leave [0, 1]";
    return "";
}

int atlasSourceSize(const mesh::PolygonMesh& reference) {
    const mesh::Material* m = atlasMaterial(reference);
    if (!m) return 0;
    int size = 0;
    for (const mesh::TextureRef* t : {&m->baseColorTexture, &m->metallicRoughnessTexture})
        if (t->present()) {
            const mesh::Image& image = reference.materials->images[size_t(t->image)];
            size = std::max({size, image.width, image.height});
        }
    return size;
}

surface::SurfaceMaps bakeAtlasAppearance(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                         maps::MapEffects effects, int size, float maxDistance) {
    SUBDFIT_CHECK(size >= 2 && atlasUnsuitability(reference).empty());
    const mesh::Material& m = *atlasMaterial(reference);
    const mesh::MaterialSet& set = *reference.materials;
    surface::SurfaceMaps maps;
    maps.appearanceLayout = surface::atlasLattice(size);
    maps.appearanceAtlas = {.size = size,
                            .cornerUvs = atlasCornerUvs(cage, reference, maxDistance > 0.0f ? maxDistance : mesh::meanEdgeLength(cage))};
    // Each texel the mean of the material over its square (a box filter in linear units, as
    // a renderer's mip chain), a few samples a source texel.
    const int samples = std::clamp((atlasSourceSize(reference) + size - 1) / size, 1, 8);
    const size_t texels = size_t(size) * size_t(size);
    const bool normal = m.normalTexture.present(), occlusion = m.occlusionTexture.present(),
               emissive = m.emissiveFactor != glm::vec3(0.0f);
    std::vector<float> color(3 * texels), roughnessMetallic(2 * texels), normals, occlusions, emission;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            glm::vec3 c(0.0f), n(0.0f), e(0.0f);
            glm::vec2 rm(0.0f);
            float o = 0.0f;
            for (int b = 0; b < samples; ++b)
                for (int a = 0; a < samples; ++a) {
                    const glm::vec2 uv((float(i) + (float(a) + 0.5f) / float(samples)) / float(size),
                                       (float(j) + (float(b) + 0.5f) / float(samples)) / float(size));
                    c += glm::vec3(m.baseColorFactor) * glm::vec3(mesh::sampleTexture(set, m.baseColorTexture, uv, true));
                    const glm::vec4 t = mesh::sampleTexture(set, m.metallicRoughnessTexture, uv, false);
                    rm += glm::vec2(m.roughnessFactor * t.g, m.metallicFactor * t.b);
                    if (normal) {
                        glm::vec3 tangent = glm::vec3(mesh::sampleTexture(set, m.normalTexture, uv, false)) * 2.0f - 1.0f;
                        tangent.x *= m.normalScale, tangent.y *= m.normalScale;
                        if (glm::length(tangent) > 1e-6f) n += glm::normalize(tangent);
                    }
                    if (occlusion) o += 1.0f + m.occlusionStrength * (mesh::sampleTexture(set, m.occlusionTexture, uv, false).r - 1.0f);
                    if (emissive) e += m.emissiveFactor * glm::vec3(mesh::sampleTexture(set, m.emissiveTexture, uv, true));
                }
            const float count = float(samples * samples);
            const size_t texel = size_t(j) * size_t(size) + size_t(i);
            auto srgb = [](float linear) { return std::clamp(mesh::linearToSrgb(linear), 0.0f, 1.0f); };
            for (int k = 0; k < 3; ++k) color[3 * texel + size_t(k)] = srgb(c[k] / count);
            roughnessMetallic[2 * texel] = std::clamp(rm.x / count, 0.0f, 1.0f);
            roughnessMetallic[2 * texel + 1] = std::clamp(rm.y / count, 0.0f, 1.0f);
            if (normal) {
                const glm::vec3 unit = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
                for (int k = 0; k < 3; ++k) normals.push_back(unit[k] * 0.5f + 0.5f);
            }
            if (occlusion) occlusions.push_back(std::clamp(o / count, 0.0f, 1.0f));
            if (emissive)
                for (int k = 0; k < 3; ++k) emission.push_back(srgb(e[k] / count));
        }
    if (effects.baseColor) maps.baseColor = std::move(color);
    if (effects.metallicRoughness) maps.metallicRoughness = std::move(roughnessMetallic);
    // Occlusion rides in the metallic-roughness image's red channel (glTF's occlusion-roughness-
    // metallic packing), so only a scene with that image keeps it.
    maps.normalTexture = std::move(normals);
    if (effects.metallicRoughness) maps.occlusion = std::move(occlusions);
    maps.emissive = std::move(emission);
    return maps;
}

}  // namespace subdfit::simplify
