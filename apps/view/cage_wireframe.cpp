#include "cage_wireframe.h"

#include <algorithm>
#include <set>
#include <utility>

#include "bindings.h"
#include "gl/raster_state.h"
#include "mesh/mesh_adjacency.h"

namespace subdfit::view {
namespace {

// OpenSubdiv's infinite sharpness (mesh::Crease).
constexpr float kInfinitelySharp = 10.0f;

using Edge = std::pair<unsigned, unsigned>;

Edge ordered(int a, int b) { return {unsigned(std::min(a, b)), unsigned(std::max(a, b))}; }

// Each edge once, as index pairs (the adjacency lists every edge from both ends), but those in `skip`.
std::vector<unsigned> edgeIndices(const mesh::PolygonMesh& cage, const std::set<Edge>& skip) {
    const auto adjacency = mesh::vertexAdjacency(cage);
    std::vector<unsigned> indices;
    for (int v = 0; v < cage.vertexCount(); ++v)
        for (int k = adjacency.offsets[v]; k < adjacency.offsets[v + 1]; ++k)
            if (const int w = adjacency.neighbors[k]; w > v && !skip.count(ordered(v, w)))
                indices.insert(indices.end(), {unsigned(v), unsigned(w)});
    return indices;
}

const gl::ProgramSpec kCage{"view_cage",
                            {{GL_VERTEX_SHADER, "view_cage.vert"}, {GL_FRAGMENT_SHADER, "view_cage.frag"}}};

}  // namespace

CageWireframe::CageWireframe(const mesh::PolygonMesh& cage) {
    std::set<Edge> creased;
    std::vector<unsigned> sharp, semiSharp, corners;
    for (const auto& crease : cage.tags.creases) {
        if (crease.sharpness <= 0.0f) continue;
        creased.insert(ordered(crease.v0, crease.v1));
        auto& list = crease.sharpness >= kInfinitelySharp ? sharp : semiSharp;
        list.insert(list.end(), {unsigned(crease.v0), unsigned(crease.v1)});
    }
    for (const auto& corner : cage.tags.corners)
        if (corner.sharpness > 0.0f) corners.push_back(unsigned(corner.vertex));
    parts_.reserve(4);
    add(GL_LINES, kSmoothEdgeColor, edgeIndices(cage, creased));
    add(GL_LINES, kSemiSharpCreaseColor, semiSharp);
    add(GL_LINES, kSharpCreaseColor, sharp);
    add(GL_POINTS, kCornerColor, corners);
}

void CageWireframe::add(GLenum primitive, glm::vec4 color, const std::vector<unsigned>& indices) {
    if (indices.empty()) return;
    Part& part = parts_.emplace_back(Part{.primitive = primitive, .color = color, .count = GLsizei(indices.size())});
    part.indices = gl::Buffer::fromVector(indices);
    part.vertexArray.elements(part.indices);
}

void CageWireframe::draw(gl::ProgramCache& programs, const gl::Buffer& vertices, const render::Camera& camera) const {
    const auto& program = programs.get(kCage);
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    vertices.bindStorage(SUBDFIT_SSBO_THETA);
    // Over the composite, never hidden by it: the cage is the thing being edited.
    gl::RasterState{.depthTest = false, .alphaBlend = true}.apply();
    glLineWidth(1.0f);
    glPointSize(7.0f);
    for (const Part& part : parts_) {
        program.set("uColor", part.color);
        part.vertexArray.bind();
        glDrawElements(part.primitive, part.count, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    gl::RasterState{}.apply();
}

}  // namespace subdfit::view
