#include "simplify/baselines.h"

#include <algorithm>

#include "export/glb_writer.h"
#include "export/map_atlas.h"
#include "export/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_scene.h"
#include "mesh/mesh_geometry.h"
#include "render/mesh_renderer.h"
#include "simplify/bake.h"
#include "simplify/decimate.h"
#include "surface/tessellation.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

std::vector<std::uint32_t> indicesOf(const mesh::PolygonMesh& triangles) {
    return {triangles.faceIndices.begin(), triangles.faceIndices.end()};
}

}  // namespace

nlohmann::json shipCage(const std::filesystem::path& path, const mesh::PolygonMesh& cageWorld, bool draco) {
    const auto triangles = mesh::triangulated(cageWorld);
    // glTF has no subdivision surfaces: say how to read the triangles as a cage.
    const nlohmann::json extras = {
        {"subdfit",
         {{"subdivision", "catmull-clark"},
          {"triangleSubdivision", cageWorld.tags.triangles == mesh::TriangleSubdivision::Smooth ? "smooth" : "catmark"},
          {"boundary", cageWorld.tags.boundary == mesh::BoundaryInterpolation::EdgeAndCorner ? "edge-and-corner"
                                                                                              : "edge-only"},
          {"maps", "maps.json beside this file: ptex-face tiles on the limit surface"}}}};
    const auto written = exporter::writeMeshGlb(path, triangles.positions, {}, indicesOf(triangles), draco, extras);
    return {{path.filename().string(), written.bytes}};
}

Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                           const BaselineSettings& settings) {
    const mesh::PolygonMesh welded = weldedTriangles(scene.reference);
    const auto path = settings.dir / "decimated.glb";
    auto ship = [&](int triangles) {
        throwIfStopRequested();
        mesh::PolygonMesh decimated = decimate(welded, triangles);
        const auto normals = mesh::vertexNormals(decimated);  // normalised or not, the same unit normals
        const auto written = exporter::writeMeshGlb(path, scene.frame.toWorld(decimated.positions), normals,
                                                    indicesOf(decimated), /*draco=*/true);
        return std::make_pair(std::move(decimated), written.bytes);
    };
    // Bytes grow with the triangle count: bisect for the most triangles within the budget, but
    // never fewer than a closed shape needs (a .glb's own header and JSON weigh hundreds of bytes,
    // so a tiny budget may not be met at all: the report then says so).
    constexpr int kFewestTriangles = 12;
    int lo = std::min(kFewestTriangles, welded.faceCount()), hi = welded.faceCount();
    while (lo < hi) {
        const int mid = lo + (hi - lo + 1) / 2;
        if (ship(mid).second <= budget) lo = mid;
        else hi = mid - 1;
    }
    auto [decimated, bytes] = ship(lo);

    Quality q;
    q.bytes = bytes;
    q.files = {{"decimated.glb", bytes}};
    q.details = {{"triangles", decimated.faceCount()}, {"over_budget", bytes > budget}};
    const render::MeshRenderer renderer(decimated.positions, mesh::vertexNormals(decimated),
                                        std::vector<unsigned>(decimated.faceIndices.begin(), decimated.faceIndices.end()));
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        renderer.draw(programs, camera, target);
    }, q);
    q.distance = worldDistance(decimated, scene.reference, scene.frame, settings.surfaceSamples);
    return q;
}

Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& cage,
                     maps::MapEffects effects, int mapResolution, const BaselineSettings& settings) {
    if (!effects.any()) effects = {.displacement = true, .normalMap = true};
    const surface::SurfaceMaps baked =
        bakeMaps(cage, scene.reference, {.effects = effects, .resolution = mapResolution});

    // Shipped exactly as subdfit ships: asset.subd, in world units (the atlases beside it for
    // DCC tools, not counted).
    const auto dir = settings.dir / "bake";
    std::filesystem::create_directories(dir);
    mesh::PolygonMesh cageWorld = cage;
    cageWorld.positions = scene.frame.toWorld(cage.positions);
    surface::SurfaceMaps bakedWorld = baked;
    for (float& d : bakedWorld.displacement) d /= scene.frame.scale;
    Quality q;
    shipCage(dir / "cage.glb", cageWorld, settings.draco);
    exporter::writeMapAtlases(dir, bakedWorld, {.compact = settings.compactMaps});
    const exporter::SubdPrecision precision{.displacementBits = settings.mapBits, .normalBits = std::min(settings.mapBits, 10)};
    q.files = {{"asset.subd", exporter::writeSubd(dir / "asset.subd",
                                                  exporter::shippableAsset(cageWorld, bakedWorld, precision.positionBits),
                                                  precision)
                                  .bytes}};
    q.bytes = totalBytes(q.files);
    q.details = {{"faces", cage.faceCount()}, {"map_resolution", mapResolution}, {"map_bits", settings.mapBits}};

    // Rendered by the fitter's own renderer with the baked values in its map groups.
    fit::CageFitSettings rendering;
    rendering.mapEffects = effects;
    rendering.maps.resolution = mapResolution;
    rendering.tessLevel = settings.segments;
    fit::CageFitter bakedScene(programs, cage, rendering);
    if (auto* g = bakedScene.maps()->displacement()) g->write(baked.displacement);
    if (auto* g = bakedScene.maps()->normalMap()) g->write(baked.normal);
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        bakedScene.render(camera, target);
    }, q);
    q.distance = shippedDistance(dir / "asset.subd", settings.segments, scene.frame, scene.reference, settings.surfaceSamples);
    return q;
}

}  // namespace subdfit::simplify
