#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/atlas_corners.h"
#include "simplify/bake/atlas_shading_normals.h"

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

// Which of a grid × grid lattice of sample points (at cell centres, over [0, 1]²) some triangle
// of the reference covers in texture space: the texture's charts, without its gutter.
std::vector<char> chartCoverage(const mesh::PolygonMesh& reference, int grid) {
    std::vector<char> covered(size_t(grid) * size_t(grid), 0);
    for (int f = 0; f < reference.faceCount(); ++f) {
        glm::vec2 t[3];
        for (int k = 0; k < 3; ++k)
            t[k] = reference.uvs[size_t(reference.faceIndices[size_t(3 * f + k)])] * float(grid);
        const float area = (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
        if (!(std::abs(area) > 0.0f)) continue;
        const auto lo = glm::max(glm::floor(glm::min(t[0], glm::min(t[1], t[2]))), glm::vec2(0.0f));
        const auto hi = glm::min(glm::ceil(glm::max(t[0], glm::max(t[1], t[2]))), glm::vec2(float(grid)));
        for (int y = int(lo.y); y < int(hi.y); ++y)
            for (int x = int(lo.x); x < int(hi.x); ++x) {
                const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
                bool inside = true;
                for (int k = 0; k < 3 && inside; ++k) {
                    const glm::vec2 a = t[k], b = t[(k + 1) % 3];
                    inside = ((b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y)) * area >= 0.0f;
                }
                if (inside) covered[size_t(y) * size_t(grid) + size_t(x)] = 1;
            }
    }
    return covered;
}

// Texels no chart reaches take their reached neighbours' mean, ring by ring (a few rings: as far
// as a ptex face's coordinates or the bilinear filter stray past a chart's edge), then the mean
// of the whole: the gutter continues each chart instead of pulling its border towards the
// texture's background, which a coarse atlas would otherwise mix into every border texel.
class GutterFill {
public:
    GutterFill(const std::vector<char>& reached, int size) : size_(size), ring_(reached.size(), kNever) {
        for (size_t t = 0; t < reached.size(); ++t)
            if (reached[t]) ring_[t] = 0;
        for (int ring = 1; ring <= kRings; ++ring)
            for (int j = 0; j < size; ++j)
                for (int i = 0; i < size; ++i)
                    if (ring_[at(i, j)] == kNever && !earlierNeighbours(i, j, ring).empty()) ring_[at(i, j)] = ring;
    }

    // Fills `values` (`channels` per texel, row by row) where no chart reaches.
    void operator()(std::vector<float>& values, size_t channels) const {
        if (values.empty()) return;
        for (int ring = 1; ring <= kRings; ++ring)
            for (int j = 0; j < size_; ++j)
                for (int i = 0; i < size_; ++i) {
                    if (ring_[at(i, j)] != ring) continue;
                    const std::vector<size_t> from = earlierNeighbours(i, j, ring);
                    for (size_t k = 0; k < channels; ++k) {
                        float sum = 0.0f;
                        for (size_t n : from) sum += values[channels * n + k];
                        values[channels * at(i, j) + k] = sum / float(from.size());
                    }
                }
        std::vector<double> mean(channels, 0.0);
        size_t filled = 0;
        for (size_t t = 0; t < ring_.size(); ++t)
            if (ring_[t] != kNever) {
                ++filled;
                for (size_t k = 0; k < channels; ++k) mean[k] += values[channels * t + k];
            }
        for (size_t t = 0; t < ring_.size(); ++t)
            if (ring_[t] == kNever)
                for (size_t k = 0; k < channels; ++k)
                    values[channels * t + k] = filled ? float(mean[k] / double(filled)) : 0.0f;
    }

private:
    static constexpr int kRings = 8, kNever = -1;
    size_t at(int i, int j) const { return size_t(j) * size_t(size_) + size_t(i); }

    std::vector<size_t> earlierNeighbours(int i, int j, int ring) const {
        std::vector<size_t> out;
        for (int y = std::max(j - 1, 0); y <= std::min(j + 1, size_ - 1); ++y)
            for (int x = std::max(i - 1, 0); x <= std::min(i + 1, size_ - 1); ++x) {
                const int r = ring_[at(x, y)];
                if (r != kNever && r < ring && (x != i || y != j)) out.push_back(at(x, y));
            }
        return out;
    }

    int size_;
    std::vector<int> ring_;  // the ring a texel is filled in: 0 reached by a chart, kNever beyond the rings
};

// What of the material an atlas carries beside its colour and metallic-roughness.
struct AtlasChannels {
    bool normal = false, occlusion = false, emissive = false;
};

// The material summed over the samples of one texel's square that a chart covers.
struct TexelSum {
    glm::vec3 color{0.0f}, normal{0.0f}, emission{0.0f};
    glm::vec2 roughnessMetallic{0.0f};
    float occlusion = 0.0f;
    int count = 0;
};

// Texel (i, j) of a size × size atlas, `samples` × `samples` points a texel, where `covered`
// (chartCoverage at size × samples) says a chart reaches.
TexelSum sumTexel(const mesh::MaterialSet& set, const mesh::Material& m, AtlasChannels channels,
                  const std::vector<char>& covered, int size, int samples, int i, int j) {
    TexelSum sum;
    for (int b = 0; b < samples; ++b)
        for (int a = 0; a < samples; ++a) {
            if (!covered[size_t(j * samples + b) * size_t(size * samples) + size_t(i * samples + a)]) continue;
            ++sum.count;
            const glm::vec2 uv((float(i) + (float(a) + 0.5f) / float(samples)) / float(size),
                               (float(j) + (float(b) + 0.5f) / float(samples)) / float(size));
            sum.color +=
                glm::vec3(m.baseColorFactor) * glm::vec3(mesh::sampleTexture(set, m.baseColorTexture, uv, true));
            const glm::vec4 t = mesh::sampleTexture(set, m.metallicRoughnessTexture, uv, false);
            sum.roughnessMetallic += glm::vec2(m.roughnessFactor * t.g, m.metallicFactor * t.b);
            if (channels.normal) {
                glm::vec3 tangent = glm::vec3(mesh::sampleTexture(set, m.normalTexture, uv, false)) * 2.0f - 1.0f;
                tangent.x *= m.normalScale, tangent.y *= m.normalScale;
                if (glm::length(tangent) > 1e-6f) sum.normal += glm::normalize(tangent);
            }
            if (channels.occlusion)
                sum.occlusion +=
                    1.0f + m.occlusionStrength * (mesh::sampleTexture(set, m.occlusionTexture, uv, false).r - 1.0f);
            if (channels.emissive)
                sum.emission += m.emissiveFactor * glm::vec3(mesh::sampleTexture(set, m.emissiveTexture, uv, true));
        }
    return sum;
}

// An atlas's texel values, row by row, as they are baked.
struct AtlasTexels {
    std::vector<float> color, roughnessMetallic, normals, occlusions, emission;
    std::vector<char> reached;  // by a chart

    explicit AtlasTexels(size_t texels) : color(3 * texels), roughnessMetallic(2 * texels), reached(texels, 0) {}

    // Texel `texel`, the next in order, the mean of `sum` (colours back in sRGB).
    void add(size_t texel, const TexelSum& sum, AtlasChannels channels) {
        reached[texel] = sum.count > 0;
        const float count = float(std::max(sum.count, 1));
        auto srgb = [](float linear) { return std::clamp(mesh::linearToSrgb(linear), 0.0f, 1.0f); };
        for (int k = 0; k < 3; ++k) color[3 * texel + size_t(k)] = srgb(sum.color[k] / count);
        roughnessMetallic[2 * texel] = std::clamp(sum.roughnessMetallic.x / count, 0.0f, 1.0f);
        roughnessMetallic[2 * texel + 1] = std::clamp(sum.roughnessMetallic.y / count, 0.0f, 1.0f);
        if (channels.normal) {
            const glm::vec3 unit =
                glm::length(sum.normal) > 1e-6f ? glm::normalize(sum.normal) : glm::vec3(0.0f, 0.0f, 1.0f);
            for (int k = 0; k < 3; ++k) normals.push_back(unit[k] * 0.5f + 0.5f);
        }
        if (channels.occlusion) occlusions.push_back(std::clamp(sum.occlusion / count, 0.0f, 1.0f));
        if (channels.emissive)
            for (int k = 0; k < 3; ++k) emission.push_back(srgb(sum.emission[k] / count));
    }
};

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
        if (t->present() && t->uvTransform != glm::mat3(1.0f))
            return "its textures are transformed (KHR_texture_transform)";
    for (const glm::vec2& uv : reference.uvs)
        if (!(uv.x >= -kUvSlack && uv.y >= -kUvSlack && uv.x <= 1.0f + kUvSlack && uv.y <= 1.0f + kUvSlack))
            return "its texture coordinates leave [0, 1]";
    return "";
}

