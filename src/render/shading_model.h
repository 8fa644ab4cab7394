#pragma once
// How a scene is lit and what its surface carries (glsl/shading.glsl). Every raster program
// takes the model as its variant bits 0-2, so a scene compiles the shading it uses and no other.
#include <string>
#include <vector>

#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::render {

enum class ShadingModel {
    Geometry,           // no material: grey Lambert under three coloured lights (shape only)
    Unlit,              // the base colour as it is (KHR_materials_unlit)
    Lambert,            // base colour, diffuse only, under the neutral light rig
    MetallicRoughness,  // glTF's BRDF: GGX specular + Lambert diffuse, under the neutral rig
};

const char* toString(ShadingModel model);  // "geometry", "unlit", "lambert", "pbr"
// The inverse; "auto" is the caller's (shadingFor). Throws subdfit::Error naming what it got.
ShadingModel parseShadingModel(const std::string& text);

// What a reference calls for: Geometry without materials or colours, Unlit when every material
// is unlit, MetallicRoughness when a material is metallic, less than fully rough or has a
// metallic-roughness texture, else Lambert.
ShadingModel shadingFor(const mesh::PolygonMesh& reference);

// The defines of bits 0-2 of every raster program's spec, and the bits of a model.
inline const std::vector<std::string> kShadingDefines{"SUBDFIT_SHADING_UNLIT", "SUBDFIT_SHADING_LAMBERT",
                                                      "SUBDFIT_SHADING_PBR"};
gl::VariantBits shadingBits(ShadingModel model);

}  // namespace subdfit::render
