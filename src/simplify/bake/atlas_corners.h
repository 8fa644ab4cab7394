#pragma once
// Where each ptex face of a cage sits in the reference's texture atlas: the texture coordinates of
// its four corners (surface::AppearanceAtlas::cornerUvs). A 4 × 4 grid on the face's limit surface
// is cast along its normals to the reference; the hits that agree with their grid neighbours (a
// coordinate step no larger than the hit triangles' texture scale allows over their distance: a
// seam of the atlas breaks the chain) are fitted bilinearly, the largest agreeing set winning, so
// a face across a seam takes one side. Corners that meet at one limit point and agree are then
// welded: the texture is continuous inside a chart and split across a seam.
#include <glm/vec2.hpp>

#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

// 4 per ptex face of `cage`, at ptex (0, 0), (1, 0), (1, 1), (0, 1); rays reach `maxDistance`.
// A face no ray placed takes what its corners' neighbours agreed on.
std::vector<glm::vec2> atlasCornerUvs(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                      float maxDistance);

}  // namespace subdfit::simplify