CarriedLook carriedLookOf(const mesh::PolygonMesh& reference) {
    CarriedLook look;
    if (!reference.materials) return look;
    std::vector<char> used(reference.materials->materials.size(), 0);
    for (int k : reference.faceMaterials) used[size_t(k)] = 1;
    for (size_t k = 0; k < used.size(); ++k) {
        if (!used[k]) continue;
        const mesh::Material& m = reference.materials->materials[k];
        look.normalTexture = look.normalTexture || m.normalTexture.present();
        look.occlusion = look.occlusion || m.occlusionTexture.present();
        look.emission = look.emission || m.emissiveFactor != glm::vec3(0.0f);
    }
    return look;
}

std::string lostOnTiles(const mesh::PolygonMesh& reference, bool metallicRoughness) {
    const CarriedLook look = carriedLookOf(reference);
    std::string list;
    if (look.normalTexture) list = "normal texture";
    if (look.occlusion && !metallicRoughness) list += (list.empty() ? "" : ", ") + std::string("occlusion texture");
    return list;
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
                                         maps::MapEffects effects, int size, float maxDistance, bool shadingNormals) {
    SUBDFIT_CHECK(size >= 2 && atlasUnsuitability(reference).empty());
    const mesh::Material& m = *atlasMaterial(reference);
    surface::SurfaceMaps maps;
    maps.appearanceLayout = surface::atlasLattice(size);
    maps.appearanceAtlas = {
        .size = size,
        .cornerUvs = atlasCornerUvs(cage, reference, maxDistance > 0.0f ? maxDistance : mesh::meanEdgeLength(cage))};
    // Each texel the mean of the material over the part of its square that a chart covers (a
    // box filter in linear units, as a renderer's mip chain, without the gutter), a few samples
    // a source texel.
    const int samples = std::clamp((atlasSourceSize(reference) + size - 1) / size, 1, 8);
    const std::vector<char> covered = chartCoverage(reference, size * samples);
    const AtlasChannels channels{.normal = m.normalTexture.present(),
                                 .occlusion = m.occlusionTexture.present(),
                                 .emissive = m.emissiveFactor != glm::vec3(0.0f)};
    const size_t texels = size_t(size) * size_t(size);
    AtlasTexels baked(texels);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
            baked.add(size_t(j) * size_t(size) + size_t(i),
                      sumTexel(*reference.materials, m, channels, covered, size, samples, i, j), channels);
    if (shadingNormals) {
        if (baked.normals.empty())
            for (size_t t = 0; t < texels; ++t) baked.normals.insert(baked.normals.end(), {0.5f, 0.5f, 1.0f});
        carryShadingNormals(cage, maps, reference, maxDistance > 0.0f ? maxDistance : mesh::meanEdgeLength(cage),
                            baked.normals);
    }
    const GutterFill fillGutter(baked.reached, size);
    fillGutter(baked.color, 3);
    fillGutter(baked.roughnessMetallic, 2);
    fillGutter(baked.normals, 3);
    fillGutter(baked.occlusions, 1);
    fillGutter(baked.emission, 3);
    if (effects.has(maps::MapKind::BaseColor)) maps.baseColor = std::move(baked.color);
    if (effects.has(maps::MapKind::MetallicRoughness)) maps.metallicRoughness = std::move(baked.roughnessMetallic);
    // Occlusion rides in the metallic-roughness image's red channel (glTF's occlusion-roughness-
    // metallic packing), so only a scene with that image keeps it.
    maps.normalTexture = std::move(baked.normals);
    if (effects.has(maps::MapKind::MetallicRoughness)) maps.occlusion = std::move(baked.occlusions);
    maps.emissive = std::move(baked.emission);
    return maps;
}

}  // namespace subdfit::simplify
