#include "render/patch_renderer.h"

#include <algorithm>
#include <optional>

#include "bindings.h"
#include "gl/dispatch.h"
#include "gl/texture.h"
#include "render/raster_pass.h"
#include "util/error.h"

namespace subdfit::render {
namespace {

const gl::ProgramSpec kPatchTessellate{
    "patch_tessellate",
    {{GL_COMPUTE_SHADER, "tessellate.comp"}},
    {"SUBDFIT_DISPLACEMENT", "SUBDFIT_LIMIT_SHADING", "SUBDFIT_GREGORY_PATCHES", "SUBDFIT_SURFACE_PAIR"}};
constexpr gl::VariantBits kTessellateDisplacement = 1u << 0, kTessellateLimitShading = 1u << 1,
                          kTessellateGregory = 1u << 2, kTessellatePair = 1u << 3;

const gl::ProgramSpec kDisplace{"patch_displace", {{GL_COMPUTE_SHADER, "displace.comp"}}, {"SUBDFIT_LIMIT_SHADING"}};
constexpr gl::VariantBits kDisplaceLimitShading = 1u << 0;

const gl::ProgramSpec kTriangulate{
    "patch_triangulate", {{GL_COMPUTE_SHADER, "triangulate.comp"}}, {"SUBDFIT_SURFACE_PAIR"}};
constexpr gl::VariantBits kTriangulatePair = 1u << 0;

// The raster pass's variant bits: the shading model's (0-2), then one per map kind with a raster
// define (kinds/map_kinds.h, in table order), then these.
constexpr gl::VariantBits kPatchFirstMapBit = 3;
constexpr gl::VariantBits kPatchMapBits = [] {
    gl::VariantBits count = 0;
    for (const kinds::MapKindInfo& i : kinds::kMapKinds) count += i.rasterDefine.empty() ? 0 : 1;
    return count;
}();
constexpr gl::VariantBits kPatchAppearanceAtlas = 1u << (kPatchFirstMapBit + kPatchMapBits),
                          kPatchAtlasNormal = kPatchAppearanceAtlas << 1,
                          kPatchCarriedOcclusion = kPatchAtlasNormal << 1,
                          kPatchCarriedEmissive = kPatchCarriedOcclusion << 1,
                          kPatchFaceInAlpha = kPatchCarriedEmissive << 1;

const gl::ProgramSpec kPatchRaster{
    "patch_raster", {{GL_VERTEX_SHADER, "surface.vert"}, {GL_FRAGMENT_SHADER, "patch.frag"}}, [] {
        std::vector<std::string> defines = kShadingDefines;
        for (const kinds::MapKindInfo& i : kinds::kMapKinds)
            if (!i.rasterDefine.empty()) defines.emplace_back(i.rasterDefine);
        defines.insert(defines.end(),
                       {"SUBDFIT_APPEARANCE_ATLAS", "SUBDFIT_ATLAS_NORMAL_TEXTURE", "SUBDFIT_CARRIED_OCCLUSION",
                        "SUBDFIT_CARRIED_EMISSIVE", "SUBDFIT_FACE_IN_ALPHA"});
        return defines;
    }()};

// The variant bits of the kinds `maps` applies in the raster pass.
gl::VariantBits rasterMapBits(kinds::MapKinds maps) {
    gl::VariantBits bits = 0, bit = 1u << kPatchFirstMapBit;
    for (const kinds::MapKindInfo& i : kinds::kMapKinds) {
        if (i.rasterDefine.empty()) continue;
        if (maps.has(i.kind)) bits |= bit;
        bit <<= 1;
    }
    return bits;
}

// A vertex of the evaluated surface (glsl/tessellate.comp): 16 floats.
constexpr GLsizei kSurfaceVertexBytes = 16 * sizeof(float);

void setMapUniforms(const gl::Program& program, const PatchMaps& maps) {
    program.set("uMapResolution", maps.resolution);
    program.set("uAppearanceResolution", maps.appearanceResolution);
    program.set("uAppearanceTable", maps.appearanceTable);
}

}  // namespace

int crackFreeTessLevel(int requested, int maxPatchDepth) {
    int level = 1;
    while (level < std::max(requested, 1 << maxPatchDepth)) level *= 2;
    return std::min(level, 64);
}

PatchRenderer::PatchRenderer(const subdiv::PatchSet& patches, int tessLevel, ShadingModel shading)
    : patchCount_(int(patches.patchInfo.size())),
      faceCount_(patches.ptexFaceCount),
      tessLevel_(crackFreeTessLevel(tessLevel, patches.maxPatchDepth)),
      shading_(shading),
      patchInfo_(gl::Buffer::fromVector(patches.patchInfo)),
      patchCvs_(gl::Buffer::fromVector(patches.patchCvIndices)),
      patchInfoTexture_(patchInfo_, GL_RGBA32I),
      patchCvTexture_(patchCvs_, GL_RGBA32I) {
    // The surface pass fetches a patch's control points four at a time (16 or 20 of them).
    for (const auto& info : patches.patchInfo) SUBDFIT_CHECK(info.x % 4 == 0);
    const PatchTessellation tessellation = tessellatePatches(patches, tessLevel_);
    runs_ = tessellation.runs;
    vertexCount_ = int(tessellation.samples.size());
    quadCount_ = int(tessellation.quads.size() / 4);
    samples_ = gl::Buffer::fromVector(tessellation.samples);
    quads_ = gl::Buffer::fromVector(tessellation.quads);
    quadsTexture_ = gl::BufferTexture(quads_, GL_RGBA32UI);
    // The record's layout is glsl/surface_vertex.glsl's; the locations are glsl/surface.vert's.
    vertexArray_.recordAttribute(0, 3, 0);                                     // position
    vertexArray_.recordAttribute(1, 3, 3 * sizeof(float));                     // normal
    vertexArray_.recordAttribute(2, 3, 6 * sizeof(float));                     // ∂P/∂u
    vertexArray_.recordAttribute(3, 3, 9 * sizeof(float));                     // ∂P/∂v
    vertexArray_.recordAttribute(4, 2, 12 * sizeof(float));                    // ptex (u, v)
    vertexArray_.recordAttribute(5, 1, 14 * sizeof(float), /*integer=*/true);  // ptex face
}

PatchRenderer::Surface PatchRenderer::makeSurface() const {
    return {makeVertices(), gl::Buffer(GLsizeiptr(std::max(1, quadCount_)) * 6 * sizeof(std::uint32_t))};
}

gl::Buffer PatchRenderer::makeVertices() const {
    return gl::Buffer(GLsizeiptr(std::max(1, vertexCount_)) * kSurfaceVertexBytes);
}

void PatchRenderer::evaluate(gl::ProgramCache& programs, const gl::Buffer& points, const Surface& surface,
                             const PatchMaps* maps) const {
    tessellate(programs, points, surface.vertices, maps);
    split(programs, surface);
}

void PatchRenderer::evaluatePair(gl::ProgramCache& programs, const gl::Buffer& points, const Surface& surface,
                                 const gl::Buffer& secondPoints, const Surface& secondSurface,
                                 const PatchMaps* maps) const {
    const Second second{secondPoints, secondSurface};
    tessellate(programs, points, surface.vertices, maps, &second);
    split(programs, surface, &secondSurface);
}

void PatchRenderer::evaluateLimit(gl::ProgramCache& programs, const gl::Buffer& points,
                                  const gl::Buffer& limitVertices) const {
    tessellate(programs, points, limitVertices, nullptr);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // displace() reads them as a texture
}

void PatchRenderer::displace(gl::ProgramCache& programs, const gl::Buffer& limitVertices, const Surface& surface,
                             const PatchMaps& maps) const {
    SUBDFIT_CHECK(maps.kinds.has(kinds::MapKind::Displacement));
    layOutHeights(programs, maps);
    const auto& program = programs.get(kDisplace, maps.limitShading ? kDisplaceLimitShading : 0);
    program.use();
    program.set("uVertexCount", vertexCount_);
    setMapUniforms(program, maps);
    program.set("uTilesPerRow", heightTiles_->tilesPerRow());
    const gl::BufferTexture limitTexture(limitVertices, GL_RGBA32F);
    limitTexture.bind(SUBDFIT_UNIT_LIMIT_VERTICES);
    surface.vertices.bindStorage(SUBDFIT_SSBO_SURFACE_VERTICES);
    glDispatchCompute(gl::groupsOf(vertexCount_, 64), 1, 1);
    split(programs, surface);
}

void PatchRenderer::tessellate(gl::ProgramCache& programs, const gl::Buffer& points, const gl::Buffer& vertices,
                               const PatchMaps* maps, const Second* second) const {
    const bool displaced = maps && maps->kinds.has(kinds::MapKind::Displacement);
    const gl::VariantBits variant =
        (displaced ? kTessellateDisplacement | (maps->limitShading ? kTessellateLimitShading : 0) : 0) |
        (second ? kTessellatePair : 0);
    patchInfoTexture_.bind(SUBDFIT_UNIT_PATCH_INFO);
    patchCvTexture_.bind(SUBDFIT_UNIT_PATCH_CVS);
    const gl::BufferTexture pointTexture(points, GL_RGB32F);
    pointTexture.bind(SUBDFIT_UNIT_PATCH_POINTS);
    std::optional<gl::BufferTexture> secondPointTexture;
    if (second) {
        secondPointTexture.emplace(second->points, GL_RGB32F);
        secondPointTexture->bind(SUBDFIT_UNIT_PATCH_SECOND_POINTS);
        second->surface.vertices.bindStorage(SUBDFIT_SSBO_SECOND_SURFACE_VERTICES);
    }
    samples_.bindStorage(SUBDFIT_SSBO_TESSELLATION_SAMPLES);
    vertices.bindStorage(SUBDFIT_SSBO_SURFACE_VERTICES);
    if (displaced) layOutHeights(programs, *maps);
    for (const SampleRun& run : runs_) {
        const auto& program = programs.get(kPatchTessellate, variant | (run.gregory ? kTessellateGregory : 0));
        program.use();
        program.set("uFirstSample", run.first);
        program.set("uSampleCount", run.count);
        if (displaced) {
            setMapUniforms(program, *maps);
            program.set("uTilesPerRow", heightTiles_->tilesPerRow());
        }
        glDispatchCompute(gl::groupsOf(run.count, 64), 1, 1);
    }
}

void PatchRenderer::layOutHeights(gl::ProgramCache& programs, const PatchMaps& maps) const {
    if (!heightTiles_ || heightTiles_->resolution() != maps.resolution)
        heightTiles_.emplace(faceCount_, maps.resolution);
    heightTiles_->fill(programs, maps);  // binds the maps too
}

void PatchRenderer::split(gl::ProgramCache& programs, const Surface& surface, const Surface* second) const {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);  // the split reads the vertices as a texture
    const auto& triangulate = programs.get(kTriangulate, second ? kTriangulatePair : 0);
    triangulate.use();
    triangulate.set("uQuadCount", quadCount_);
    quadsTexture_.bind(SUBDFIT_UNIT_TESSELLATION_QUADS);
    const gl::BufferTexture vertexTexture(surface.vertices, GL_RGBA32F);
    vertexTexture.bind(SUBDFIT_UNIT_SURFACE_VERTICES);
    surface.triangles.bindStorage(SUBDFIT_SSBO_SURFACE_TRIANGLES);
    std::optional<gl::BufferTexture> secondVertexTexture;
    if (second) {
        secondVertexTexture.emplace(second->vertices, GL_RGBA32F);
        secondVertexTexture->bind(SUBDFIT_UNIT_SECOND_SURFACE_VERTICES);
        second->triangles.bindStorage(SUBDFIT_SSBO_SECOND_SURFACE_TRIANGLES);
    }
    glDispatchCompute(gl::groupsOf(quadCount_, 64), 1, 1);
    glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT);
}

