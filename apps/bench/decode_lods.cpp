// `subdfit-bench lods`: `subdfit decode --lods`'s levels next to gltfpack's at the same triangle
// counts: gltfpack -cc -si R on the decoded surface (floats), and on the dense reference when
// given. Every file is measured as it loads (quantisation included) against the same surfaces:
// level 0 as floats (the full decoded surface) and the reference. Plots bytes against each distance.
#include <cstdio>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "bench_commands.h"
#include "bench_common.h"
#include "plot.h"
#include "export/engine/engine_decode.h"
#include "export/engine/surface_error.h"
#include "export/engine/subd_decode.h"
#include "geometry/surface_distance.h"
#include "io/external_program.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

namespace subdfit::bench {
namespace {

struct Row {
    std::string source, method;
    int lod = 0;
    int triangles = 0;
    std::uintmax_t bytes = 0;
    geometry::SurfaceDistance toFull{}, toReference{};
};

mesh::PolygonMesh loadedTriangles(const std::filesystem::path& glb) { return mesh::triangulated(mesh::loadMesh(glb)); }

// gltfpack -cc -si `ratio` of `input` into `output` (with -sa where its error bound stops it
// short of the count, as a user held to a count would); false when gltfpack fails.
bool gltfpack(const std::filesystem::path& program, const std::filesystem::path& input,
              const std::filesystem::path& output, double ratio, int triangles) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9f", ratio);
    std::vector<std::string> arguments{"-i", input.string(), "-o", output.string(), "-cc"};
    if (ratio < 1.0) arguments.insert(arguments.end(), {"-si", text});
    if (io::runProgram(program, arguments) != 0) return false;
    if (ratio < 1.0 && loadedTriangles(output).faceCount() > triangles * 11 / 10) {
        arguments.push_back("-sa");
        if (io::runProgram(program, arguments) != 0) return false;
    }
    return std::filesystem::exists(output);
}

// Distances span decades down to quantisation steps: four significant digits each.
std::string scientific(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4e", value);
    return text;
}

}  // namespace

int runDecodeLods(const DecodeLodsOptions& o) {
    std::filesystem::create_directories(o.out);
    const auto subdfitGlb = o.out / "subdfit.glb";
    exporter::decodeForEngines(o.asset, subdfitGlb, {.density = {}, .maxError = std::nullopt, .lods = o.lods});
    std::ifstream file(exporter::lodJsonPath(subdfitGlb));
    const nlohmann::json lods = nlohmann::json::parse(file)["lods"];
    const int segments = lods[0]["segments"];
    const auto fullGlb = o.out / "full_float.glb";
    exporter::decodeToGlb(o.asset, fullGlb, {.segments = segments}, exporter::MeshCoding::Float);
    const mesh::PolygonMesh full = loadedTriangles(fullGlb);
    const std::optional<mesh::PolygonMesh> reference =
        o.reference.empty() ? std::nullopt : std::optional(loadedTriangles(o.reference));

    std::vector<Row> rows;
    auto measure = [&](const std::string& source, const std::string& method, int lod,
                       const std::filesystem::path& glb) {
        const mesh::PolygonMesh m = loadedTriangles(glb);
        Row row{source, method, lod, m.faceCount(), std::filesystem::file_size(glb)};
        row.toFull = geometry::surfaceDistance(m, full, exporter::kErrorSamples);
        if (reference) row.toReference = geometry::surfaceDistance(m, *reference, exporter::kErrorSamples);
        rows.push_back(row);
    };
    const auto program = io::findProgram("gltfpack");
    if (!program) std::fprintf(stderr, "subdfit-bench: gltfpack not found: subdfit's levels only\n");
    for (size_t k = 0; k < lods.size(); ++k) {
        const int triangles = lods[k]["triangles"];
        measure("subdfit", lods[k]["method"], int(k), o.out / lods[k]["file"].get<std::string>());
        if (!program) continue;
        const auto decoded = o.out / ("gltfpack_decoded_lod" + std::to_string(k) + ".glb");
        if (gltfpack(*program, fullGlb, decoded, double(triangles) / double(full.faceCount()), triangles))
            measure("gltfpack (decoded)", "simplification of the decoded surface", int(k), decoded);
        if (!reference) continue;
        const auto packed = o.out / ("gltfpack_reference_lod" + std::to_string(k) + ".glb");
        const double ratio = std::min(1.0, double(triangles) / double(reference->faceCount()));
        if (gltfpack(*program, o.reference, packed, ratio, triangles))
            measure("gltfpack (reference)", "simplification of the reference", int(k), packed);
    }

    std::vector<std::vector<std::string>> csv{{"source", "method", "lod", "triangles", "bytes", "mean_to_full",
                                               "max_to_full", "mean_to_reference", "max_to_reference"}};
    std::printf("%-21s %-14s %3s %9s %9s %12s %12s %12s %12s\n", "", "", "lod", "triangles", "bytes", "mean→full",
                "max→full", "mean→ref", "max→ref");
    for (const Row& r : rows) {
        std::printf("%-21s %-14s %3d %9d %9ju %12.3e %12.3e %12.3e %12.3e\n", r.source.c_str(),
                    r.method.substr(0, r.method.find(' ')).c_str(), r.lod, r.triangles, r.bytes, r.toFull.meanDistance,
                    r.toFull.hausdorff, r.toReference.meanDistance, r.toReference.hausdorff);
        csv.push_back({r.source, r.method, std::to_string(r.lod), std::to_string(r.triangles), std::to_string(r.bytes),
                       scientific(r.toFull.meanDistance), scientific(r.toFull.hausdorff),
                       scientific(r.toReference.meanDistance), scientific(r.toReference.hausdorff)});
    }
    writeCsv(o.out / "decode_lods.csv", csv);

    auto plot = [&](const std::string& file, const char* to, double geometry::SurfaceDistance::*measure,
                    geometry::SurfaceDistance Row::*from) {
        std::map<std::string, Series> series;
        for (const Row& r : rows) {
            Series& s = series[r.source];
            s.label = r.source;
            s.x.push_back(double(r.bytes));
            s.y.push_back(r.*from.*measure);
        }
        PlotSpec spec{.title = "subdfit decode --lods and gltfpack -si at its levels' triangles",
                      .xLabel = "bytes",
                      .yLabel = to,
                      .logX = true,
                      .logY = true};
        for (auto& [source, s] : series) spec.series.push_back(std::move(s));
        writePlot(o.out / file, spec);
    };
    plot("lods_max_to_full.png", "largest distance to the full decoded surface", &geometry::SurfaceDistance::hausdorff,
         &Row::toFull);
    if (reference)
        plot("lods_mean_to_reference.png", "mean distance to the reference", &geometry::SurfaceDistance::meanDistance,
             &Row::toReference);
    std::printf("%s\npeak_rss_mib=%.0f\n", (o.out / "decode_lods.csv").string().c_str(), peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
