// `subdfit-bench recovery`: a noised cage fitted back to renders of its own true limit surface.
// For cages with creases (OpenSubdiv's shapes) this says whether the fit cleans the cage or
// only the surface: the cage's vertex error and the limit surface's distance to the truth,
// before and after, with the image loss beside them.
#include <cmath>
#include <cstdio>
#include <random>

#include "bench_commands.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/device_defaults.h"
#include "fit/fit_run.h"
#include "geometry/surface_distance.h"
#include "gl/platform_defines.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "surface/tessellation.h"

namespace subdfit::bench {
namespace {

double rms(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += double(glm::dot(a[i] - b[i], a[i] - b[i]));
    return std::sqrt(sum / double(std::max<size_t>(1, a.size())));
}

struct Measure {
    double vertexRms, chamfer, loss, normalRms;
};

// The reference: the true limit surface, drawn finer than any fit draws it (fit/fit_scene.h).
constexpr float kReferenceSegmentPixels = 1.0f;

Measure measure(fit::FitRun& run, const std::vector<glm::vec3>& truth, const mesh::PolygonMesh& truthSurface,
                int segments) {
    mesh::PolygonMesh cage = run.scene().cage;
    cage.positions = run.fitter().vertices();
    mesh::PolygonMesh truthCage = cage;
    truthCage.positions = truth;
    const auto normals = mesh::vertexNormals(truthCage);
    double normalSum = 0.0;
    for (size_t v = 0; v < truth.size(); ++v) {
        const double d = glm::dot(cage.positions[v] - truth[v], normals[v]);
        normalSum += d * d;
    }
    return {rms(cage.positions, truth),
            geometry::surfaceDistance(surface::limitMesh(cage, segments), truthSurface, 30000).chamferL2Squared,
            fit::score(run.fitter(), run.scene().training).loss,
            std::sqrt(normalSum / double(std::max<size_t>(1, truth.size())))};
}

}  // namespace

int runRecovery(const RecoveryOptions& given) {
    auto context = context::createHeadlessContext(given.fit.glProvider);
    RecoveryOptions o = given;
    if (const std::string chosen = fit::resolveForCurrentDevice(o.fit); !chosen.empty())
        std::printf("%s\n", chosen.c_str());
    std::printf("recovery: cages noised by %.1f %% of the scene radius, %d views at %d^2, %d steps\n", 100.0 * o.sigma,
                o.fit.views, o.fit.resolution, o.fit.steps);
    std::printf("%-28s %9s %9s %7s %9s %11s %11s %7s %8s %7s %6s %5s\n", "shape", "vtx rms", "after", "ratio", "normal",
                "chamfer", "after", "ratio", "loss x", "floor x", "s", "steps");
    std::vector<std::vector<std::string>> rows{{"shape", "vertex_rms_before", "vertex_rms_after", "chamfer_before",
                                                "chamfer_after", "loss_ratio", "floor_ratio", "seconds"}};
    double worstVertexRatio = INFINITY, worstLossRatio = 0.0;  // as the table: vertex before/after, loss after/before
    for (const auto& shape : o.shapes) {
        const mesh::PolygonMesh truthWorld = mesh::loadMesh(shape);
        fit::FitOptions options = o.fit;
        options.out = o.out;
        gl::ProgramCache programs(gl::platformDefines());
        // Noise in world units, a fraction of the reference's radius.
        mesh::PolygonMesh noisedWorld = truthWorld;
        int segments = 0;
        {
            const fit::FitScene probe(fit::resolved(options), programs, truthWorld, surface::limitMesh(truthWorld, 8));
            std::mt19937 rng(o.noiseSeed);
            std::normal_distribution<float> normal(0.0f, o.sigma / probe.frame.scale);
            for (auto& p : noisedWorld.positions) p += glm::vec3(normal(rng), normal(rng), normal(rng));
            segments = std::max(8, fit::screenSegments(probe.cage, o.fit.resolution, kReferenceSegmentPixels));
        }
        const mesh::PolygonMesh referenceWorld = surface::limitMesh(truthWorld, segments);
        fit::FitScene scene(fit::resolved(options), programs, noisedWorld, referenceWorld);
        const auto truth = scene.frame.toNormalized(truthWorld.positions);
        mesh::PolygonMesh truthSurface = referenceWorld;
        truthSurface.positions = scene.frame.toNormalized(referenceWorld.positions);
        fit::FitRun run(fit::resolved(options), programs, scene);
        const Measure before = measure(run, truth, truthSurface, segments);
        // The loss the true cage itself scores, drawn as the fit draws it: how low the loss can go.
        const auto noised = run.fitter().vertices();
        run.fitter().setVertices(truth);
        const double floor = fit::score(run.fitter(), run.scene().training).loss / before.loss;
        run.fitter().setVertices(noised);
        const auto start = std::chrono::steady_clock::now();
        const fit::StopReason reason = run.run(o.out / "checkpoint.bin");
        glFinish();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const Measure after = measure(run, truth, truthSurface, segments);
        const std::string name = shape.stem().string();
        std::printf("%-28s %9.4f %9.4f %7.2f %9.4f %11.3e %11.3e %7.2f %8.2f %7.3f %6.1f %5d %s\n", name.c_str(),
                    before.vertexRms, after.vertexRms, before.vertexRms / after.vertexRms, after.normalRms,
                    before.chamfer, after.chamfer, before.chamfer / after.chamfer, after.loss / before.loss, floor,
                    seconds, run.step(), fit::toString(reason));
        std::fflush(stdout);
        rows.push_back({name, std::to_string(before.vertexRms), std::to_string(after.vertexRms),
                        std::to_string(before.chamfer), std::to_string(after.chamfer),
                        std::to_string(after.loss / before.loss), std::to_string(floor), std::to_string(seconds)});
        worstVertexRatio = std::min(worstVertexRatio, before.vertexRms / after.vertexRms);
        worstLossRatio = std::max(worstLossRatio, after.loss / before.loss);
    }
    std::filesystem::create_directories(o.out);
    writeCsv(o.out / "recovery.csv", rows);
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("worst_vertex_ratio=%.3f worst_loss_ratio=%.3f\n", worstVertexRatio, worstLossRatio);
    return 0;
}

}  // namespace subdfit::bench
