#pragma once
// The cage as a UsdGeomMesh: Catmull-Clark with the rules subdfit evaluates, its creases, corners
// and holes, and face-varying texture coordinates that place every ptex tile of the maps exactly.
//
// A renderer blends a face's corner `st` bilinearly across the face (faceVaryingLinearInterpolation
// "all"), which is how subdfit samples a tile on a ptex face: on a quad, the tile's four corners
// make it exact. A triangle or an n-gon has n ptex faces, and no n corner values place n
// axis-aligned square tiles. So a cage with such faces whose maps need texture coordinates is
// written refined once (subdiv::refinedOnceWithPtex): all quads, the same limit surface, each
// face inside one ptex face. Any other cage is written as it is: the cage an artist edits.
#include <functional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "export/usd/usda_text.h"
#include "subdiv/uniform_refinement.h"

namespace subdfit::exporter {

// A face-varying set of texture coordinates: USD's `st` (origin at the image's bottom left) of
// ptex (u, v) on a ptex face of the cage.
struct UsdTexCoords {
    std::string primvar;  // e.g. "st"
    std::function<glm::vec2(int ptexFace, glm::vec2 uv)> at;
};

struct UsdCageOptions {
    std::string name = "Cage";
    std::string material;  // the bound material's path; "" for none
    // How far the displacement may move the surface: widens the extent, and is RenderMan's
    // displacement bound.
    float reach = 0.0f;
};

// The cage as it goes into USD (see above); `texCoords`: whether any map needs them. Left as it
// is, an all-quad cage's faces are their own ptex faces; a cage with other faces and no maps
// has no ptex correspondence (ptexFace empty).
subdiv::RefinedCage usdCageOf(const mesh::PolygonMesh& cage, bool texCoords);

// The Mesh prim `options.name` into `layer`, inside the current block. `texCoords` needs
// cage.ptexFace.
void writeCagePrim(usda::Layer& layer, const subdiv::RefinedCage& cage, const std::vector<UsdTexCoords>& texCoords,
                   const UsdCageOptions& options);

// The rules' tokens as USD spells them.
std::string usdBoundaryToken(mesh::BoundaryInterpolation boundary);
std::string usdTriangleToken(mesh::TriangleSubdivision triangles);

}  // namespace subdfit::exporter
