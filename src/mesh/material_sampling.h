#pragma once
// A reference's material evaluated on the CPU at a point of one of its triangles, as the
// reference renderer's fragment shader does (glsl/mesh.frag): what a bake reads.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

struct MaterialSample {
    glm::vec4 baseColor{1.0f};  // linear RGBA: factor × texture × vertex colour
    float roughness = 1.0f, metallic = 0.0f;
    float occlusion = 1.0f;    // 1 + strength × (texture − 1): 1 without an occlusion texture
    glm::vec3 emissive{0.0f};  // linear: factor × texture
};

// A texture's value at glTF texture coordinates `uv` (its KHR_texture_transform applied),
// bilinear with its wrap modes; decoded from sRGB when `srgb`.
glm::vec4 sampleTexture(const MaterialSet& set, const TextureRef& texture, glm::vec2 uv, bool srgb);

// The material of `triangle` at barycentrics (u, v): (1 − u − v)·p0 + u·p1 + v·p2. A mesh
// without materials is white, rough and not metallic.
MaterialSample sampleMaterial(const PolygonMesh& triangles, int triangle, float u, float v);

float srgbToLinear(float c);
float linearToSrgb(float c);

}  // namespace subdfit::mesh
