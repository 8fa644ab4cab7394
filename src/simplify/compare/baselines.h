#pragma once
// The ways a technical artist would simplify an asset without subdfit, at a byte budget, each
// the strongest honest version of itself (docs/simplify.md says which options each searches):
//  (a) decimation + Draco: the reference decimated (meshoptimizer) to as many triangles as fit
//      the budget, shipped as a Draco-compressed GLB, its position bits and whether it ships
//      normals (the reference's own, where they pay) searched on the monitor views, which is
//      what a web or game pipeline would run;
//  (b) gltfpack (Debian's, when on PATH): `gltfpack -si R -cc -vp B` at the largest ratio R whose
//      output fits the budget, B and normals searched the same way, which is what a web or game
//      developer would run;
//  (c) the bake route: a cage (the initial one, or the budget search's best with maps) with maps
//      ray-cast from the reference onto its limit surface, no optimisation, shipped in subdfit's
//      own format (BakeRoute says how).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gl/program_cache.h"
#include "maps/map_parameters.h"
#include "simplify/compare/quality.h"
#include "simplify/compare/triangle_encoding.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

struct BaselineSettings {
    std::filesystem::path dir;    // where the baselines' shipped files go
    bool compactMaps = true;      // and maps
    int surfaceSamples = 100000;  // per side, for the surface distance
    int segments = 8;             // tessellation of limit surfaces for the surface distance
    bool distance = true;         // measure the surface distance (the comparison's; not what a route needs)
};

// The bake route's recipe: a cage (normalised frame) and how the maps baked onto it ship,
// unfitted.
struct BakeRoute {
    mesh::PolygonMesh cage;
    maps::MapEffects effects;       // none means displacement and normal: a bake route without maps is no bake
    int resolution = 4;             // map cells per face edge
    int bits = 12;                  // per map value in its asset.subd
    int positionBits = 14;          // per cage coordinate in its asset.subd
    int appearanceResolution = 16;  // its appearance lattice and JPEG quality (scenes with materials)
    int appearanceQuality = 90;
    int appearanceAtlas = 0;  // texels per side when the appearance is in the reference's atlas; 0: tiles
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;  // of its heights
};

// How a triangle baseline brings the welded reference down to a count (simplify/cage/decimate.h's
// decimate or cluster), and the file under BaselineSettings::dir it ships.
struct Reduction {
    std::function<mesh::PolygonMesh(const mesh::PolygonMesh& welded, int triangles)> reduce;
    std::string file;  // "decimated.glb"
};

// The triangle baselines start from `welded`: weldedTriangles(scene.reference), made once.
// Writes dir/reduction.file (Draco): the reference reduced to the most triangles that fit the
// budget, at the encoding that scores best.
Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& welded,
                           std::uintmax_t budget, const BaselineSettings& settings, const Reduction& reduction);

// The reference as decimationBaseline ships it at every triangle (positions at 14 bits, the
// reference's normals at 10 where `normals`; welded unless its normals split): writes `path`,
// returns its bytes.
std::uintmax_t writeWholeDecimation(const fit::FitScene& scene, const mesh::PolygonMesh& welded, bool normals,
                                    const std::filesystem::path& path);

// Writes dir/gltfpack.glb; nothing (and no file) when gltfpack is not installed.
std::optional<Quality> gltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                        const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                        const BaselineSettings& settings);

// gltfpack's -vn default: the bits its normals ship at.
inline constexpr int kGltfpackNormalBits = 8;

// gltfpack on `input`, simplified to `ratio` of its triangles (-si), positions at
// encoding.positionBits (-vp), with `extra` flags; its output's bytes. Throws when it fails.
std::uintmax_t runGltfpack(const std::filesystem::path& gltfpack, const std::filesystem::path& input,
                           const std::filesystem::path& output, double ratio, const VertexEncoding& encoding,
                           const std::vector<std::string>& extra);
// The command line that made a gltfpack baseline, as the report says it.
std::string gltfpackCommand(const VertexEncoding& encoding, const std::vector<std::string>& flags);

// An asset.subd already drawn and measured: its file and its scores, drawn with `segments`.
struct ScoredFile {
    std::filesystem::path path;
    const Quality& quality;
    int segments;
};

// Writes dir/bake/{asset.subd, maps}. Where that file is, byte for byte, `scored`'s (a fit that
// kept its bake), drawn with the same segments, its scores are `scored`'s: not drawn again.
Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const BakeRoute& route,
                     const BaselineSettings& settings, const std::optional<ScoredFile>& scored = std::nullopt);

}  // namespace subdfit::simplify
