#include "simplify/compare/baselines.h"

#include <algorithm>
#include <cstdio>
#include <functional>

#include "export/gltf/glb_writer.h"
#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "io/external_program.h"
#include "io/input_file.h"
#include "mesh/mesh_loader.h"
#include "mesh/mesh_geometry.h"
#include "mesh/position_map.h"
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

namespace {

// The reference's own shading normals (its author's where the file has them, else smooth ones)
// where decimation kept its vertices: meshoptimizer keeps a subset of the vertices where they
// were, so a kept vertex is found by its position. Where the reference splits a vertex (a hard
// edge), its normals there are averaged: the welded copy has one vertex.
class ReferenceNormals {
public:
    explicit ReferenceNormals(const mesh::PolygonMesh& reference) {
        const std::vector<glm::vec3> shading = mesh::shadingNormals(reference);
        index_.reserve(reference.positions.size());
        for (size_t v = 0; v < reference.positions.size(); ++v) {
            const auto [it, fresh] = index_.try_emplace(reference.positions[v], std::uint32_t(normals_.size()));
            if (fresh) normals_.push_back(glm::vec3(0.0f));
            normals_[it->second] += shading[v];
        }
        for (glm::vec3& n : normals_) n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    }
    std::vector<glm::vec3> at(const mesh::PolygonMesh& decimated) const {
        std::vector<glm::vec3> normals = mesh::vertexNormals(decimated);  // where a vertex is not the reference's
        for (size_t v = 0; v < decimated.positions.size(); ++v)
            if (const auto it = index_.find(decimated.positions[v]); it != index_.end())
                normals[v] = normals_[it->second];
        return normals;
    }

private:
    std::vector<glm::vec3> normals_;
    mesh::PositionMap<std::uint32_t> index_;
};

// One candidate of the decimation as it ships: `decimated` in the world frame, the reference's
// normals where the encoding ships them.
std::uintmax_t writeDecimation(const fit::FitScene& scene, const ReferenceNormals& referenceNormals,
                               const mesh::PolygonMesh& decimated, const VertexEncoding& encoding,
                               const std::filesystem::path& path) {
    const auto normals = encoding.normals ? referenceNormals.at(decimated) : std::vector<glm::vec3>{};
    return exporter::writeMeshGlb(path, scene.frame.toWorld(decimated.positions), normals, indicesOf(decimated),
                                  exporter::DracoBits{.position = encoding.positionBits, .normal = encoding.normalBits})
        .bytes;
}

// The reference as it is, its vertices split where it splits them and its own normals where the
// encoding ships normals: what every triangle of a reference whose normals split at some
// positions (hard edges) ships as, since welding would smooth them.
std::uintmax_t writeReferenceAsItIs(const fit::FitScene& scene, const VertexEncoding& encoding,
                                    const std::filesystem::path& path) {
    const auto normals = encoding.normals ? mesh::shadingNormals(scene.reference) : std::vector<glm::vec3>{};
    return exporter::writeMeshGlb(path, scene.frame.toWorld(scene.reference.positions), normals,
                                  indicesOf(scene.reference),
                                  exporter::DracoBits{.position = encoding.positionBits, .normal = encoding.normalBits})
        .bytes;
}

// Where a budget's triangle count is first looked for: about two bytes a triangle.
int firstGuess(std::uintmax_t budget, int most) {
    return int(std::min<std::uintmax_t>(std::uintmax_t(most), budget / 2 + 1));
}

// The probes of a dense reference's baselines (the counts and encodings tried) start from a copy
// decimated once to this many times the first guess (the fewest position bits fit about twice
// it): a search decimates some twenty times, each a pass over the whole reference.
constexpr int kProbeSourceGuesses = 8;

// That copy, where the reference has more than twice its triangles; else none (the probes start
// from the reference itself).
std::optional<mesh::PolygonMesh> probeSourceFor(const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                                const Decimations::Decimate& reduce) {
    const int triangles = kProbeSourceGuesses * firstGuess(budget, welded.faceCount());
    if (welded.faceCount() <= 2 * triangles) return std::nullopt;
    return reduce(welded, triangles);
}

// The file as held-out views and (when asked) the surface distance see it.
void scoreShipped(gl::ProgramCache& programs, const fit::FitScene& scene, const std::filesystem::path& path,
                  const BaselineSettings& settings, Quality& q) {
    const mesh::PolygonMesh shipped = readBack(path, scene);
    const render::MeshRenderer renderer(shipped, scene.shading);
    scoreHoldout(
        scene.holdout,
        [&](const render::Camera& camera, const render::RenderTarget& target) {
            renderer.draw(programs, camera, target);
        },
        q);
    if (settings.distance) q.distance = worldDistance(shipped, scene.reference, scene.frame, settings.surfaceSamples);
    q.details["triangles"] = shipped.faceCount();
}

}  // namespace

