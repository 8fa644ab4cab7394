#pragma once
// The two ways a technical artist would simplify an asset without subdfit, at the byte budget
// subdfit's result ships in:
//  (a) decimation + Draco: the reference decimated (meshoptimizer) to as many triangles as fit
//      the budget, shipped as a Draco-compressed GLB with smooth normals (14-bit positions,
//      10-bit normals), which is what a web or game pipeline would run;
//  (b) gltfpack (Debian's, when on PATH): `gltfpack -si R -cc` at the largest ratio R whose
//      output fits the budget, which is what a web or game developer would run;
//  (c) the bake route: a cage (the initial one, or the budget search's best with maps) with maps
//      ray-cast from the reference onto its limit surface, no optimisation, shipped in subdfit's
//      own format (BakeRoute says how).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include "gl/program_cache.h"
#include "maps/map_parameters.h"
#include "simplify/compare/quality.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

struct BaselineSettings {
    std::filesystem::path dir;   // where the baselines' shipped files go
    bool compactMaps = true;     // and maps
    int surfaceSamples = 100000; // per side, for the surface distance
    int segments = 8;            // tessellation of limit surfaces for the surface distance
};

// The bake route's recipe: a cage (normalised frame) and how the maps baked onto it ship,
// unfitted.
struct BakeRoute {
    mesh::PolygonMesh cage;
    maps::MapEffects effects;  // none means displacement and normal: a bake route without maps is no bake
    int resolution = 4;        // map cells per face edge
    int bits = 12;             // per map value in its asset.subd
    int appearanceResolution = 16;  // its appearance lattice and JPEG quality (scenes with materials)
    int appearanceQuality = 90;
    int appearanceAtlas = 0;  // texels per side when the appearance is in the reference's atlas; 0: tiles
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;  // of its heights
};

// Both triangle baselines start from `welded`: weldedTriangles(scene.reference), made once.
// Writes dir/decimated.glb (Draco).
Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& welded,
                           std::uintmax_t budget, const BaselineSettings& settings);

// Writes dir/gltfpack.glb; nothing (and no file) when gltfpack is not installed.
std::optional<Quality> gltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                        const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                        const BaselineSettings& settings);

// Writes dir/bake/{asset.subd, maps}.
Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const BakeRoute& route,
                     const BaselineSettings& settings);

// The most triangles in [fewest, most] whose shipped file (`ship` writes it, returns its bytes)
// fits `budget`: bytes grow with triangles. At `fewest` when even that is over (the report then
// says so: a .glb's own header and JSON weigh hundreds of bytes). The file is left as shipped.
int mostWithinBudget(int fewest, int most, std::uintmax_t budget, const std::function<std::uintmax_t(int)>& ship);

}  // namespace subdfit::simplify
