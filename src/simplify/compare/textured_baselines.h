#pragma once
// The triangle baselines (simplify/compare/baselines.h) for a reference with an appearance: what a
// pipeline ships for a textured asset at a byte budget. The texture coordinates survive the
// decimation (each material decimated on its own, UV seams kept as meshoptimizer keeps
// borders) and the images are re-encoded (JPEG at quality 85, PNG where they have alpha) at
// 1, 1/2, 1/4 ... of their size: the scale whose result scores best on the monitor views
// (neither training nor held-out) within the budget is the one reported. gltfpack gets the
// textured mesh at that scale (Debian's 0.18 cannot scale textures itself without BasisU).
#include <cstdint>
#include <optional>

#include "gl/program_cache.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/quality.h"

namespace subdfit::simplify {

// `scene.reference` must have materials. Writes dir/decimated.glb (Draco).
Quality texturedDecimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                                   const BaselineSettings& settings);

// Writes dir/gltfpack.glb; nothing when gltfpack is not installed.
std::optional<Quality> texturedGltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                                std::uintmax_t budget, const BaselineSettings& settings);

// The reference whole as the textured decimation ships it at every triangle (its normals, its
// images re-encoded at full size, the same file to the byte): writes `path`, returns its bytes.
std::uintmax_t writeWholeTextured(const fit::FitScene& scene, const std::filesystem::path& path);

// `triangles` (with faceMaterials and materials, uvs if any) collapsed to about `targetTriangles`, each
// material in proportion to its share; the appearance is kept.
mesh::PolygonMesh decimateTextured(const mesh::PolygonMesh& triangles, int targetTriangles);

}  // namespace subdfit::simplify
