#include "export/engine/engine_decode.h"

#include <cmath>
#include <new>

#include <nlohmann/json.hpp>

#include "export/engine/subd_decode.h"
#include "export/gltf/surface_glb.h"
#include "io/atomic_file.h"
#include "util/error.h"
#include "util/warnings.h"
#include "util/json_text.h"

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

std::vector<io::WrittenFile> decodeForEngines(const std::filesystem::path& subd, const std::filesystem::path& out,
                                              const EngineDecodeOptions& o) {
    if (o.maxError && !(o.maxError->value > 0.0 && std::isfinite(o.maxError->value)))
        throw OptionError("max-error", "must be a positive distance");
    if (o.lods < 0 || o.lods > kMostLods) throw OptionError("lods", "must be in 1.." + std::to_string(kMostLods));
    const int levels = std::max(o.lods, 1);
    for (int k = 0; k < levels; ++k) io::checkOutputFile(lodPath(out, k), subd);
    if (o.lods > 0) io::checkOutputFile(lodJsonPath(out), subd);
    try {
        codec::DecodeBudget budget(subd.string());
        // The whole chain is priced before any of it is made (with the file, where the density
        // is the default or asked for; an error bound's once it is known).
        const DecodeInput input = readForDecode(subd, o.maxError ? codec::DensityRequest{} : o.density, budget,
                                                o.maxError ? 1 : levels, o.firstBytes);
        const codec::SubdAsset& asset = input.asset;
        codec::DecodeDensity density = input.density;
        std::optional<ErrorDensity> fromError;
        if (o.maxError) {
            fromError = densityWithin(asset, *o.maxError, budget);
            density = fromError->density;
            budget.spend(
                1, lodChainBytes(density, levels),
                std::to_string(levels) + " levels of detail from " + std::to_string(density.triangles) + " triangles");
        }
        SurfaceGlb glb = surfaceGlb(asset.cage, asset.maps, density.segments);
        LodChain chain = lodChain(asset, std::move(glb.mesh), density.segments, levels, o.screenSize);
        if (int(chain.levels.size()) < levels)
            warn(out.string() + ": " + std::to_string(chain.levels.size()) + " levels of detail written, not " +
                 std::to_string(levels) +
                 ": neither a coarser tessellation nor meshoptimizer's simplification (texture "
                 "seams and borders kept) gives level " +
                 std::to_string(chain.levels.size()) + " fewer triangles than " +
                 std::to_string(chain.levels.back().mesh.triangleCount()));

        std::vector<std::vector<unsigned char>> encoded;
        std::vector<std::size_t> meshBytes;
        for (LodLevel& level : chain.levels) {
            withoutUnreadAttributes(level.mesh, glb.textures);
            encoded.push_back(encodeFittedGlb(level.mesh, glb.textures, o.coding));
            meshBytes.push_back(glb.textures.any() ? encodeFittedGlb(level.mesh, {}, o.coding).size()
                                                   : encoded.back().size());
        }
        // The JSON first, from the bytes each level will have; then every file at once.
        std::vector<std::pair<std::filesystem::path, std::string_view>> files;
        nlohmann::json lods = nlohmann::json::array();
        for (size_t k = 0; k < chain.levels.size(); ++k) {
            const LodLevel& level = chain.levels[k];
            files.emplace_back(lodPath(out, int(k)),
                               std::string_view(reinterpret_cast<const char*>(encoded[k].data()), encoded[k].size()));
            nlohmann::json entry = {{"lod", k},
                                    {"file", lodPath(out, int(k)).filename().string()},
                                    {"triangles", level.mesh.triangleCount()},
                                    {"bytes", encoded[k].size()},
                                    {"bytes_without_images", meshBytes[k]},
                                    {"method", level.segments > 0 ? "tessellation" : "simplification"},
                                    {"mean_distance", level.meanDistance},
                                    {"max_distance", level.maxDistance},
                                    {"screen_size", level.screenSize}};
            if (level.segments > 0) entry["segments"] = level.segments;
            lods.push_back(std::move(entry));
        }
        std::string json;
        if (o.lods > 0) {
            nlohmann::json doc = {
                {"asset", subd.filename().string()},
                {"decode_triangles", asset.decodeTriangles},
                {"coding", o.coding == MeshCoding::Meshopt     ? "KHR_mesh_quantization, EXT_meshopt_compression"
                           : o.coding == MeshCoding::Quantized ? "KHR_mesh_quantization"
                                                               : "float"},
                {"distances", "mean and largest sampled distance to lod 0, both ways, in the asset's units"},
                {"screen_size_rule",
                 {{"pixel_error", o.screenSize.pixelError},
                  {"screen_height", o.screenSize.screenHeight},
                  {"bounding_sphere_radius", chain.boundingRadius},
                  {"screen_size",
                   "2 * pixel_error * bounding_sphere_radius / (max_distance * screen_height): the "
                   "bounding sphere's diameter over the screen height below which the level may be drawn"}}},
                {"lods", lods}};
            if (fromError)
                doc["max_error"] = {{"bound", fromError->bound},
                                    {"max_distance", fromError->maxDistance},
                                    {"reference_segments", fromError->referenceSegments},
                                    {"clamped_to_finest", fromError->clamped}};
            json = jsonText(doc, 2);
            files.emplace_back(lodJsonPath(out), json);
        }
        io::writeFilesTogether(files);
        std::vector<io::WrittenFile> written;
        for (const auto& [path, bytes] : files) written.push_back({.path = path, .bytes = bytes.size()});
        return written;
    } catch (const std::bad_alloc&) {
        throw fileError(subd.string(), "out of memory while decoding it");
    }
}

}  // namespace subdfit::exporter
