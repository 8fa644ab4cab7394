#include "simplify/triangle_route.h"

#include <limits>

#include "mesh/mesh_geometry.h"
#include "simplify/cage/decimate.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/textured_baselines.h"

namespace subdfit::simplify {
namespace {

// A reference whose materials the triangle baselines must keep (textured or a plain colour), as
// a user's would.
bool withMaterials(const fit::FitScene& scene) {
    return scene.shading != render::ShadingModel::Geometry && scene.reference.materials != nullptr;
}

// Whether the reference is shaded flat, every triangle with vertices of its own and its face's
// normal (as a glTF primitive without normals is read, or a file without normals whose every
// corner has texture coordinates of its own): then its welded triangles drawn without normals,
// as viewers draw a file that ships none, look just as it does.
bool shadedFlat(const fit::FitScene& scene) {
    const mesh::PolygonMesh& r = scene.reference;
    if (r.vertexCount() != int(r.faceIndices.size())) return false;
    const std::vector<glm::vec3> normals = mesh::shadingNormals(r);
    for (size_t first = 0, f = 0; f < r.faceSizes.size(); first += size_t(r.faceSizes[f]), ++f) {
        if (r.faceSizes[f] != 3) return false;
        const glm::vec3 a = r.positions[size_t(r.faceIndices[first])],
                        b = r.positions[size_t(r.faceIndices[first + 1])],
                        c = r.positions[size_t(r.faceIndices[first + 2])];
        const glm::vec3 face = glm::cross(b - a, c - a);
        const float length = glm::length(face);
        if (!(length > 0.0f)) continue;  // a degenerate triangle covers no pixel
        for (size_t k = 0; k < 3; ++k)
            if (glm::dot(normals[size_t(r.faceIndices[first + k])], face / length) < 0.9999f) return false;
    }
    return true;
}

}  // namespace

std::uintmax_t compressedReferenceBytes(const fit::FitScene& scene, const std::filesystem::path& scratch) {
    std::uintmax_t bytes = 0;
    if (withMaterials(scene)) {
        bytes = writeWholeTextured(scene, scratch);
    } else {
        const mesh::PolygonMesh welded = weldedTriangles(scene.reference);
        // Its normals ship unless a viewer's flat shading is its look: split vertices (seams of
        // its texture coordinates) need not mean hard edges.
        bytes = writeWholeDecimation(scene, welded, !shadedFlat(scene), scratch);
    }
    std::filesystem::remove(scratch);
    return bytes;
}

TriangleBaselines triangleBaselines(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                                    const BaselineSettings& settings, CompareLevel level) {
    std::filesystem::create_directories(settings.dir);
    TriangleBaselines t;
    int wholeTriangles = 0;
    bool everyTexel = true;
    if (withMaterials(scene)) {
        t.decimation = texturedDecimationBaseline(programs, scene, budget, settings);
        if (level != CompareLevel::None) t.gltfpack = texturedGltfpackBaseline(programs, scene, budget, settings);
        wholeTriangles = scene.reference.faceCount();
        everyTexel = t.decimation->details.value("texture_scale", 0.0) == 1.0;
    } else {
        const mesh::PolygonMesh welded = weldedTriangles(scene.reference);
        t.decimation = decimationBaseline(programs, scene, welded, budget, settings);
        if (level != CompareLevel::None) t.gltfpack = gltfpackBaseline(programs, scene, welded, budget, settings);
        // Holding every triangle holds the look where the decimation ships normals (the
        // reference's own: at every triangle it ships the reference as it is where its normals
        // split), or the reference is flat and it ships none.
        const bool withNormals = t.decimation->details.value(nlohmann::json::json_pointer("/encoding/normals"), false);
        const bool sameShading = withNormals || shadedFlat(scene);
        wholeTriangles = sameShading ? welded.faceCount() : std::numeric_limits<int>::max();
    }
    if (!t.decimation->details.value("over_budget", true) &&
        t.decimation->details.value("triangles", 0) >= wholeTriangles)
        t.holds = everyTexel ? Holds::Whole : Holds::EveryTriangle;
    t.gltfpackMissing = level != CompareLevel::None && !t.gltfpack;
    return t;
}

Quality shipTriangles(const TriangleChoice& triangles, const std::filesystem::path& out) {
    std::filesystem::copy_file(out / triangles.quality->shipped, out / "asset.glb",
                               std::filesystem::copy_options::overwrite_existing);
    Quality shipped = *triangles.quality;
    shipped.files = {{"asset.glb", shipped.bytes}};
    shipped.shipped = "asset.glb";
    return shipped;
}

}  // namespace subdfit::simplify