Quality decimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& welded,
                           std::uintmax_t budget, const BaselineSettings& settings, const Reduction& reduction) {
    const auto path = settings.dir / reduction.file;
    const ReferenceNormals referenceNormals(scene.reference);
    const bool splitNormals = !mesh::oneNormalPerPosition(scene.reference);
    const auto shipFrom = [&](Decimations& decimations) {
        return [&](const VertexEncoding& encoding, int triangles) {
            throwIfStopRequested();
            if (splitNormals && encoding.normals && triangles >= welded.faceCount())
                return writeReferenceAsItIs(scene, encoding, path);
            return writeDecimation(scene, referenceNormals, decimations.at(triangles), encoding, path);
        };
    };
    const std::optional<mesh::PolygonMesh> probeSource = probeSourceFor(welded, budget, reduction.reduce);
    Decimations fromReference(welded, reduction.reduce),
        fromCopy(probeSource ? *probeSource : welded, reduction.reduce);
    EncodedChoice chosen = bestEncoding(programs, scene, budget, (probeSource ? *probeSource : welded).faceCount(),
                                        path, shipFrom(probeSource ? fromCopy : fromReference),
                                        {.positionBits = 14, .normals = false}, firstGuess(budget, welded.faceCount()));
    if (probeSource) {
        // What ships: the reference itself decimated, at the most triangles that fit, looked for from the probes' choice.
        const auto ship = shipFrom(fromReference);
        chosen.triangles = mostWithinBudget(
            kFewestTriangles, welded.faceCount(), budget,
            [&](int triangles) { return chosen.bytes = ship(chosen.encoding, triangles); }, chosen.triangles);
    }
    Quality q;
    q.bytes = chosen.bytes;
    q.files = {{reduction.file, chosen.bytes}};
    q.shipped = settings.dir.filename() / path.filename();
    q.details = {{"over_budget", chosen.bytes > budget},
                 {"encoding", toJson(chosen.encoding)},
                 {"monitor_psnr", chosen.monitorPsnr},
                 {"encodings_tried", chosen.tried}};
    if (probeSource) q.details["probes_decimated_from"] = probeSource->faceCount();
    scoreShipped(programs, scene, path, settings, q);
    return q;
}

std::uintmax_t writeWholeDecimation(const fit::FitScene& scene, const mesh::PolygonMesh& welded, bool normals,
                                    const std::filesystem::path& path) {
    const VertexEncoding encoding{.positionBits = 14, .normals = normals};
    if (normals && !mesh::oneNormalPerPosition(scene.reference)) return writeReferenceAsItIs(scene, encoding, path);
    return writeDecimation(scene, ReferenceNormals(scene.reference), decimate(welded, welded.faceCount()), encoding,
                           path);
}

std::uintmax_t runGltfpack(const std::filesystem::path& gltfpack, const std::filesystem::path& input,
                           const std::filesystem::path& output, double ratio, const VertexEncoding& encoding,
                           const std::vector<std::string>& extra) {
    throwIfStopRequested();
    char text[32];
    std::snprintf(text, sizeof text, "%.9f", ratio);
    std::vector<std::string> arguments{"-i",  input.string(), "-o",  output.string(),
                                       "-si", text,           "-vp", std::to_string(encoding.positionBits)};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const int status = io::runProgram(gltfpack, arguments);
    if (status != 0 || !std::filesystem::exists(output))
        throw Error(gltfpack.string() + " -si " + text + " failed (exit " + std::to_string(status) + ")");
    return std::filesystem::file_size(output);
}

std::string gltfpackCommand(const VertexEncoding& encoding, const std::vector<std::string>& flags) {
    std::string command = "gltfpack -si R -vp " + std::to_string(encoding.positionBits);
    for (const auto& flag : flags) command += " " + flag;
    return command + (encoding.normals ? " (input with normals)" : " (input without normals)");
}

