#include "cage_wireframe.h"

#include "bindings.h"
#include "gl/raster_state.h"
#include "mesh/mesh_adjacency.h"

namespace subdfit::view {
namespace {

// Each edge once, as index pairs (the adjacency lists every edge from both ends).
std::vector<unsigned> edgeIndices(const mesh::PolygonMesh& cage) {
    const auto adjacency = mesh::vertexAdjacency(cage);
    std::vector<unsigned> indices;
    for (int v = 0; v < cage.vertexCount(); ++v)
        for (int k = adjacency.offsets[v]; k < adjacency.offsets[v + 1]; ++k)
            if (adjacency.neighbors[k] > v) indices.insert(indices.end(), {unsigned(v), unsigned(adjacency.neighbors[k])});
    return indices;
}

const gl::ProgramSpec kCage{"view_cage", {{GL_VERTEX_SHADER, "view_cage.vert"}, {GL_FRAGMENT_SHADER, "view_cage.frag"}}};

}  // namespace

CageWireframe::CageWireframe(const mesh::PolygonMesh& cage) {
    const auto indices = edgeIndices(cage);
    indexCount_ = GLsizei(indices.size());
    edges_ = gl::Buffer::fromVector(indices);
    vertexArray_.elements(edges_);
}

void CageWireframe::draw(gl::ProgramCache& programs, const gl::Buffer& vertices, const render::Camera& camera) const {
    const auto& program = programs.get(kCage);
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    program.set("uColor", glm::vec4(1.0f, 0.85f, 0.25f, 0.75f));
    vertices.bindStorage(SUBDFIT_SSBO_THETA);
    // Over the composite, never hidden by it: the cage is the thing being edited.
    gl::RasterState{.depthTest = false, .alphaBlend = true}.apply();
    vertexArray_.bind();
    glDrawElements(GL_LINES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    gl::RasterState{}.apply();
}

}  // namespace subdfit::view