void PatchRenderer::rasterize(gl::ProgramCache& programs, const Surface& surface, const Camera& camera,
                              const RenderTarget& target, const PatchMaps* maps) const {
    const bool appearance = maps && maps->kinds.appearance();
    const gl::VariantBits mapBits =
        maps ? rasterMapBits(maps->kinds) | (maps->appearanceAtlas && appearance ? kPatchAppearanceAtlas : 0) : 0;
    // The reference's textures the appearance lattice carries: only where it is drawn, with a
    // material (the normal texture only with its atlas, whose frame it is in).
    const bool carried = appearance && shading_ != ShadingModel::Geometry;
    const gl::VariantBits carriedBits =
        carried ? (maps->atlasNormal && (mapBits & kPatchAppearanceAtlas) ? kPatchAtlasNormal : 0) |
                      (maps->carriedOcclusion ? kPatchCarriedOcclusion : 0) |
                      (maps->carriedEmissive ? kPatchCarriedEmissive : 0)
                : 0;
    const gl::VariantBits targetBits = target.faceInAlpha() ? kPatchFaceInAlpha : 0;
    const auto& program = programs.get(kPatchRaster, shadingBits(shading_) | mapBits | carriedBits | targetBits);
    beginRasterPass(program, camera, target);
    if (mapBits != 0) {
        if (maps->bind) maps->bind();
        setMapUniforms(program, *maps);
    }
    vertexArray_.records(surface.vertices, kSurfaceVertexBytes);
    vertexArray_.elements(surface.triangles);
    vertexArray_.bind();
    glDrawElements(GL_TRIANGLES, 6 * quadCount_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

void PatchRenderer::draw(gl::ProgramCache& programs, const gl::Buffer& points, const Camera& camera,
                         const RenderTarget& target, const PatchMaps* maps) const {
    const Surface surface = makeSurface();
    evaluate(programs, points, surface, maps);
    rasterize(programs, surface, camera, target, maps);
}

}  // namespace subdfit::render
