#pragma once
// The two ways a technical artist would simplify an asset without subdfit, at the byte budget
// subdfit's result ships in:
//  (a) plain decimation: the reference decimated to as many triangles as fit the budget,
//      shipped as a GLB with smooth normals;
//  (b) the bake route: the initial cage (same faces as subdfit's) with maps ray-cast from the
//      reference onto its limit surface, no optimisation, shipped in subdfit's own format.
#include <cstdint>
#include <filesystem>

#include "gl/program_cache.h"
#include "maps/map_parameters.h"
#include "simplify/quality.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

struct BaselineSettings {
    std::filesystem::path dir;   // where the baselines' shipped files go
    bool draco = false;          // compress meshes as subdfit's are
    bool compactMaps = true;     // and maps
    int surfaceSamples = 100000; // per side, for the surface distance
    int segments = 8;            // tessellation of limit surfaces for the surface distance
};

// Writes dir/decimated.glb.
Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                           const BaselineSettings& settings);

// `cage`: the initial cage in the scene's normalised frame. Writes dir/bake/{cage.glb, maps}.
// `effects` none means displacement and normal: a bake route without maps is no bake.
Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& cage,
                     maps::MapEffects effects, int mapResolution, const BaselineSettings& settings);

// What subdfit-format assets ship: the cage as a GLB of positions and indices (written to
// `path`, world units) plus the map files written beside it. Returns {file: bytes}.
nlohmann::json shipCage(const std::filesystem::path& path, const mesh::PolygonMesh& cageWorld, bool draco);

}  // namespace subdfit::simplify
