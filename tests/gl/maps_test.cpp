// Displacement and normal maps: per-texel gradients, recovering a bump, watertightness across
// tiles, and effects on demand (no map, no map code).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "gl_test_context.h"
#include "gradient_checks.h"
#include "surface/texel_layout.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "optim/updates.h"
#include "subdiv/limit_evaluator.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

void upload(optim::ParameterGroup& group, const std::vector<float>& values) {
    group.theta.upload(values.data(), GLsizeiptr(values.size() * sizeof(float)));
}

TEST(MapsGradient, DisplacementTexelsAgreeWithFiniteDifferences) {
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(4, 0.2f, 3), 2, 96);
    fit::CageFitSettings settings;
    settings.resolution = 96;
    settings.mapEffects.set(maps::MapKind::Displacement);
    settings.maps.resolution = 2;
    fit::CageFitter fitter(programs(), scene.cage, settings);
    auto& displacement = *fitter.maps()->displacement();
    const float epsilon = displacement.settings().epsilon;
    const int views[] = {0, 1};

    // Vertices and texels are perturbed together, as in a fit: the vertex signs are noise here.
    const int samples = 256;
    for (int k = 0; k < samples; ++k) fitter.accumulate(*scene.targets, views, false);
    optim::resolveGradient(programs(), displacement);  // G's fixed-point sums as floats
    const auto raw = displacement.gradient.read<float>();
    std::vector<double> sge(raw.begin(), raw.end());
    for (auto& g : sge) g /= samples;

    std::vector<double> reference(sge.size());
    std::vector<float> theta(sge.size(), 0.0f);
    for (size_t i = 0; i < reference.size(); ++i) {
        theta[i] = epsilon;
        upload(displacement, theta);
        const double plus = totalLoss(fitter, *scene.targets);
        theta[i] = -epsilon;
        upload(displacement, theta);
        const double minus = totalLoss(fitter, *scene.targets);
        theta[i] = 0.0f;
        reference[i] = (plus - minus) / (2.0 * epsilon);
    }
    const double similarity = cosine(sge, reference);
    std::printf("displacement texels: SGE vs finite differences cosine %.3f over %zu texels\n", similarity, sge.size());
    // Each pixel's Δ also carries the ~50 vertex parameters' perturbations and its 4 texels:
    // the same variance argument as for vertices gives ≈ 1/sqrt(1 + 54/256) ≈ 0.9 for K = 256.
    EXPECT_GT(similarity, 0.75);
    expectNoGlError();
}

// A triangle's tessellation level counts segments along its whole edge, which is two ptex
// edges, each with a whole map tile: a triangle cage needs twice the map resolution, or the
// heights of every other node are skipped between the vertices.
TEST(MapsTessellation, EveryMapCellGetsASegmentOnQuadAndTriangleCages) {
    for (const bool triangles : {false, true}) {
        const mesh::PolygonMesh cage =
            triangles ? mesh::triangulated(mesh::makeQuadSphere(1)) : mesh::makeQuadSphere(1);
        fit::CageFitSettings settings;
        settings.mapEffects.set(maps::MapKind::Displacement);
        settings.maps.resolution = 8;
        fit::CageFitter fitter(programs(), cage, settings);
        EXPECT_GE(fitter.renderer().tessLevel(), (triangles ? 2 : 1) * settings.maps.resolution) << triangles;
    }
    expectNoGlError();
}

