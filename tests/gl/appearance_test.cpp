// Appearance: a reference's material in its renders, the appearance groups' per-texel gradients
// against finite differences, shading on demand (a scene without materials compiles and
// dispatches no material code), and simplify shipping a coloured asset, glow included.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numeric>

#include <nlohmann/json.hpp>

#include "codec/subd_format.h"
#include "export/gltf/textured_glb.h"
#include "gl_test_context.h"
#include "gradient_checks.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "optim/updates.h"
#include "render/shading_model.h"
#include "scene_fixture.h"
#include "small_simplify.h"
#include "simplify/simplify_job.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

// A lumpy sphere painted by position (vertex colours) with one material: `metallic` and
// `roughness` as given.
mesh::PolygonMesh paintedSphere(float metallic, float roughness) {
    mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeLumpySphere(4, 0.15f, 3));
    for (const glm::vec3& p : sphere.positions)
        sphere.colors.push_back({0.5f + 0.4f * p.x, 0.5f + 0.4f * std::sin(3.0f * p.y), 0.5f - 0.3f * p.z, 1.0f});
    mesh::Material m = mesh::defaultMaterial();
    m.metallicFactor = metallic;
    m.roughnessFactor = roughness;
    sphere.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{m}, {}});
    sphere.faceMaterials.assign(size_t(sphere.faceCount()), 0);
    return sphere;
}

struct ShadedScene {
    mesh::PolygonMesh cage, reference;
    std::unique_ptr<render::MeshRenderer> renderer;
    std::unique_ptr<scene::TargetSet> targets;
};

ShadedScene shadedScene(render::ShadingModel shading, int views, int resolution) {
    ShadedScene s;
    s.reference = paintedSphere(0.3f, 0.4f);
    const auto frame = scene::frameAround(s.reference.positions);
    s.reference.positions = frame.toNormalized(s.reference.positions);
    s.cage = mesh::makeQuadSphere(2);
    s.cage.positions = frame.toNormalized(s.cage.positions);
    s.renderer = std::make_unique<render::MeshRenderer>(s.reference, shading);
    s.targets = std::make_unique<scene::TargetSet>(programs(), *s.renderer, render::orbitCameras(views, 1), resolution);
    return s;
}

// Atlas coordinates for every ptex corner of a quad cage: its cage vertex seen from +z, so that
// the front and the back of the sphere share the 4 × 4 texels (each texel reached by many faces).
std::vector<glm::vec2> projectedCornerUvs(const mesh::PolygonMesh& cage) {
    std::vector<glm::vec2> uvs;
    int offset = 0;
    for (int n : cage.faceSizes) {
        EXPECT_EQ(n, 4);
        for (int k : {0, 1, 2, 3}) {
            const glm::vec3 p = cage.positions[size_t(cage.faceIndices[size_t(offset + k)])];
            uvs.push_back(glm::vec2(0.5f) + 0.45f * glm::vec2(p.x, p.y) / glm::length(p));
        }
        offset += n;
    }
    return uvs;
}

