// `subdfit-bench maps`: what the displacement and normal maps buy over a vertex-only fit, on a
// reference with detail far finer than the cage can express (by default a sphere covered in small
// bumps over the ~200-quad sphere cage; or any cage, with its own limit surface relieved as the
// reference): held-out PSNR, time and the bytes of asset.subd, each fit with the same
// options but its maps.
#include <cstdio>

#include "bench_commands.h"
#include "bench_common.h"
#include "export/gltf/glb_writer.h"
#include "fit/fit_job.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "surface/relief_surface.h"

namespace subdfit::bench {
namespace {

// The case's cage and reference, as files a fit reads.
std::pair<std::filesystem::path, std::filesystem::path> writeCase(const MapsGainOptions& o) {
    if (o.cage.empty()) {
        mesh::writeObj(o.out / "bumpy_sphere.obj", mesh::makeLumpySphere(6, 0.04f, 3, 150, 0.002f, 0.01f));
        mesh::writeObj(o.out / "quad_sphere_cage.obj", mesh::makeQuadSphere(6));
        return {o.out / "quad_sphere_cage.obj", o.out / "bumpy_sphere.obj"};
    }
    if (!o.reference.empty()) return {o.cage, o.reference};
    const mesh::PolygonMesh surface =
        surface::reliefSurface(mesh::loadMesh(o.cage), {.amplitude = o.reliefAmplitude, .seed = o.reliefSeed});
    const auto reference = o.out / "relief_reference.glb";
    exporter::writeMeshGlb(reference, surface.positions, mesh::vertexNormals(surface),
                           {surface.faceIndices.begin(), surface.faceIndices.end()}, /*draco=*/false);
    return {o.cage, reference};
}

}  // namespace

int runMapsGain(const MapsGainOptions& o) {
    std::filesystem::create_directories(o.out);
    const auto [cage, reference] = writeCase(o);
    std::vector<std::string> runs{"none"};
    runs.insert(runs.end(), o.compared.begin(), o.compared.end());
    std::vector<std::vector<std::string>> rows{{"maps", "steps", "stop_reason", "fit_seconds", "psnr_holdout_initial",
                                                "psnr_holdout", "gain_over_none_db", "asset_subd_bytes", "parameters"}};
    std::printf("maps: %s against %s\n", cage.filename().c_str(), reference.filename().c_str());
    std::printf("%-22s %6s %10s %8s %10s %10s %9s %12s\n", "maps", "steps", "stop", "fit s", "PSNR in", "PSNR out",
                "vs none", "asset.subd B");
    double vertexOnly = 0.0;
    for (const auto& maps : runs) {
        fit::FitOptions fit = o.fit;
        fit.cage = cage;
        fit.reference = reference;
        fit.out = o.out / maps;
        fit.maps = maps::parseMapEffects(maps);
        fit.force = true;
        const auto report = fit::runFit(fit);
        const std::uintmax_t bytes = report.exports.at("asset.subd");
        int parameters = 0;
        for (const auto& [group, count] : report.parameters) parameters += count;
        if (maps == "none") vertexOnly = report.holdoutAfter.psnr;
        const double gain = report.holdoutAfter.psnr - vertexOnly;
        std::printf("%-22s %6d %10s %8.1f %10.2f %10.2f %+9.2f %12ju\n", maps.c_str(), report.steps,
                    report.stopReason.c_str(), report.fitSeconds, report.holdoutBefore.psnr, report.holdoutAfter.psnr,
                    gain, bytes);
        std::fflush(stdout);
        rows.push_back({maps, std::to_string(report.steps), report.stopReason, std::to_string(report.fitSeconds),
                        std::to_string(report.holdoutBefore.psnr), std::to_string(report.holdoutAfter.psnr),
                        std::to_string(gain), std::to_string(bytes), std::to_string(parameters)});
    }
    writeCsv(o.out / "maps_gain.csv", rows);
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
