#pragma once
// A cage's maps as CPU values: node values on the shared texel layout, before any packing into
// images. What the displaced surface is evaluated from, what a bake produces, what exporters read.
#include <string_view>
#include <vector>

#include "kinds/map_kinds.h"
#include "surface/appearance_atlas.h"
#include "surface/texel_layout.h"
#include "util/named_enum.h"

namespace subdfit::surface {

// What shades a displaced surface. Displaced: its own normal, the heights' slopes tilting the
// limit normal (relief the heights carry shows). Limit: the limit surface's, the heights only
// placing the surface: a light reference's flat triangles shaded with smooth vertex normals,
// whose facets heights baked onto them would otherwise copy into the shading.
enum class ShadingNormal { Displaced, Limit };

}  // namespace subdfit::surface

template <>
struct subdfit::EnumNames<subdfit::surface::ShadingNormal> {
    static constexpr std::array names{std::pair{surface::ShadingNormal::Displaced, std::string_view("displaced")},
                                      std::pair{surface::ShadingNormal::Limit, std::string_view("limit")}};
};

namespace subdfit::surface {

struct SurfaceMaps {
    TexelLayout layout;  // resolution 0: no maps at all
    // layout.nodeCount heights along the limit normal, in the cage's units; empty = no
    // displacement map.
    std::vector<float> displacement;
    ShadingNormal shadingNormal = ShadingNormal::Displaced;  // with a displacement
    // 2 per node: tangent-space (x, y); the normal is normalize(x, y, 1) in the frame
    // (dPdu, dPdv, N) of the limit surface; empty = no normal map.
    std::vector<float> normal;

    // The appearance maps, on a lattice of their own (resolution 0: none): 3 per node, the sRGB
    // base colour in [0, 1]; 2 per node, (roughness, metallic) in [0, 1]; empty = none. With an
    // atlas the lattice is its texel grid (atlasLattice) and the corners' atlas coordinates place
    // it on the surface; without, per-face tiles.
    TexelLayout appearanceLayout;
    AppearanceAtlas appearanceAtlas;
    std::vector<float> baseColor;
    std::vector<float> metallicRoughness;
    // With an atlas, the reference's other textures on the same texel grid: not fitted, but its
    // renders show them, so the asset's must. The tangent-space normal as a glTF normal texture's
    // rgb in [0, 1] (3 per texel, the normal scale folded in; its frame is the atlas coordinates'
    // own, as a renderer without tangents derives it); occlusion (1 per texel, the strength
    // folded in); emissive (3 per texel, sRGB, the factor folded in). Empty = none.
    std::vector<float> normalTexture, occlusion, emissive;

    // Each kind's node values (kinds/map_kinds.h), for code that is the same for every kind.
    std::vector<float>& values(kinds::MapKind kind) { return this->*kValues[size_t(kind)]; }
    const std::vector<float>& values(kinds::MapKind kind) const { return this->*kValues[size_t(kind)]; }
    bool has(kinds::MapKind kind) const { return !values(kind).empty(); }
    // The kinds present.
    kinds::MapKinds kinds() const {
        kinds::MapKinds out;
        for (const kinds::MapKindInfo& i : kinds::kMapKinds) out.set(i.kind, has(i.kind));
        return out;
    }

    // The appearance of `other` (lattice, atlas and values) in place of this one's.
    void setAppearance(const SurfaceMaps& other) {
        appearanceLayout = other.appearanceLayout;
        appearanceAtlas = other.appearanceAtlas;
        for (const kinds::MapKindInfo& i : kinds::kMapKinds)
            if (i.lattice == kinds::MapLattice::Appearance) values(i.kind) = other.values(i.kind);
        normalTexture = other.normalTexture;
        occlusion = other.occlusion;
        emissive = other.emissive;
    }

    bool hasDisplacement() const { return !displacement.empty(); }
    bool hasNormal() const { return !normal.empty(); }
    bool hasBaseColor() const { return !baseColor.empty(); }
    bool hasMetallicRoughness() const { return !metallicRoughness.empty(); }

private:
    static constexpr std::array<std::vector<float> SurfaceMaps::*, kinds::kMapKindCount> kValues{
        &SurfaceMaps::displacement, &SurfaceMaps::normal, &SurfaceMaps::baseColor, &SurfaceMaps::metallicRoughness};
};

}  // namespace subdfit::surface