// SGE of one appearance group, alone in the turns, against central differences of the image
// loss, parameter by parameter; on 2-cell tiles, or on a 4 × 4 atlas.
double appearanceCosine(render::ShadingModel shading, bool baseColor, bool atlas = false) {
    const ShadedScene scene = shadedScene(shading, 2, 96);
    fit::CageFitSettings settings;
    settings.resolution = 96;
    settings.shading = shading;
    settings.mapEffects = {maps::MapKind::BaseColor};
    settings.mapEffects.set(maps::MapKind::MetallicRoughness, shading == render::ShadingModel::MetallicRoughness);
    settings.maps.appearanceResolution = 2;
    settings.maps.appearanceAtlas = atlas ? 4 : 0;
    fit::CageFitter fitter(programs(), scene.cage, settings);
    if (atlas) fitter.maps()->setAppearanceUvs(projectedCornerUvs(scene.cage));
    auto& group = *fitter.maps()->group(baseColor ? maps::MapKind::BaseColor : maps::MapKind::MetallicRoughness);
    for (auto* g : fitter.groups()) fitter.setOptimised(*g, g == &group);
    const float epsilon = group.settings().epsilon;
    const int views[] = {0, 1};
    const int samples = 256;
    for (int k = 0; k < samples; ++k) fitter.accumulate(*scene.targets, views, false);
    optim::resolveGradient(programs(), group);
    const auto raw = group.gradient.read<float>();
    std::vector<double> sge(raw.begin(), raw.end());
    for (auto& g : sge) g /= samples;

    const std::vector<float> start = group.read();
    std::vector<double> reference(sge.size());
    for (size_t i = 0; i < reference.size(); ++i) {
        std::vector<float> theta = start;
        theta[i] = start[i] + epsilon;
        group.write(theta);
        const double plus = totalLoss(fitter, *scene.targets);
        theta[i] = start[i] - epsilon;
        group.write(theta);
        const double minus = totalLoss(fitter, *scene.targets);
        reference[i] = (plus - minus) / (2.0 * epsilon);
    }
    group.write(start);
    const double similarity = cosine(sge, reference);
    std::printf("%s: SGE vs finite differences cosine %.3f over %zu parameters\n", group.name().c_str(), similarity,
                sge.size());
    expectNoGlError();
    return similarity;
}

TEST(AppearanceGradient, BaseColorTexelsAgreeWithFiniteDifferences) {
    EXPECT_GT(appearanceCosine(render::ShadingModel::Lambert, true), 0.75);
}

TEST(AppearanceGradient, MetallicRoughnessTexelsAgreeWithFiniteDifferences) {
    EXPECT_GT(appearanceCosine(render::ShadingModel::MetallicRoughness, false), 0.75);
}

TEST(AppearanceGradient, AtlasTexelsAgreeWithFiniteDifferences) {
    EXPECT_GT(appearanceCosine(render::ShadingModel::Lambert, true, true), 0.75);
    EXPECT_GT(appearanceCosine(render::ShadingModel::MetallicRoughness, false, true), 0.75);
}

TEST(AppearanceRender, TheDuckRendersInItsOwnYellow) {
    mesh::PolygonMesh duck = mesh::triangulated(mesh::loadReference(assetPath("gltf/Duck/Duck.glb")));
    ASSERT_EQ(render::shadingFor(duck), render::ShadingModel::Lambert);
    const auto frame = scene::frameAround(duck.positions);
    duck.positions = frame.toNormalized(duck.positions);
    gl::ProgramCache cache(platformDefines());
    const render::MeshRenderer renderer(duck, render::ShadingModel::Lambert);
    render::RenderTarget target(96, 96);
    renderer.draw(cache, render::orbitCameras(1, 3)[0], target);
    glm::dvec3 sum(0.0);
    int covered = 0;
    const auto ids = target.readFaceId();
    const auto colors = target.readColor();
    for (size_t p = 0; p < colors.size(); ++p)
        if (ids[p] >= 0) sum += glm::dvec3(colors[p]), ++covered;
    ASSERT_GT(covered, 500);
    sum /= double(covered);
    std::printf("duck: mean colour (%.2f, %.2f, %.2f) over %d pixels\n", sum.x, sum.y, sum.z, covered);
    EXPECT_GT(sum.x, 2.0 * sum.z);
    EXPECT_GT(sum.y, 1.5 * sum.z);
    // A Lambert scene with a base colour texture: that texture's code, and no other material's.
    EXPECT_TRUE(anyVariantDefines(cache, "SUBDFIT_BASE_COLOR_TEXTURE"));
    EXPECT_TRUE(anyVariantDefines(cache, "SUBDFIT_SHADING_LAMBERT"));
    EXPECT_FALSE(anyVariantDefines(cache, "SUBDFIT_SHADING_PBR"));
    EXPECT_FALSE(anyVariantDefines(cache, "SUBDFIT_METALLIC_ROUGHNESS_TEXTURE"));
    EXPECT_FALSE(anyVariantDefines(cache, "SUBDFIT_NORMAL_TEXTURE"));
    expectNoGlError();
}

