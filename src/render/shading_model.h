#pragma once
// How a scene is lit and what its surface carries (glsl/shading.glsl). Every raster program
// takes the model as its variant bits 0-2, so a scene compiles the shading it uses and no other.
#include <string>
#include <vector>

#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"
#include "util/named_enum.h"

namespace subdfit::render {

enum class ShadingModel {
    Geometry,           // no material: grey Lambert under three coloured lights (shape only)
    Unlit,              // the base colour as it is (KHR_materials_unlit)
    Lambert,            // base colour, diffuse only, under the neutral light rig
    MetallicRoughness,  // glTF's BRDF: GGX specular + Lambert diffuse, under the neutral rig
};

// What a reference calls for: Geometry without materials or colours, Unlit when every material
// is unlit, MetallicRoughness when a material is metallic, less than fully rough or has a
// metallic-roughness texture, else Lambert.
ShadingModel shadingFor(const mesh::PolygonMesh& reference);

// The defines of bits 0-2 of every raster program's spec, and the bits of a model.
inline const std::vector<std::string> kShadingDefines{"SUBDFIT_SHADING_UNLIT", "SUBDFIT_SHADING_LAMBERT",
                                                      "SUBDFIT_SHADING_PBR"};
gl::VariantBits shadingBits(ShadingModel model);

}  // namespace subdfit::render

template <>
struct subdfit::EnumNames<subdfit::render::ShadingModel> {
    using M = render::ShadingModel;
    static constexpr std::array names{
        std::pair{M::Geometry, std::string_view("geometry")}, std::pair{M::Unlit, std::string_view("unlit")},
        std::pair{M::Lambert, std::string_view("lambert")}, std::pair{M::MetallicRoughness, std::string_view("pbr")}};
};
