#include "subdiv/uniform_refinement.h"

#include <opensubdiv/far/primvarRefiner.h>

#include <glm/vec3.hpp>

#include "subdiv/topology.h"
#include "util/error.h"

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

// What PrimvarRefiner interpolates: a point with the operations it needs.
struct Point {
    glm::vec3 p{0.0f};
    void Clear(void* = nullptr) { p = glm::vec3(0.0f); }
    void AddWithWeight(const Point& other, float weight) { p += weight * other.p; }
};

// The refined cage's tags from level 1. Far sharpens boundary edges (and, with edge-and-corner,
// the vertices of one face) itself; tagging them again would only repeat what the rule says.
void copyTags(const Far::TopologyLevel& level, const mesh::SubdivisionTags& rules, mesh::PolygonMesh& out) {
    const bool sharpBoundary = rules.boundary != mesh::BoundaryInterpolation::None;
    const bool sharpCorners = rules.boundary == mesh::BoundaryInterpolation::EdgeAndCorner;
    for (int v = 0; v < level.GetNumVertices(); ++v) {
        const bool implied = sharpCorners && level.GetVertexFaces(v).size() == 1;
        if (const float s = level.GetVertexSharpness(v); s > 0.0f && !implied) out.tags.corners.push_back({v, s});
    }
    for (int f = 0; f < level.GetNumFaces(); ++f)
        if (level.IsFaceHole(f)) out.tags.holes.push_back(f);
    for (int e = 0; e < level.GetNumEdges(); ++e) {
        const bool implied = sharpBoundary && level.GetEdgeFaces(e).size() == 1;
        if (const float s = level.GetEdgeSharpness(e); s > 0.0f && !implied) {
            const auto ends = level.GetEdgeVertices(e);
            out.tags.creases.push_back({ends[0], ends[1], s});
        }
    }
}

// Where a level-1 vertex lies on base face f's ptex parametrisation: f's corner k, the middle
// of its edge k (from corner k to k + 1), or its centre. A quad's (u, v) run along its edges 0
// and 3; an n-gon's ptex face k has its origin at corner k, u towards the middle of edge k and v
// towards the middle of edge k − 1 (Far::PtexIndices, OpenSubdiv's parametrisation).
glm::vec2 ptexUvOf(const Far::TopologyLevel& base, int f, int k, int child) {
    const auto corners = base.GetFaceVertices(f);
    const auto edges = base.GetFaceEdges(f);
    const int n = corners.size();
    if (child == base.GetFaceChildVertex(f)) return n == 4 ? glm::vec2(0.5f) : glm::vec2(1.0f);
    if (n == 4) {
        static constexpr glm::vec2 kCorner[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int c = 0; c < 4; ++c) {
            if (child == base.GetVertexChildVertex(corners[c])) return kCorner[c];
            if (child == base.GetEdgeChildVertex(edges[c])) return 0.5f * (kCorner[c] + kCorner[(c + 1) % 4]);
        }
    } else {
        if (child == base.GetVertexChildVertex(corners[k])) return {0, 0};
        if (child == base.GetEdgeChildVertex(edges[k])) return {1, 0};
        if (child == base.GetEdgeChildVertex(edges[(k + n - 1) % n])) return {0, 1};
    }
    SUBDFIT_CHECK(!"a child face's corner is not one of its parent's points");
    return {};
}

RefinedCage refine(const mesh::PolygonMesh& cage, bool withPtex) {
    RefinerPtr refiner = buildTopologyRefiner(cage);
    Far::TopologyRefiner::UniformOptions options(1);
    options.fullTopologyInLastLevel = true;  // its edges, for the creases
    refiner->RefineUniform(options);
    const Far::TopologyLevel& base = refiner->GetLevel(0);
    const Far::TopologyLevel& level = refiner->GetLevel(1);

    std::vector<Point> points(size_t(refiner->GetNumVerticesTotal()));
    for (int v = 0; v < cage.vertexCount(); ++v) points[size_t(v)].p = cage.positions[size_t(v)];
    Point* refined = points.data() + cage.vertexCount();
    Far::PrimvarRefiner(*refiner).Interpolate(1, points.data(), refined);

    RefinedCage out;
    out.mesh.sourcePath = cage.sourcePath;
    out.mesh.tags = cage.tags;
    out.mesh.tags.creases.clear();
    out.mesh.tags.corners.clear();
    out.mesh.tags.holes.clear();
    for (int v = 0; v < level.GetNumVertices(); ++v) out.mesh.positions.push_back(refined[v].p);
    for (int f = 0; f < level.GetNumFaces(); ++f) {
        const auto corners = level.GetFaceVertices(f);
        out.mesh.faceSizes.push_back(corners.size());
        for (int k = 0; k < corners.size(); ++k) out.mesh.faceIndices.push_back(corners[k]);
    }
    copyTags(level, cage.tags, out.mesh);
    if (!withPtex) return out;

    out.ptexFace.resize(size_t(level.GetNumFaces()));
    out.cornerUv.resize(4 * size_t(level.GetNumFaces()));
    for (int f = 0, ptex = 0; f < base.GetNumFaces(); ++f) {
        const auto children = base.GetFaceChildFaces(f);
        const bool quad = children.size() == 4 && base.GetFaceVertices(f).size() == 4;
        for (int k = 0; k < children.size(); ++k) {
            const int child = children[k];
            out.ptexFace[size_t(child)] = quad ? ptex : ptex + k;
            const auto corners = level.GetFaceVertices(child);
            for (int c = 0; c < 4; ++c) out.cornerUv[4 * size_t(child) + size_t(c)] = ptexUvOf(base, f, k, corners[c]);
        }
        ptex += quad ? 1 : children.size();
    }
    return out;
}

}  // namespace

mesh::PolygonMesh refinedOnce(const mesh::PolygonMesh& cage) { return refine(cage, false).mesh; }

RefinedCage refinedOnceWithPtex(const mesh::PolygonMesh& cage) { return refine(cage, true); }

}  // namespace subdfit::subdiv
