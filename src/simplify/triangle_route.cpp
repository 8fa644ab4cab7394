#include "simplify/triangle_route.h"

#include <algorithm>

#include "simplify/cage/decimate.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/textured_baselines.h"

namespace subdfit::simplify {
std::uintmax_t compressedReferenceBytes(const fit::FitScene& scene, const std::filesystem::path& scratch) {
    std::uintmax_t bytes = 0;
    if (shipsMaterials(scene)) {
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
    for (const auto& baseline : triangleBaselinesFor(scene, level)) {
        if (std::string why = baseline->unavailable(); !why.empty()) {
            t.unavailable.emplace_back(baseline->name(), std::move(why));
            continue;
        }
        Quality q = baseline->ship(programs, scene, budget, settings);
        t.holds = std::max(t.holds, baseline->holds(scene, q));
        t.made.push_back({baseline->name(), baseline->title(), std::move(q)});
    }
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
