#include "cage_wireframe.h"

#include "bindings.h"
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

}  // namespace

CageWireframe::CageWireframe(const mesh::PolygonMesh& cage) {
    const auto indices = edgeIndices(cage);
    indexCount_ = GLsizei(indices.size());
    edges_ = gl::Buffer::fromVector(indices);
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    vertexArray_ = gl::GlHandle<gl::VertexArrayTraits>(id);
    glVertexArrayElementBuffer(id, edges_.id());
}

void CageWireframe::draw(gl::ProgramCache& programs, const gl::Buffer& vertices, const render::Camera& camera) const {
    const auto& program = programs.get("view_cage", {{GL_VERTEX_SHADER, "view_cage.vert"},
                                                     {GL_FRAGMENT_SHADER, "view_cage.frag"}});
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    glUniform4f(program.location("uColor"), 1.0f, 0.85f, 0.25f, 0.75f);
    vertices.bindStorage(SUBDFIT_SSBO_THETA);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(vertexArray_.id());
    glDrawElements(GL_LINES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

}  // namespace subdfit::view
