#include "render/mesh_renderer.h"

#include "render/raster_pass.h"

namespace subdfit::render {
namespace {
const gl::ProgramSpec kMeshRaster{"mesh_raster", {{GL_VERTEX_SHADER, "mesh.vert"}, {GL_FRAGMENT_SHADER, "mesh.frag"}}};
}  // namespace

MeshRenderer::MeshRenderer(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                           const std::vector<unsigned>& triangleIndices)
    : indexCount_(GLsizei(triangleIndices.size())),
      positions_(gl::Buffer::fromVector(positions)),
      normals_(gl::Buffer::fromVector(normals)),
      indices_(gl::Buffer::fromVector(triangleIndices)) {
    vertexArray_.attribute(0, positions_, 3);
    vertexArray_.attribute(1, normals_, 3);
    vertexArray_.elements(indices_);
}

void MeshRenderer::draw(gl::ProgramCache& programs, const Camera& camera, const RenderTarget& target) const {
    const auto& program = programs.get(kMeshRaster);
    beginRasterPass(program, camera, target);
    vertexArray_.bind();
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

}  // namespace subdfit::render
