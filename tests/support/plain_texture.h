#pragma once
// One material with a white base colour texture on every face: the least a reference needs to
// keep its appearance in its own atlas (simplify/bake/atlas_bake.h), with nothing to see in it.
#include <memory>

#include "mesh/material.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::test {

inline void paintWhite(mesh::PolygonMesh& reference) {
    mesh::Image white{.name = "white", .width = 4, .height = 4, .rgba = std::vector<std::uint8_t>(64, 255)};
    mesh::Material m = mesh::defaultMaterial();
    m.baseColorTexture.image = 0;
    reference.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{m}, {white}});
    reference.faceMaterials.assign(size_t(reference.faceCount()), 0);
}

}  // namespace subdfit::test
