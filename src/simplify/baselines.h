#pragma once
// The two ways a technical artist would simplify an asset without subdfit, at the byte budget
// subdfit's result ships in:
//  (a) decimation + Draco: the reference decimated (meshoptimizer) to as many triangles as fit
//      the budget, shipped as a Draco-compressed GLB with smooth normals (14-bit positions,
//      10-bit normals), which is what a web or game pipeline would run;
//  (b) gltfpack (Debian's, when on PATH): `gltfpack -si R -cc` at the largest ratio R whose
//      output fits the budget, which is what a web or game developer would run;
//  (c) the bake route: the initial cage (same faces as subdfit's) with maps ray-cast from the
//      reference onto its limit surface, no optimisation, shipped in subdfit's own format.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include "gl/program_cache.h"
#include "maps/map_parameters.h"
#include "simplify/quality.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

struct BaselineSettings {
    std::filesystem::path dir;   // where the baselines' shipped files go
    bool draco = false;          // the convenience cage.glb with Draco (the decimation always has it)
    bool compactMaps = true;     // and maps
    int surfaceSamples = 100000; // per side, for the surface distance
    int segments = 8;            // tessellation of limit surfaces for the surface distance
    int mapBits = 12;            // per map value in the bake's asset.subd, as subdfit's
    int appearanceResolution = 16;  // the appearance maps' lattice and JPEG quality in the bake's asset.subd
    int appearanceQuality = 90;
    int appearanceAtlas = 0;  // texels per side when the appearance is in the reference's atlas
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;  // of the bake's heights
};

// Both triangle baselines start from `welded`: weldedTriangles(scene.reference), made once.
// Writes dir/decimated.glb (Draco).
Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& welded,
                           std::uintmax_t budget, const BaselineSettings& settings);

// Writes dir/gltfpack.glb; nothing (and no file) when gltfpack is not installed.
std::optional<Quality> gltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                        const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                        const BaselineSettings& settings);

// `cage`: the initial cage in the scene's normalised frame. Writes dir/bake/{cage.glb, maps}.
// `effects` none means displacement and normal: a bake route without maps is no bake.
Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& cage,
                     maps::MapEffects effects, int mapResolution, const BaselineSettings& settings);

// The most triangles in [fewest, most] whose shipped file (`ship` writes it, returns its bytes)
// fits `budget`: bytes grow with triangles. At `fewest` when even that is over (the report then
// says so: a .glb's own header and JSON weigh hundreds of bytes). The file is left as shipped.
int mostWithinBudget(int fewest, int most, std::uintmax_t budget, const std::function<std::uintmax_t(int)>& ship);

// What subdfit-format assets ship: the cage as a GLB of positions and indices (written to
// `path`, world units) plus the map files written beside it. Returns {file: bytes}.
nlohmann::json shipCage(const std::filesystem::path& path, const mesh::PolygonMesh& cageWorld, bool draco);

}  // namespace subdfit::simplify
