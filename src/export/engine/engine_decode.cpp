#include "export/engine/engine_decode.h"

#include <cmath>
#include <new>

#include <nlohmann/json.hpp>

#include "export/subd_decode.h"
#include "export/surface_glb.h"
#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::exporter {

std::filesystem::path lodPath(const std::filesystem::path& out, int k) {
    if (k == 0) return out;
    std::filesystem::path path = out;
    return path.replace_filename(out.stem().string() + "_lod" + std::to_string(k) + out.extension().string());
}

std::filesystem::path lodJsonPath(const std::filesystem::path& out) {
    std::filesystem::path path = out;
    return path.replace_filename(out.stem().string() + "_lods.json");
}

std::vector<WrittenFile> decodeForEngines(const std::filesystem::path& subd, const std::filesystem::path& out,
                                          const EngineDecodeOptions& o) {
    if (o.maxError && !(o.maxError->value > 0.0 && std::isfinite(o.maxError->value)))
        throw OptionError("max-error", "must be a positive distance");
    if (o.lods < 0 || o.lods > kMostLods) throw OptionError("lods", "must be in 1.." + std::to_string(kMostLods));
    const int levels = std::max(o.lods, 1);
    for (int k = 0; k < levels; ++k) io::checkOutputFile(lodPath(out, k), subd);
    if (o.lods > 0) io::checkOutputFile(lodJsonPath(out), subd);
    try {
        DecodeBudget budget(subd.string());
        const DecodeInput input = readForDecode(subd, o.maxError ? DensityRequest{} : o.density, budget);
        const SubdAsset& asset = input.asset;
        DecodeDensity density = input.density;
        std::optional<ErrorDensity> fromError;
        if (o.maxError) {
            fromError = densityWithin(asset, *o.maxError, budget);
            density = fromError->density;
        }
        // The other levels together take about what level 0 does.
        if (levels > 1) budget.spend(1, decodeOutputBytes(density), "levels of detail below " + std::to_string(density.triangles) + " triangles");
        SurfaceGlb glb = surfaceGlb(asset.cage, asset.maps, density.segments);
        LodChain chain = lodChain(asset, std::move(glb.mesh), density.segments, levels, o.screenSize);

        std::vector<std::vector<unsigned char>> encoded;
        std::vector<std::size_t> meshBytes;
        for (LodLevel& level : chain.levels) {
            // Compact files carry no TANGENT that no normal texture reads, no TEXCOORD_0 that no image reads.
            if (o.coding == MeshCoding::Meshopt && glb.textures.normalPng.empty()) level.mesh.tangents.clear();
            if (o.coding == MeshCoding::Meshopt && !glb.textures.any()) level.mesh.uvs.clear();
            encoded.push_back(encodeFittedGlb(level.mesh, glb.textures, o.coding));
            meshBytes.push_back(encodeFittedGlb(level.mesh, {}, o.coding).size());
        }
        std::vector<WrittenFile> written;
        nlohmann::json lods = nlohmann::json::array();
        for (size_t k = 0; k < chain.levels.size(); ++k) {
            const LodLevel& level = chain.levels[k];
            written.push_back(writeBytes(lodPath(out, int(k)), encoded[k]));
            nlohmann::json entry = {{"lod", k},
                                    {"file", lodPath(out, int(k)).filename().string()},
                                    {"triangles", level.mesh.triangleCount()},
                                    {"bytes", written.back().bytes},
                                    {"bytes_without_images", meshBytes[k]},
                                    {"method", level.segments > 0 ? "tessellation" : "simplification"},
                                    {"mean_distance", level.meanDistance},
                                    {"max_distance", level.maxDistance},
                                    {"screen_size", level.screenSize}};
            if (level.segments > 0) entry["segments"] = level.segments;
            lods.push_back(std::move(entry));
        }
        if (o.lods > 0) {
            nlohmann::json doc = {
                {"asset", subd.filename().string()},
                {"decode_triangles", asset.decodeTriangles},
                {"coding", o.coding == MeshCoding::Meshopt ? "KHR_mesh_quantization, EXT_meshopt_compression" : "float"},
                {"distances", "mean and largest sampled distance to lod 0, both ways, in the asset's units"},
                {"screen_size_rule",
                 {{"pixel_error", o.screenSize.pixelError},
                  {"screen_height", o.screenSize.screenHeight},
                  {"bounding_sphere_radius", chain.boundingRadius},
                  {"screen_size", "2 * pixel_error * bounding_sphere_radius / (max_distance * screen_height): the "
                                  "bounding sphere's diameter over the screen height below which the level may be drawn"}}},
                {"lods", lods}};
            if (fromError)
                doc["max_error"] = {{"bound", fromError->bound},
                                    {"max_distance", fromError->maxDistance},
                                    {"reference_segments", fromError->referenceSegments}};
            const std::string text = doc.dump(2) + "\n";
            written.push_back(writeBytes(lodJsonPath(out), {reinterpret_cast<const unsigned char*>(text.data()), text.size()}));
        }
        return written;
    } catch (const std::bad_alloc&) {
        throw fileError(subd.string(), "out of memory while decoding it");
    }
}

}  // namespace subdfit::exporter