TEST(MapsBump, FlatCageRecoversABumpInTheDisplacementMap) {
    const auto bump = [](float x, float y) { return 0.25f * std::exp(-(x * x + y * y) / 0.08f); };
    auto scene = makeFitScene(programs(), mesh::makeQuadGrid(3), mesh::makeQuadGrid(96, bump), 12, 128);
    fit::CageFitSettings settings;
    settings.resolution = 128;
    settings.mapEffects.set(maps::MapKind::Displacement);
    settings.maps.resolution = 8;
    settings.plannedSteps = 2000;
    settings.mapsStartFraction = 0.0f;
    settings.vertices.learningRate = 1e-4f;  // keep the cage flat: the bump must come from the map
    fit::CageFitter fitter(programs(), scene.cage, settings);
    for (int step = 0; step < settings.plannedSteps; ++step) {
        const int view[] = {step % scene.targets->size()};
        fitter.step(*scene.targets, view, false);
    }
    // Compare the displaced limit surface with the bump at the centre cells of the grid.
    const auto& layout = fitter.maps()->layout();
    const auto heights = fitter.maps()->displacement()->read();
    const auto cage = fitter.vertices();
    const subdiv::LimitEvaluator evaluator(scene.cage);
    // The reference went through the same normalisation as the cage: map the bump with it.
    const auto frame = scene::frameAround(mesh::makeQuadGrid(96, bump).positions);
    double errorFlat = 0.0, errorFitted = 0.0;
    int samples = 0;
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (float u : {0.25f, 0.5f, 0.75f})
            for (float v : {0.25f, 0.5f, 0.75f}) {
                const auto s = evaluator.evaluate(face, u, v, cage);
                const glm::vec3 n = glm::normalize(glm::cross(s.dPdu, s.dPdv));
                const glm::vec3 p = s.position + surface::sampleBilinear(layout, heights, 1, 0, face, u, v) * n;
                const glm::vec3 world = frame.toWorld(p);
                const float truth = frame.toNormalized(glm::vec3(world.x, world.y, bump(world.x, world.y))).z;
                errorFitted += std::pow(double(p.z - truth), 2);
                errorFlat += std::pow(double(s.position.z - truth), 2);
                ++samples;
            }
    errorFlat = std::sqrt(errorFlat / samples);
    errorFitted = std::sqrt(errorFitted / samples);
    const float peak = *std::max_element(heights.begin(), heights.end());
    std::printf("bump: height RMS error %.4f (no map) -> %.4f (fitted map), map peak %.3f\n", errorFlat, errorFitted,
                peak);
    EXPECT_LT(errorFitted, 0.4 * errorFlat);
    EXPECT_GT(peak, 0.0f);
    expectNoGlError();
}

TEST(MapsWatertight, ConstantDisplacementLeavesNoCrackAcrossTiles) {
    // Spot's cage: quads, triangles and pentagons, so tiles meet across n-gon splits too.
    auto cage = mesh::loadMesh(assetPath("spot/spot_control_mesh.obj"));
    const auto frame = scene::frameAround(cage.positions);
    cage.positions = frame.toNormalized(cage.positions);
    const auto layout = surface::buildTexelLayout(cage, 4);
    const std::vector<float> heights(size_t(layout.nodeCount), 0.03f);

    // Model: every welded border node lands on one point, whichever face evaluates it.
    const subdiv::LimitEvaluator evaluator(cage);
    std::vector<glm::vec3> nodePoint(size_t(layout.nodeCount), glm::vec3(NAN));
    float worst = 0.0f;
    const int n = layout.resolution;
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                if (i != 0 && j != 0 && i != n && j != n) continue;
                const float u = float(i) / n, v = float(j) / n;
                const auto s = evaluator.evaluate(face, u, v, cage.positions);
                const glm::vec3 p = s.position + 0.03f * glm::normalize(glm::cross(s.dPdu, s.dPdv));
                auto& seen = nodePoint[size_t(layout.node(face, i, j))];
                if (std::isnan(seen.x)) seen = p;
                else worst = std::max(worst, glm::length(seen - p));
            }
    std::printf("watertight: largest gap between tiles %.2e (scene radius 1)\n", worst);
    EXPECT_LT(worst, 1e-4f);

    // Raster: the displaced, closed surface shows no pinholes from any view.
    fit::CageFitSettings settings;
    settings.resolution = 192;
    settings.mapEffects.set(maps::MapKind::Displacement);
    settings.maps.resolution = 4;
    fit::CageFitter fitter(programs(), cage, settings);
    upload(*fitter.maps()->displacement(), heights);
    render::RenderTarget target(192, 192);
    for (const auto& camera : render::orbitCameras(6, 9)) {
        fitter.render(camera, target);
        const auto ids = target.readFaceId();
        int pinholes = 0;
        for (int y = 1; y + 1 < 192; ++y)
            for (int x = 1; x + 1 < 192; ++x) {
                auto at = [&](int dx, int dy) { return ids[size_t(y + dy) * 192 + size_t(x + dx)]; };
                if (at(0, 0) < 0 && at(1, 0) >= 0 && at(-1, 0) >= 0 && at(0, 1) >= 0 && at(0, -1) >= 0) ++pinholes;
            }
        EXPECT_EQ(pinholes, 0);
    }
    expectNoGlError();
}