// The whole fit, from targets to updates, on a scene without materials and on a Lambert one:
// what each compiled is what each ran (programs are built on first use).
TEST(AppearanceEffects, ASceneWithoutMaterialsCompilesAndRunsNoMaterialWork) {
    auto run = [](render::ShadingModel shading, gl::ProgramCache& cache) {
        mesh::PolygonMesh reference = paintedSphere(0.0f, 1.0f);
        if (shading == render::ShadingModel::Geometry) {
            reference.materials.reset();
            reference.faceMaterials.clear();
            reference.colors.clear();
        }
        const auto frame = scene::frameAround(reference.positions);
        reference.positions = frame.toNormalized(reference.positions);
        mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
        cage.positions = frame.toNormalized(cage.positions);
        const render::MeshRenderer renderer(reference, shading);
        const scene::TargetSet targets(cache, renderer, render::orbitCameras(2, 1), 48);
        fit::CageFitSettings settings;
        settings.resolution = 48;
        settings.shading = shading;
        settings.mapEffects = {maps::MapKind::Displacement};
        settings.mapEffects.set(maps::MapKind::BaseColor, shading != render::ShadingModel::Geometry);
        settings.maps.resolution = 2;
        settings.maps.appearanceResolution = 2;
        fit::CageFitter fitter(cache, cage, settings);
        const int view[] = {0};
        for (int k = 0; k < 6; ++k) fitter.step(targets, view);  // vertex and texel turns
        EXPECT_EQ(fitter.groups().size(), shading == render::ShadingModel::Geometry ? 2u : 3u);
    };
    gl::ProgramCache plain(platformDefines());
    run(render::ShadingModel::Geometry, plain);
    for (const char* define :
         {"SUBDFIT_SHADING_UNLIT", "SUBDFIT_SHADING_LAMBERT", "SUBDFIT_SHADING_PBR", "SUBDFIT_BASE_COLOR_TEXTURE",
          "SUBDFIT_BASE_COLOR_MAP", "SUBDFIT_METALLIC_ROUGHNESS_MAP"})
        EXPECT_FALSE(anyVariantDefines(plain, define)) << define;
    // Its only texel group is the displacement: one channel, and no three-channel G variant.
    for (const auto& v : plain.variants()) {
        if (v.defines.count("SUBDFIT_TEXEL_CHANNELS")) {
            EXPECT_EQ(v.defines.at("SUBDFIT_TEXEL_CHANNELS"), "1");
        }
    }

    gl::ProgramCache colored(platformDefines());
    run(render::ShadingModel::Lambert, colored);
    EXPECT_TRUE(anyVariantDefines(colored, "SUBDFIT_SHADING_LAMBERT"));
    EXPECT_TRUE(anyVariantDefines(colored, "SUBDFIT_BASE_COLOR_MAP"));
    EXPECT_FALSE(anyVariantDefines(colored, "SUBDFIT_METALLIC_ROUGHNESS_MAP"));
    bool threeChannels = false;
    for (const auto& v : colored.variants())
        threeChannels = threeChannels ||
                        (v.defines.count("SUBDFIT_TEXEL_CHANNELS") && v.defines.at("SUBDFIT_TEXEL_CHANNELS") == "3");
    EXPECT_TRUE(threeChannels);
    expectNoGlError();
}

// A small simplify of `reference` into dir/out: 120 faces, T = 2 heights, appearance T = 4, a preview.
simplify::SimplifyOptions smallColouredSimplify(const std::filesystem::path& reference,
                                                const std::filesystem::path& dir, int steps) {
    simplify::SimplifyOptions o = smallSimplify(reference, dir / "out", steps);
    o.fit.mapResolution = 2;
    o.fit.appearanceResolution = 4;
    o.fit.preview = true;
    o.faces = 120;
    return o;
}

