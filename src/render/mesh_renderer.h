#pragma once
// Draws a triangle mesh (the reference) with the same shading as the cage, and, in a scene with
// materials, with its own: one draw per material, the variant of each naming only the textures
// that material has.
#include <glm/vec3.hpp>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "mesh/polygon_mesh.h"
#include "render/camera.h"
#include "render/render_target.h"
#include "render/shading_model.h"

namespace subdfit::render {

class MeshRenderer {
public:
    // Geometry only: the grey surface of ShadingModel::Geometry.
    MeshRenderer(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                 const std::vector<unsigned>& triangleIndices);
    // A triangle mesh with its appearance (if any), shaded by `shading`.
    MeshRenderer(const mesh::PolygonMesh& triangles, ShadingModel shading);

    void draw(gl::ProgramCache& programs, const Camera& camera, const RenderTarget& target) const;
    ShadingModel shading() const { return shading_; }

private:
    struct Batch {
        int material;          // -1: none (Geometry)
        GLsizei first, count;  // in indices
    };
    void setMaterial(const gl::Program& program, const mesh::Material& material) const;
    gl::VariantBits variantFor(int material) const;

    ShadingModel shading_ = ShadingModel::Geometry;
    std::vector<Batch> batches_;
    gl::Buffer positions_, normals_, uvs_, colors_, indices_;
    gl::VertexArray vertexArray_;
    std::shared_ptr<const mesh::MaterialSet> materials_;
    // One texture per (image, sRGB or linear) a material samples, one sampler per texture slot.
    std::map<std::pair<int, bool>, gl::Texture> textures_;
    std::map<const mesh::TextureRef*, gl::Sampler> samplers_;
};

}  // namespace subdfit::render
