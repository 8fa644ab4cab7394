#pragma once
// One value per node of a cage's texel layout, from where the node lies on the limit surface:
// continuous across tiles, as a baked map is. (Holes have no surface: their nodes keep 0.)
#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/polygon_mesh.h"
#include "surface/tessellation.h"
#include "surface/texel_layout.h"

namespace subdfit::test {

template <class Value>
std::vector<float> valuesOnLimit(const mesh::PolygonMesh& cage, const surface::TexelLayout& layout, Value value) {
    const int T = layout.resolution;
    std::vector<float> values(size_t(layout.nodeCount), 0.0f);
    const auto limit = surface::tessellate(cage, {}, T);
    for (size_t k = 0; k < limit.vertexCount(); ++k) {
        const auto& at = limit.ptex[k];
        const int node = layout.node(at.face, int(std::lround(at.u * float(T))), int(std::lround(at.v * float(T))));
        values[size_t(node)] = value(limit.positions[k]);
    }
    return values;
}

}  // namespace subdfit::test
