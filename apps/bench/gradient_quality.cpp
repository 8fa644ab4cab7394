// `subdfit-bench gradient`: what the SGE gradient is worth against what it costs. On a small
// scene (a 54-quad sphere cage against a lumpy sphere, 2 views at 96²): cosine similarity of the
// estimate averaged over k samples to central finite differences of the same rasteriser, against
// k and against time, for the per-pixel estimator and plain full-image SPSA; and an ε sweep.
#include <glad/gl.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "bench_commands.h"
#include "gl/platform_defines.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "fit/finite_differences.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "plot.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"

namespace subdfit::bench {
namespace {

struct Scene {
    mesh::PolygonMesh cage;
    std::unique_ptr<render::MeshRenderer> reference;
    std::unique_ptr<scene::TargetSet> targets;
};

Scene makeScene(gl::ProgramCache& programs) {
    Scene s;
    auto reference = mesh::makeLumpySphere(4, 0.2f, 3);
    s.cage = mesh::makeQuadSphere(3);
    const auto frame = scene::frameAround(reference.positions);
    reference.positions = frame.toNormalized(reference.positions);
    s.cage.positions = frame.toNormalized(s.cage.positions);
    s.reference = std::make_unique<render::MeshRenderer>(
        reference.positions, mesh::vertexNormals(reference),
        std::vector<unsigned>(reference.faceIndices.begin(), reference.faceIndices.end()));
    s.targets = std::make_unique<scene::TargetSet>(programs, *s.reference, render::orbitCameras(2, 1), 96);
    return s;
}

double cosine(const std::vector<float>& a, const std::vector<double>& b) {
    double ab = 0, aa = 0, bb = 0;
    for (size_t i = 0; i < b.size(); ++i) ab += a[i] * b[i], aa += double(a[i]) * a[i], bb += b[i] * b[i];
    return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

struct Curve {
    std::vector<double> samples, seconds, cosine;
};

// Cosine of the running mean after 1, 2, 4, ... samples (the mean's direction is the sum's).
Curve sampleCurve(gl::ProgramCache& programs, const Scene& s, const std::vector<double>& reference, float epsilon,
                  bool fullImage, int maxSamples) {
    fit::CageFitSettings settings;
    settings.resolution = s.targets->resolution();
    settings.vertices.epsilon = epsilon;
    settings.fullImageEstimator = fullImage;
    fit::CageFitter fitter(programs, s.cage, settings);
    const int views[] = {0, 1};
    fitter.accumulate(*s.targets, views, false);  // compile outside the clock
    fitter.takeGradient();
    Curve curve;
    double seconds = 0.0;
    for (int k = 1, next = 1; k <= maxSamples; ++k) {
        const auto start = std::chrono::steady_clock::now();
        fitter.accumulate(*s.targets, views, false);
        glFinish();
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (k == next) {
            curve.samples.push_back(k);
            curve.seconds.push_back(seconds);
            curve.cosine.push_back(cosine(fitter.accumulatedGradient(), reference));
            next *= 2;
        }
    }
    return curve;
}

}  // namespace

int runGradientQuality(const GradientOptions& o) {
    auto context = context::createHeadlessContext(o.glProvider);
    gl::ProgramCache programs(gl::platformDefines());
    const Scene scene = makeScene(programs);
    fit::CageFitSettings settings;
    settings.resolution = scene.targets->resolution();
    fit::CageFitter probe(programs, scene.cage, settings);
    const auto reference = fit::vertexFiniteDifferences(probe, *scene.targets, scene.cage.positions, o.epsilon);
    std::printf("scene: %d-quad cage, %zu parameters, 2 views at %d^2; finite differences with h = %.3g\n",
                scene.cage.faceCount(), reference.size(), scene.targets->resolution(), double(o.epsilon));

    std::filesystem::create_directories(o.out);
    std::vector<std::vector<std::string>> rows{{"experiment", "estimator", "epsilon", "samples", "seconds", "cosine"}};
    std::vector<Series> bySamples, byTime;
    double perPixelAtMax = 0.0, fullImageAtMax = 0.0;
    std::printf("\n%-12s %8s %10s %8s\n", "estimator", "samples", "seconds", "cosine");
    for (bool fullImage : {false, true}) {
        const std::string name = fullImage ? "full-image" : "per-pixel";
        const auto curve = sampleCurve(programs, scene, reference, o.epsilon, fullImage, o.maxSamples);
        for (size_t i = 0; i < curve.samples.size(); ++i) {
            std::printf("%-12s %8.0f %10.3f %8.3f\n", name.c_str(), curve.samples[i], curve.seconds[i],
                        curve.cosine[i]);
            rows.push_back({"samples", name, std::to_string(o.epsilon), std::to_string(int(curve.samples[i])),
                            std::to_string(curve.seconds[i]), std::to_string(curve.cosine[i])});
        }
        (fullImage ? fullImageAtMax : perPixelAtMax) = curve.cosine.back();
        bySamples.push_back({name, curve.samples, curve.cosine});
        byTime.push_back({name, curve.seconds, curve.cosine});
    }

    std::printf("\nε sweep, per-pixel, %d samples (cosine to the h = %.3g finite differences)\n", o.sweepSamples,
                double(o.epsilon));
    std::printf("%10s %8s\n", "epsilon", "cosine");
    Series sweep{"per-pixel", {}, {}};
    for (float epsilon : {0.0005f, 0.001f, 0.002f, 0.004f, 0.008f, 0.016f, 0.032f, 0.064f, 0.128f}) {
        const auto curve = sampleCurve(programs, scene, reference, epsilon, false, o.sweepSamples);
        std::printf("%10.4f %8.3f\n", double(epsilon), curve.cosine.back());
        rows.push_back({"epsilon", "per-pixel", std::to_string(epsilon), std::to_string(o.sweepSamples),
                        std::to_string(curve.seconds.back()), std::to_string(curve.cosine.back())});
        sweep.x.push_back(epsilon);
        sweep.y.push_back(curve.cosine.back());
    }

    writeCsv(o.out / "gradient.csv", rows);
    auto logXPlot = [](std::string title, std::string xLabel, std::vector<Series> series) {
        PlotSpec spec;
        spec.title = std::move(title);
        spec.xLabel = std::move(xLabel);
        spec.yLabel = "cosine similarity";
        spec.logX = true;
        spec.series = std::move(series);
        return spec;
    };
    writePlot(o.out / "gradient_cosine_vs_samples.png",
              logXPlot("SGE gradient quality: cosine to finite differences", "samples averaged (k)", bySamples));
    writePlot(o.out / "gradient_cosine_vs_time.png",
              logXPlot("SGE gradient quality against cost", "seconds (llvmpipe, this machine)", byTime));
    writePlot(o.out / "gradient_epsilon.png",
              logXPlot("Perturbation size (" + std::to_string(o.sweepSamples) + " samples, per-pixel)",
                       "epsilon (scene radius = 1)", {sweep}));
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("full_image_cosine=%.3f\n", fullImageAtMax);
    std::printf("per_pixel_cosine=%.3f\n", perPixelAtMax);
    return 0;
}

}  // namespace subdfit::bench
