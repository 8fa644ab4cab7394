#pragma once
// The triangle route of one simplify: the triangle baselines at its budget (what a cage must
// beat, and what ships where none does), the reference compressed (what a default budget is made
// from), and shipping the winner as DIR/asset.glb.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fit/fit_scene.h"
#include "gl/program_cache.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/triangle_baseline.h"
#include "simplify/route.h"

namespace subdfit::simplify {

// The reference whole as the triangle route would ship it, written to `scratch` (then removed):
// its bytes, what the default budget is made from.
std::uintmax_t compressedReferenceBytes(const fit::FitScene& scene, const std::filesystem::path& scratch);

// The triangle baselines at a budget (triangleBaselinesFor): decimation + Draco always (the
// route weighs it), the others unless --compare none.
struct TriangleBaselines {
    std::vector<MadeBaseline> made;                                // decimation first
    std::vector<std::pair<std::string, std::string>> unavailable;  // name, why
    Holds holds = Holds::Part;                                     // of the reference, by the decimation
    TriangleChoice best() const { return bestTriangleRoute(made); }
};

// Their files go to settings.dir.
TriangleBaselines triangleBaselines(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                                    const BaselineSettings& settings, CompareLevel level);

// The triangle route ships: its file, as the baseline wrote it under `out`, becomes out/asset.glb;
// what ships is measured as that baseline was.
Quality shipTriangles(const TriangleChoice& triangles, const std::filesystem::path& out);

}  // namespace subdfit::simplify