TEST(AppearanceSimplify, TheDuckShipsInColour) {
    const auto dir = scratchDir("appearance_duck");
    const simplify::SimplifyOptions o = smallColouredSimplify(assetPath("gltf/Duck/Duck.glb"), dir, 30);
    const auto report = simplify::toJson(simplify::runSimplify(o));
    const auto effects = report["effects"];
    EXPECT_NE(std::find(effects.begin(), effects.end(), "base_color"), effects.end()) << effects;
    // The shipped file carries the base colour, on the lattice the options asked for.
    const auto shipped = codec::readSubd(dir / "out" / "asset.subd");
    ASSERT_TRUE(shipped.maps.hasBaseColor());
    EXPECT_EQ(shipped.maps.appearanceLayout.resolution, 4);
    // The duck is yellow wherever it is not its orange beak or black eyes: most nodes are.
    int yellow = 0;
    const auto& c = shipped.maps.baseColor;
    for (size_t n = 0; n < c.size(); n += 3) yellow += c[n] > 0.6f && c[n + 1] > 0.5f && c[n + 2] < 0.35f;
    EXPECT_GT(yellow, int(c.size() / 3) / 2);
    // The preview's material shows it: a base colour texture on TEXCOORD_0.
    std::ifstream in(dir / "out" / "fitted.glb", std::ios::binary);
    const std::string glb{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NE(glb.find("\"baseColorTexture\""), std::string::npos);
    EXPECT_GT(report["psnr_holdout"].get<double>(), report["psnr_holdout_initial"].get<double>() - 0.5);
    expectNoGlError();
}

// A reference of two materials (so tiles, not its atlas) whose top half glows: the tiles carry
// its emission unfitted, asset.subd ships it (EMIS) and the preview's material shows it.
TEST(AppearanceSimplify, AGlowOnTilesIsCarriedAndShipped) {
    const auto dir = scratchDir("appearance_glow");
    mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(6));
    mesh::Material plain = mesh::defaultMaterial(), glowing = plain;
    plain.baseColorFactor = glowing.baseColorFactor = {0.2f, 0.2f, 0.25f, 1.0f};
    plain.metallicFactor = glowing.metallicFactor = 0.0f;
    glowing.emissiveFactor = {1.0f, 0.5f, 0.0f};
    sphere.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{plain, glowing}, {}});
    for (int f = 0; f < sphere.faceCount(); ++f) {
        const auto* v = &sphere.faceIndices[size_t(3 * f)];
        const float y =
            (sphere.positions[size_t(v[0])].y + sphere.positions[size_t(v[1])].y + sphere.positions[size_t(v[2])].y) /
            3.0f;
        sphere.faceMaterials.push_back(y > 0.2f ? 1 : 0);
    }
    exporter::writeTexturedGlb(dir / "glow.glb", sphere, mesh::vertexNormals(sphere), {}, false);

    const auto report = simplify::toJson(simplify::runSimplify(smallColouredSimplify(dir / "glow.glb", dir, 10)));
    EXPECT_NE(report["shader_variants"].dump().find("SUBDFIT_CARRIED_EMISSIVE"), std::string::npos);
    const auto shipped = codec::readSubd(dir / "out" / "asset.subd");
    ASSERT_EQ(shipped.maps.emissive.size(), 3 * size_t(shipped.maps.appearanceLayout.nodeCount));
    int lit = 0, dark = 0;
    const auto& e = shipped.maps.emissive;
    for (size_t n = 0; n < e.size(); n += 3) {
        lit += e[n] > 0.85f && e[n + 1] > 0.6f && e[n + 2] < 0.15f;  // (1, 0.5, 0) linear, in sRGB
        dark += e[n] < 0.1f && e[n + 1] < 0.1f && e[n + 2] < 0.1f;
    }
    const int nodes = shipped.maps.appearanceLayout.nodeCount;
    EXPECT_GT(lit, nodes / 5) << "of " << nodes;
    EXPECT_GT(dark, nodes / 3) << "of " << nodes;
    std::ifstream in(dir / "out" / "fitted.glb", std::ios::binary);
    const std::string glb{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NE(glb.find("\"emissiveTexture\""), std::string::npos);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
