#pragma once
// The cage's edges drawn over the view, straight from the fitter's control vertices on the GPU
// (no readback per frame).
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/vertex_array.h"
#include "mesh/polygon_mesh.h"
#include "render/camera.h"

namespace subdfit::view {

class CageWireframe {
public:
    explicit CageWireframe(const mesh::PolygonMesh& cage);

    // Into the bound framebuffer and viewport, blended over what is there, without depth test:
    // the whole cage shows, also where it lies behind the surface.
    void draw(gl::ProgramCache& programs, const gl::Buffer& vertices, const render::Camera& camera) const;

private:
    GLsizei indexCount_;
    gl::Buffer edges_;
    gl::VertexArray vertexArray_;
};

}  // namespace subdfit::view
