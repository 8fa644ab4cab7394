#include "simplify/compare/baselines.h"

#include <algorithm>
#include <cstdio>
#include <functional>

#include "export/glb_writer.h"
#include "export/map_atlas.h"
#include "export/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "io/external_program.h"
#include "mesh/mesh_loader.h"
#include "mesh/mesh_geometry.h"
#include "render/mesh_renderer.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/decimate.h"
#include "surface/tessellation.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

std::vector<std::uint32_t> indicesOf(const mesh::PolygonMesh& triangles) {
    return {triangles.faceIndices.begin(), triangles.faceIndices.end()};
}

}  // namespace

int mostWithinBudget(int fewest, int most, std::uintmax_t budget, const std::function<std::uintmax_t(int)>& ship) {
    int lo = std::min(fewest, most), hi = most;
    while (lo < hi) {
        const int mid = lo + (hi - lo + 1) / 2;
        if (ship(mid) <= budget) lo = mid;
        else hi = mid - 1;
    }
    ship(lo);
    return lo;
}

namespace {

// A triangle baseline (normalised frame) scored as every baseline is: rendered with smooth
// normals on the held-out views, and its surface distance to the reference.
void scoreTriangles(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& triangles,
                    const BaselineSettings& settings, Quality& q) {
    const render::MeshRenderer renderer(triangles.positions, mesh::vertexNormals(triangles),
                                        std::vector<unsigned>(triangles.faceIndices.begin(), triangles.faceIndices.end()));
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        renderer.draw(programs, camera, target);
    }, q);
    q.distance = worldDistance(triangles, scene.reference, scene.frame, settings.surfaceSamples);
}

// Never fewer triangles than a closed shape needs.
constexpr int kFewestTriangles = 12;

}  // namespace

Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& welded,
                           std::uintmax_t budget, const BaselineSettings& settings) {
    const auto path = settings.dir / "decimated.glb";
    mesh::PolygonMesh decimated;
    std::uintmax_t bytes = 0;
    mostWithinBudget(kFewestTriangles, welded.faceCount(), budget, [&](int triangles) {
        throwIfStopRequested();
        decimated = decimate(welded, triangles);
        const auto normals = mesh::vertexNormals(decimated);  // normalised or not, the same unit normals
        bytes = exporter::writeMeshGlb(path, scene.frame.toWorld(decimated.positions), normals, indicesOf(decimated),
                                       /*draco=*/true)
                    .bytes;
        return bytes;
    });
    Quality q;
    q.bytes = bytes;
    q.files = {{"decimated.glb", bytes}};
    q.shipped = settings.dir.filename() / path.filename();
    q.details = {{"triangles", decimated.faceCount()}, {"over_budget", bytes > budget}};
    scoreTriangles(programs, scene, decimated, settings, q);
    return q;
}

