#include "subdiv/uniform_refinement.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <glm/vec3.hpp>

#include "subdiv/topology.h"

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

// What PrimvarRefiner interpolates: a point with the operations it needs.
struct Point {
    glm::vec3 p{0.0f};
    void Clear(void* = nullptr) { p = glm::vec3(0.0f); }
    void AddWithWeight(const Point& other, float weight) { p += weight * other.p; }
};

}  // namespace

mesh::PolygonMesh refinedOnce(const mesh::PolygonMesh& cage) {
    RefinerPtr refiner = buildTopologyRefiner(cage);
    Far::TopologyRefiner::UniformOptions options(1);
    options.fullTopologyInLastLevel = true;  // its edges, for the creases
    refiner->RefineUniform(options);
    const Far::TopologyLevel& level = refiner->GetLevel(1);

    std::vector<Point> points(size_t(refiner->GetNumVerticesTotal()));
    for (int v = 0; v < cage.vertexCount(); ++v) points[size_t(v)].p = cage.positions[size_t(v)];
    Point* refined = points.data() + cage.vertexCount();
    Far::PrimvarRefiner(*refiner).Interpolate(1, points.data(), refined);

    mesh::PolygonMesh out;
    out.sourcePath = cage.sourcePath;
    out.tags = cage.tags;
    out.tags.creases.clear();
    out.tags.corners.clear();
    out.tags.holes.clear();
    for (int v = 0; v < level.GetNumVertices(); ++v) {
        out.positions.push_back(points[size_t(cage.vertexCount() + v)].p);
        if (const float s = level.GetVertexSharpness(v); s > 0.0f) out.tags.corners.push_back({v, s});
    }
    for (int f = 0; f < level.GetNumFaces(); ++f) {
        const auto corners = level.GetFaceVertices(f);
        out.faceSizes.push_back(corners.size());
        for (int k = 0; k < corners.size(); ++k) out.faceIndices.push_back(corners[k]);
        if (level.IsFaceHole(f)) out.tags.holes.push_back(f);
    }
    for (int e = 0; e < level.GetNumEdges(); ++e)
        if (const float s = level.GetEdgeSharpness(e); s > 0.0f) {
            const auto ends = level.GetEdgeVertices(e);
            out.tags.creases.push_back({ends[0], ends[1], s});
        }
    return out;
}

}  // namespace subdfit::subdiv