std::optional<Quality> gltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                        const mesh::PolygonMesh& welded, std::uintmax_t budget,
                                        const BaselineSettings& settings) {
    const auto gltfpack = io::findProgram("gltfpack");
    if (!gltfpack) return std::nullopt;
    // gltfpack gets what the decimation gets: the welded reference, with the reference's own
    // normals or none.
    struct Input {
        std::filesystem::path withNormals, without;
        int triangles;
    };
    std::vector<std::filesystem::path> written;
    const auto writeInput = [&](const mesh::PolygonMesh& m, const std::vector<glm::vec3>& normals,
                                const std::string& name) {
        const Input input{settings.dir / (name + ".glb"), settings.dir / (name + "_bare.glb"), m.faceCount()};
        exporter::writeMeshGlb(input.withNormals, scene.frame.toWorld(m.positions), normals, indicesOf(m),
                               /*draco=*/false);
        exporter::writeMeshGlb(input.without, scene.frame.toWorld(m.positions), {}, indicesOf(m), /*draco=*/false);
        written.insert(written.end(), {input.withNormals, input.without});
        return input;
    };
    const ReferenceNormals referenceNormals(scene.reference);
    const Input whole = writeInput(welded, referenceNormals.at(welded), "gltfpack_input");
    // As the decimation's: a dense reference's probes start from a copy decimated once (with the
    // reference's own normals where it kept its vertices); what ships starts from the reference.
    std::optional<Input> copy;
    if (const auto probeSource = probeSourceFor(welded, budget, decimate))
        copy = writeInput(*probeSource, referenceNormals.at(*probeSource), "gltfpack_probe_input");
    const Input& probes = copy ? *copy : whole;
    const auto output = settings.dir / "gltfpack.glb";
    // gltfpack's simplifier stops where its error bound says the shape would suffer; a user
    // held to a budget it cannot reach that way adds -sa (aggressive), and so does this.
    std::vector<std::string> flags{"-cc"};
    const auto shipFrom = [&](const Input& input) {
        return [&](const VertexEncoding& encoding, int triangles) {
            return runGltfpack(*gltfpack, encoding.normals ? input.withNormals : input.without, output,
                               double(triangles) / double(input.triangles), encoding, flags);
        };
    };
    const auto search = [&] {
        EncodedChoice c = bestEncoding(programs, scene, budget, probes.triangles, output, shipFrom(probes),
                                       {.positionBits = 14, .normals = true, .normalBits = kGltfpackNormalBits},
                                       firstGuess(budget, welded.faceCount()));
        if (copy) {
            const auto ship = shipFrom(whole);
            c.triangles = mostWithinBudget(
                kFewestTriangles, whole.triangles, budget,
                [&](int triangles) { return c.bytes = ship(c.encoding, triangles); }, c.triangles);
        }
        return c;
    };
    EncodedChoice chosen = search();
    if (chosen.bytes > budget) {
        flags.push_back("-sa");
        chosen = search();
    }
    for (const auto& path : written) std::filesystem::remove(path);
    Quality q;
    q.bytes = chosen.bytes;
    q.files = {{"gltfpack.glb", chosen.bytes}};
    q.shipped = settings.dir.filename() / output.filename();
    q.details = {{"over_budget", chosen.bytes > budget},
                 {"command", gltfpackCommand(chosen.encoding, flags)},
                 {"encoding", toJson(chosen.encoding)},
                 {"monitor_psnr", chosen.monitorPsnr},
                 {"encodings_tried", chosen.tried}};
    if (copy) q.details["probes_decimated_from"] = copy->triangles;
    scoreShipped(programs, scene, output, settings, q);
    return q;
}

Quality bakeBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, const BakeRoute& route,
                     const BaselineSettings& settings, const std::optional<ScoredFile>& scored) {
    const mesh::PolygonMesh& cage = route.cage;
    const int mapResolution = route.resolution;
    maps::MapEffects effects = route.effects & maps::MapEffects::on(kinds::MapLattice::Geometric);
    if (!effects.geometric()) effects = {maps::MapKind::Displacement, maps::MapKind::NormalMap};
    if (route.appearanceAtlas > 0) effects.set(maps::MapKind::NormalMap, false);  // an atlas pairs with heights alone
    effects = effects | maps::appearanceFor(scene.shading);
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
    const auto precision = codec::SubdPrecision::forMapBits(route.bits, route.appearanceQuality, route.positionBits);
    q.files = {{"asset.subd", codec::writeSubd(dir / "asset.subd",
                                               codec::shippableAsset(cageWorld, bakedWorld, precision.positionBits,
                                                                     std::uint32_t(scene.reference.faceCount())),
                                               precision)
                                  .bytes}};
    q.bytes = totalBytes(q.files);
    q.shipped = settings.dir.filename() / dir.filename() / "asset.subd";
    q.details = {{"faces", cage.faceCount()},
                 {"map_resolution", mapResolution},
                 {"map_bits", route.bits},
                 {"position_bits", route.positionBits},
                 {"shading_normal", nameOf(route.shadingNormal)}};

    if (scored && scored->segments == settings.segments && (scored->quality.distance || !settings.distance) &&
        io::readInputFile(scored->path) == io::readInputFile(dir / "asset.subd")) {
        const Quality& same = scored->quality;
        q.psnrHoldout = same.psnrHoldout;
        q.ssimHoldout = same.ssimHoldout;
        q.psnrViews = same.psnrViews;
        q.view = same.view;
        if (settings.distance) q.distance = same.distance;
        return q;
    }
    // Drawn as it ships: the file decoded (positions and maps at their bits), by the fitter's
    // own renderer.
    const auto shipped = drawnAsFitted(programs, scene, codec::readSubd(dir / "asset.subd"), settings.segments);
    scoreHoldout(
        scene.holdout,
        [&](const render::Camera& camera, const render::RenderTarget& target) { shipped->render(camera, target); }, q);
    if (settings.distance)
        q.distance = shippedDistance(dir / "asset.subd", settings.segments, scene.frame, scene.reference,
                                     settings.surfaceSamples);
    return q;
}

}  // namespace subdfit::simplify