TEST(MapsEffects, OnlyTheEffectsTheSceneUsesAreCompiledAndRun) {
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(3, 0.2f, 3), 1, 48);
    const int view[] = {0};
    auto run = [&](maps::MapEffects effects) {
        auto cache = std::make_unique<gl::ProgramCache>(platformDefines());
        fit::CageFitSettings settings;
        settings.resolution = 48;
        settings.mapEffects = effects;
        settings.maps.resolution = 2;
        fit::CageFitter fitter(*cache, scene.cage, settings);
        fitter.step(*scene.targets, view);
        render::RenderTarget image(48, 48);
        fitter.render(scene.targets->camera(0), image);
        EXPECT_EQ(fitter.groups().size(),
                  1 + size_t(effects.has(maps::MapKind::Displacement)) + size_t(effects.has(maps::MapKind::NormalMap)));
        EXPECT_EQ(fitter.maps() == nullptr, !effects.any());
        return cache;
    };
    // No maps: no variant with map code exists, so none was ever dispatched or drawn.
    const auto plain = run({});
    EXPECT_FALSE(anyVariantDefines(*plain, "SUBDFIT_DISPLACEMENT"));
    EXPECT_FALSE(anyVariantDefines(*plain, "SUBDFIT_NORMAL_MAP"));
    // Displacement only: its code, and still no normal-map code.
    const auto displaced = run({maps::MapKind::Displacement});
    EXPECT_TRUE(anyVariantDefines(*displaced, "SUBDFIT_DISPLACEMENT"));
    EXPECT_FALSE(anyVariantDefines(*displaced, "SUBDFIT_NORMAL_MAP"));
    const auto normal = run({maps::MapKind::NormalMap});
    EXPECT_FALSE(anyVariantDefines(*normal, "SUBDFIT_DISPLACEMENT"));
    EXPECT_TRUE(anyVariantDefines(*normal, "SUBDFIT_NORMAL_MAP"));
    EXPECT_FALSE(anyVariantDefines(*displaced, "SUBDFIT_LIMIT_SHADING"));  // only where asked for (below)
    expectNoGlError();
}

// surface::ShadingNormal::Limit, what simplify ships for a faceted reference: the heights move
// the surface, the limit normal shades it. A flat cage then shades in one colour whatever its
// heights, and the same heights shade it unevenly when their slopes tilt the normal.
TEST(MapsShading, LimitShadingIgnoresTheHeightsSlopes) {
    auto cage = mesh::makeQuadGrid(3);
    cage.positions = scene::frameAround(cage.positions).toNormalized(cage.positions);
    constexpr int kSize = 96;
    auto colourSpread = [&](surface::ShadingNormal shading) {
        auto cache = std::make_unique<gl::ProgramCache>(platformDefines());
        fit::CageFitSettings settings;
        settings.resolution = kSize;
        settings.mapEffects.set(maps::MapKind::Displacement);
        settings.maps.resolution = 8;
        settings.maps.shadingNormal = shading;
        fit::CageFitter fitter(*cache, cage, settings);
        std::vector<float> heights(size_t(fitter.maps()->layout().nodeCount));
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> height(-0.02f, 0.02f);
        for (float& h : heights) h = height(rng);
        upload(*fitter.maps()->displacement(), heights);
        render::RenderTarget image(kSize, kSize);
        fitter.render(render::orbitCamera({0.3f, 0.2f, 1.0f}), image);
        EXPECT_EQ(anyVariantDefines(*cache, "SUBDFIT_LIMIT_SHADING"), shading == surface::ShadingNormal::Limit);
        // Spread of the red channel over the covered pixels (the lights are directional and the
        // flat cage's shading Lambertian: one normal, one colour).
        double sum = 0.0, squares = 0.0;
        int covered = 0;
        for (const glm::vec4& p : image.readColor())
            if (p.a > 0.5f) sum += p.r, squares += double(p.r) * p.r, ++covered;
        EXPECT_GT(covered, kSize * kSize / 4);
        const double mean = sum / covered;
        return std::sqrt(std::max(0.0, squares / covered - mean * mean));
    };
    const double limit = colourSpread(surface::ShadingNormal::Limit);
    const double displaced = colourSpread(surface::ShadingNormal::Displaced);
    std::printf("red spread over a flat cage with rough heights: limit-shaded %.5f, displaced %.5f\n", limit,
                displaced);
    EXPECT_LT(limit, 2e-3);
    EXPECT_GT(displaced, 10.0 * limit + 0.01);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
