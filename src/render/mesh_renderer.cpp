#include "render/mesh_renderer.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "bindings.h"
#include "mesh/mesh_geometry.h"
#include "render/raster_pass.h"
#include "util/error.h"

namespace subdfit::render {
namespace {

std::vector<std::string> meshDefines() {
    std::vector<std::string> defines = kShadingDefines;  // bits 0-2
    defines.insert(defines.end(), {"SUBDFIT_BASE_COLOR_TEXTURE", "SUBDFIT_METALLIC_ROUGHNESS_TEXTURE",
                                   "SUBDFIT_NORMAL_TEXTURE", "SUBDFIT_OCCLUSION_TEXTURE", "SUBDFIT_EMISSIVE_TEXTURE"});
    return defines;
}
const gl::ProgramSpec kMeshRaster{
    "mesh_raster", {{GL_VERTEX_SHADER, "mesh.vert"}, {GL_FRAGMENT_SHADER, "mesh.frag"}}, meshDefines()};
constexpr gl::VariantBits kBaseColorTexture = 1u << 3, kMetallicRoughnessTexture = 1u << 4, kNormalTexture = 1u << 5,
                          kOcclusionTexture = 1u << 6, kEmissiveTexture = 1u << 7;

GLenum glWrap(mesh::Wrap wrap) {
    switch (wrap) {
        case mesh::Wrap::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case mesh::Wrap::MirroredRepeat: return GL_MIRRORED_REPEAT;
        case mesh::Wrap::Repeat: break;
    }
    return GL_REPEAT;
}

// The texture slots of a material with the unit and colour space each is sampled in.
struct Slot {
    const mesh::TextureRef* ref;
    GLuint unit;
    bool srgb;
    const char* transform;
    gl::VariantBits bit;
};
std::vector<Slot> slotsOf(const mesh::Material& m, ShadingModel shading) {
    std::vector<Slot> slots{
        {&m.baseColorTexture, SUBDFIT_UNIT_BASE_COLOR, true, "ubaseColorTransform", kBaseColorTexture}};
    if (shading == ShadingModel::Unlit) return slots;
    slots.push_back({&m.normalTexture, SUBDFIT_UNIT_NORMAL, false, "unormalTransform", kNormalTexture});
    slots.push_back({&m.occlusionTexture, SUBDFIT_UNIT_OCCLUSION, false, "uocclusionTransform", kOcclusionTexture});
    slots.push_back({&m.emissiveTexture, SUBDFIT_UNIT_EMISSIVE, true, "uemissiveTransform", kEmissiveTexture});
    if (shading == ShadingModel::MetallicRoughness)
        slots.push_back({&m.metallicRoughnessTexture, SUBDFIT_UNIT_METALLIC_ROUGHNESS, false,
                         "umetallicRoughnessTransform", kMetallicRoughnessTexture});
    return slots;
}

bool usable(const mesh::TextureRef& t, const mesh::MaterialSet& set) {
    return t.present() && !set.images[size_t(t.image)].rgba.empty();
}

}  // namespace

MeshRenderer::MeshRenderer(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                           const std::vector<unsigned>& triangleIndices)
    : batches_{{-1, 0, GLsizei(triangleIndices.size())}},
      positions_(gl::Buffer::fromVector(positions)),
      normals_(gl::Buffer::fromVector(normals)),
      indices_(gl::Buffer::fromVector(triangleIndices)) {
    vertexArray_.attribute(0, positions_, 3);
    vertexArray_.attribute(1, normals_, 3);
    vertexArray_.elements(indices_);
}

MeshRenderer::MeshRenderer(const mesh::PolygonMesh& triangles, ShadingModel shading)
    : shading_(shading),
      positions_(gl::Buffer::fromVector(triangles.positions)),
      normals_(gl::Buffer::fromVector(mesh::shadingNormals(triangles))),
      materials_(triangles.materials) {
    // A material shading asked of a mesh without materials: one plain white one.
    std::vector<int> plain;
    const std::vector<int>* faceMaterials = &triangles.faceMaterials;
    if (shading_ != ShadingModel::Geometry && !materials_) {
        mesh::Material white = mesh::defaultMaterial();
        white.metallicFactor = 0.0f;
        materials_ = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{white}, {}});
        plain.assign(size_t(triangles.faceCount()), 0);
        faceMaterials = &plain;
    }
    // Triangles grouped by material, each group one draw.
    const int faces = triangles.faceCount();
    std::vector<int> order(static_cast<size_t>(faces));
    std::iota(order.begin(), order.end(), 0);
    const bool material = shading_ != ShadingModel::Geometry;
    if (material)
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return (*faceMaterials)[size_t(a)] < (*faceMaterials)[size_t(b)]; });
    std::vector<unsigned> indices;
    indices.reserve(size_t(faces) * 3);
    for (int f : order) {
        const int m = material ? (*faceMaterials)[size_t(f)] : -1;
        if (batches_.empty() || batches_.back().material != m) batches_.push_back({m, GLsizei(indices.size()), 0});
        for (int k = 0; k < 3; ++k) indices.push_back(unsigned(triangles.faceIndices[size_t(3 * f + k)]));
        batches_.back().count += 3;
    }
    indices_ = gl::Buffer::fromVector(indices);
    vertexArray_.attribute(0, positions_, 3);
    vertexArray_.attribute(1, normals_, 3);
    if (material) {
        // Absent attributes read as glTF's defaults: (0, 0) and opaque white.
        const size_t n = triangles.positions.size();
        uvs_ =
            gl::Buffer::fromVector(triangles.uvs.empty() ? std::vector<glm::vec2>(n, glm::vec2(0.0f)) : triangles.uvs);
        colors_ = gl::Buffer::fromVector(triangles.colors.empty() ? std::vector<glm::vec4>(n, glm::vec4(1.0f))
                                                                  : triangles.colors);
        vertexArray_.attribute(2, uvs_, 2);
        vertexArray_.attribute(3, colors_, 4);
        for (const Batch& batch : batches_)
            for (const Slot& slot : slotsOf(materials_->materials[size_t(batch.material)], shading_)) {
                if (!usable(*slot.ref, *materials_) || samplers_.count(slot.ref)) continue;
                const mesh::Image& image = materials_->images[size_t(slot.ref->image)];
                const auto key = std::make_pair(slot.ref->image, slot.srgb);
                if (!textures_.count(key))
                    textures_.emplace(key,
                                      gl::Texture::fromImage(image.rgba.data(), image.width, image.height, slot.srgb));
                samplers_.emplace(slot.ref,
                                  gl::Sampler(glWrap(slot.ref->wrapS), glWrap(slot.ref->wrapT), slot.ref->nearest));
            }
    }
    vertexArray_.elements(indices_);
}