std::optional<Quality> gltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                        const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                        const BaselineSettings& settings) {
    const auto gltfpack = io::findProgram("gltfpack");
    if (!gltfpack) return std::nullopt;
    // gltfpack gets what the decimation gets: the welded reference with smooth normals.
    const auto input = settings.dir / "gltfpack_input.glb", output = settings.dir / "gltfpack.glb";
    exporter::writeMeshGlb(input, scene.frame.toWorld(welded.positions), mesh::vertexNormals(welded), indicesOf(welded),
                           /*draco=*/false);
    // gltfpack's simplifier stops where its error bound says the shape would suffer; a user
    // held to a budget it cannot reach that way adds -sa (aggressive), and so does this.
    std::uintmax_t bytes = 0;
    std::vector<std::string> flags{"-cc"};
    auto ship = [&](int triangles) {
        throwIfStopRequested();
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "%.9f", double(triangles) / double(welded.faceCount()));
        std::vector<std::string> arguments{"-i", input.string(), "-o", output.string(), "-si", ratio};
        arguments.insert(arguments.end(), flags.begin(), flags.end());
        const int status = io::runProgram(*gltfpack, arguments);
        if (status != 0 || !std::filesystem::exists(output))
            throw Error(gltfpack->string() + " -si " + ratio + " failed (exit " + std::to_string(status) + ")");
        bytes = std::filesystem::file_size(output);
        return bytes;
    };
    mostWithinBudget(kFewestTriangles, welded.faceCount(), budget, ship);
    if (bytes > budget) {
        flags.push_back("-sa");
        mostWithinBudget(kFewestTriangles, welded.faceCount(), budget, ship);
    }
    std::filesystem::remove(input);
    mesh::PolygonMesh packed = mesh::triangulated(mesh::loadMesh(output));
    packed.positions = scene.frame.toNormalized(packed.positions);
    Quality q;
    q.bytes = bytes;
    q.files = {{"gltfpack.glb", bytes}};
    q.shipped = settings.dir.filename() / output.filename();
    std::string command = "gltfpack -si R";
    for (const auto& flag : flags) command += " " + flag;
    q.details = {{"triangles", packed.faceCount()}, {"over_budget", bytes > budget}, {"command", command}};
    scoreTriangles(programs, scene, packed, settings, q);
    return q;
}

Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const BakeRoute& route,
                     const BaselineSettings& settings) {
    const mesh::PolygonMesh& cage = route.cage;
    const int mapResolution = route.resolution;
    maps::MapEffects effects = route.effects;
    if (!effects.geometric()) effects.displacement = effects.normalMap = true;
    if (route.appearanceAtlas > 0) effects.normalMap = false;  // an atlas pairs with heights alone
    effects.baseColor = scene.shading != render::ShadingModel::Geometry;
    effects.metallicRoughness = scene.shading == render::ShadingModel::MetallicRoughness;
    surface::SurfaceMaps baked = bakeMaps(cage, scene.reference, {.effects = effects, .resolution = mapResolution});
    baked.shadingNormal = route.shadingNormal;
    if (effects.appearance()) {
        baked.setAppearance(bakeAppearance(
            cage, scene.reference,
            {.effects = effects, .resolution = route.appearanceResolution, .atlas = route.appearanceAtlas}));
    }

    // Shipped exactly as subdfit ships: asset.subd, in world units (the atlases beside it for
    // DCC tools, not counted).
    const auto dir = settings.dir / "bake";
    std::filesystem::create_directories(dir);
    mesh::PolygonMesh cageWorld = cage;
    cageWorld.positions = scene.frame.toWorld(cage.positions);
    surface::SurfaceMaps bakedWorld = baked;
    for (float& d : bakedWorld.displacement) d /= scene.frame.scale;
    Quality q;
    exporter::writeMapAtlases(dir, bakedWorld, {.compact = settings.compactMaps});
    const auto precision = exporter::SubdPrecision::forMapBits(route.bits, route.appearanceQuality);
    q.files = {{"asset.subd", exporter::writeSubd(dir / "asset.subd",
                                                  exporter::shippableAsset(cageWorld, bakedWorld, precision.positionBits),
                                                  precision)
                                  .bytes}};
    q.bytes = totalBytes(q.files);
    q.shipped = settings.dir.filename() / dir.filename() / "asset.subd";
    q.details = {{"faces", cage.faceCount()}, {"map_resolution", mapResolution}, {"map_bits", route.bits},
                 {"shading_normal", nameOf(route.shadingNormal)}};

    // Rendered by the fitter's own renderer with the baked values in its map groups.
    fit::CageFitSettings rendering;
    rendering.mapEffects = effects;
    rendering.shading = scene.shading;
    rendering.maps.resolution = mapResolution;
    rendering.maps.appearanceResolution = route.appearanceResolution;
    rendering.maps.appearanceAtlas = effects.appearance() ? route.appearanceAtlas : 0;
    rendering.maps.shadingNormal = route.shadingNormal;
    rendering.tessLevel = settings.segments;
    fit::CageFitter bakedScene(programs, cage, rendering);
    fit::writeMaps(bakedScene, baked);
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        bakedScene.render(camera, target);
    }, q);
    q.distance = shippedDistance(dir / "asset.subd", settings.segments, scene.frame, scene.reference, settings.surfaceSamples);
    return q;
}

}  // namespace subdfit::simplify