gl::VariantBits MeshRenderer::variantFor(int material) const {
    gl::VariantBits bits = shadingBits(shading_);
    if (material < 0) return bits;
    for (const Slot& slot : slotsOf(materials_->materials[size_t(material)], shading_))
        if (usable(*slot.ref, *materials_)) bits |= slot.bit;
    return bits;
}

void MeshRenderer::setMaterial(const gl::Program& program, const mesh::Material& m) const {
    program.set("uBaseColorFactor", m.baseColorFactor);
    program.set("uMetallicFactor", m.metallicFactor);
    program.set("uRoughnessFactor", m.roughnessFactor);
    program.set("uNormalScale", m.normalScale);
    program.set("uOcclusionStrength", m.occlusionStrength);
    program.set("uEmissiveFactor", m.emissiveFactor);
    program.set("uAlphaCutoff", m.alphaMode == mesh::AlphaMode::Mask ? m.alphaCutoff : 0.0f);
    for (const Slot& slot : slotsOf(m, shading_)) {
        if (!usable(*slot.ref, *materials_)) continue;
        glBindTextureUnit(slot.unit, textures_.at({slot.ref->image, slot.srgb}).id());
        samplers_.at(slot.ref).bind(slot.unit);
        program.set(slot.transform, slot.ref->uvTransform);
    }
}

void MeshRenderer::draw(gl::ProgramCache& programs, const Camera& camera, const RenderTarget& target) const {
    SUBDFIT_CHECK(!target.faceInAlpha());  // triangle ids of a dense reference may pass 2^24
    for (size_t k = 0; k < batches_.size(); ++k) {
        const Batch& batch = batches_[k];
        const auto& program = programs.get(kMeshRaster, variantFor(batch.material));
        if (k == 0) beginRasterPass(program, camera, target);
        else useWithCamera(program, camera);
        if (batch.material >= 0) setMaterial(program, materials_->materials[size_t(batch.material)]);
        vertexArray_.bind();
        glDrawElements(GL_TRIANGLES, batch.count, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(std::uintptr_t(batch.first) * sizeof(unsigned)));
    }
    for (GLuint unit = SUBDFIT_UNIT_BASE_COLOR; unit <= SUBDFIT_UNIT_EMISSIVE; ++unit) glBindSampler(unit, 0);
    glBindVertexArray(0);
}

}  // namespace subdfit::render
