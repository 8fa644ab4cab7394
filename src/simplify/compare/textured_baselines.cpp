#include "simplify/compare/textured_baselines.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>

#include "export/gltf/textured_glb.h"
#include "fit/fit_scene.h"
#include "io/external_program.h"
#include "io/image_io.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "render/mesh_renderer.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

constexpr int kTextureDivisors[] = {1, 2, 4, 8, 16, 32, 64};

// The reference's textures at 1/1, 1/2, 1/4, ... of their size as shipped (JPEG unless they
// have alpha), each level resized from the one above it: a 2048² texture resized straight to 32²
// filters 64² of its texels for every one it writes, seconds a level.
class ScaledTextures {
public:
    explicit ScaledTextures(const mesh::MaterialSet& set) : set_(set) {
        for (const mesh::Image& image : set.images) {
            bool opaque = true;
            for (size_t p = 3; p < image.rgba.size() && opaque; p += 4) opaque = image.rgba[p] == 255;
            opaque_.push_back(opaque);
        }
    }

    // The images at 1/divisor (a power of two) of their size, and their bytes in all.
    const std::vector<exporter::EncodedImage>& at(int divisor, std::uintmax_t& bytes) {
        auto& level = encoded_[divisor];
        if (level.images.empty()) {
            const std::vector<io::DecodedImage>& images = decoded(divisor);
            for (size_t i = 0; i < images.size(); ++i) {
                if (images[i].rgba.empty()) {
                    level.images.push_back({});
                    continue;
                }
                const auto format = opaque_[i] ? io::ImageFormat::Jpeg : io::ImageFormat::Png;
                level.images.push_back({io::encodeImage(images[i], images[i].width, images[i].height, format),
                                        opaque_[i] ? "image/jpeg" : "image/png"});
                level.bytes += level.images.back().bytes.size();
            }
        }
        bytes = level.bytes;
        return level.images;
    }

private:
    const std::vector<io::DecodedImage>& decoded(int divisor) {
        if (auto it = decoded_.find(divisor); it != decoded_.end()) return it->second;
        std::vector<io::DecodedImage> level;
        if (divisor == 1) {
            for (const mesh::Image& image : set_.images) level.push_back({image.width, image.height, image.rgba});
        } else {
            for (const io::DecodedImage& above : decoded(divisor / 2))
                level.push_back(above.rgba.empty() ? io::DecodedImage{}
                                                   : io::resizedImage(above, std::max(1, above.width / 2),
                                                                      std::max(1, above.height / 2)));
        }
        return decoded_[divisor] = std::move(level);
    }

    struct Encoded {
        std::vector<exporter::EncodedImage> images;
        std::uintmax_t bytes = 0;
    };
    const mesh::MaterialSet& set_;
    std::vector<bool> opaque_;
    std::map<int, std::vector<io::DecodedImage>> decoded_;
    std::map<int, Encoded> encoded_;
};

// The texture scale and vertex coding search both baselines share: `ship(encoding, images,
// triangles)` writes the candidate and returns its bytes. Each texture scale, at the starting
// encoding (the leanest where that fits at none), gets the most triangles that fit and is scored
// on the monitor views; at the best scale the encodings are searched (triangle_encoding.h), and
// the file is left holding the choice.
struct Shipped {
    int divisor = 1, triangles = 0;
    std::uintmax_t bytes = 0, textureBytes = 0;
    EncodedChoice choice;
};
using ShipFunction = std::function<std::uintmax_t(const VertexEncoding& encoding,
                                                  const std::vector<exporter::EncodedImage>& images, int triangles)>;

// The texture scales at one vertex coding, each with the most triangles that fit; the best
// that fits, else the first tried (over budget); none where every scale's images alone are over.
std::optional<Shipped> weighScales(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                                   const std::filesystem::path& output, ScaledTextures& textures,
                                   const VertexEncoding& encoding, const ShipFunction& ship) {
    const int most = scene.reference.faceCount();
    std::optional<Shipped> best;
    double bestPsnr = -1.0;
    for (int divisor : kTextureDivisors) {
        throwIfStopRequested();
        Shipped candidate{.divisor = divisor, .choice = {}};
        const auto& images = textures.at(divisor, candidate.textureBytes);
        if (candidate.textureBytes >= budget) continue;
        candidate.triangles = mostWithinBudget(
            kFewestTriangles, most, budget,
            [&](int triangles) { return candidate.bytes = ship(encoding, images, triangles); },
            best ? std::optional<int>(best->triangles) : std::nullopt);
        if (candidate.bytes > budget && best) continue;
        const double psnr = monitorPsnr(programs, scene, readBack(output, scene));
        const bool better = !best || (candidate.bytes <= budget && psnr > bestPsnr) || best->bytes > budget;
        if (better) {
            best = candidate;
            bestPsnr = psnr;
        }
        // Scores rise and then fall as the textures shrink: past the peak, smaller ones only lose.
        // And halving them frees at most 3/4 of their bytes: once they are a small share of the
        // budget, smaller ones cannot buy the geometry anything.
        if ((!better && candidate.bytes <= budget) || candidate.textureBytes < budget / 16) break;
    }
    return best;
}

Shipped bestScale(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                  const std::filesystem::path& output, ScaledTextures& textures, const VertexEncoding& start,
                  const ShipFunction& ship) {
    const int most = scene.reference.faceCount();
    std::optional<Shipped> best = weighScales(programs, scene, budget, output, textures, start, ship);
    // Where `start` fits at no scale (a tight budget, a decimation held above its fewest
    // triangles by its seams), the scales are weighed at the leanest coding the search reaches.
    const VertexEncoding leanest{.positionBits = kFewestPositionBits, .normals = false};
    if ((!best || best->bytes > budget) && start != leanest) {
        std::optional<Shipped> lean = weighScales(programs, scene, budget, output, textures, leanest, ship);
        if (lean && (!best || lean->bytes < best->bytes)) best = lean;
    }
    if (!best) {  // even the smallest images do not fit: the smallest there is, over budget
        best = Shipped{.divisor = kTextureDivisors[std::size(kTextureDivisors) - 1], .choice = {}};
        best->triangles = kFewestTriangles;
    }
    const auto& images = textures.at(best->divisor, best->textureBytes);
    best->choice = bestEncoding(
        programs, scene, budget, most, output,
        [&](const VertexEncoding& encoding, int triangles) { return ship(encoding, images, triangles); }, start,
        best->triangles);
    best->triangles = best->choice.triangles;
    best->bytes = best->choice.bytes;
    return *best;
}

Quality scored(gl::ProgramCache& programs, const fit::FitScene& scene, const std::filesystem::path& output,
               const Shipped& shipped, std::uintmax_t budget, const BaselineSettings& settings) {
    const mesh::PolygonMesh candidate = readBack(output, scene);
    Quality q;
    q.bytes = shipped.bytes;
    q.files = {{output.filename().string(), shipped.bytes}};
    q.shipped = settings.dir.filename() / output.filename();
    q.details = {{"triangles", candidate.faceCount()},          {"texture_scale", 1.0 / shipped.divisor},
                 {"texture_bytes", shipped.textureBytes},       {"over_budget", shipped.bytes > budget},
                 {"encoding", toJson(shipped.choice.encoding)}, {"monitor_psnr", shipped.choice.monitorPsnr},
                 {"encodings_tried", shipped.choice.tried}};
    const render::MeshRenderer renderer(candidate, scene.shading);
    scoreHoldout(
        scene.holdout,
        [&](const render::Camera& camera, const render::RenderTarget& target) {
            renderer.draw(programs, camera, target);
        },
        q);
    if (settings.distance) q.distance = worldDistance(candidate, scene.reference, scene.frame, settings.surfaceSamples);
    return q;
}

}  // namespace

mesh::PolygonMesh decimateTextured(const mesh::PolygonMesh& triangles, int targetTriangles) {
    SUBDFIT_CHECK(triangles.materials);
    const int total = triangles.faceCount();
    std::vector<unsigned> kept;
    std::vector<int> keptMaterials;
    const float* positions = &triangles.positions[0].x;
    for (size_t m = 0; m < triangles.materials->materials.size(); ++m) {
        std::vector<unsigned> indices;
        for (int f = 0; f < total; ++f)
            if (triangles.faceMaterials[size_t(f)] == int(m))
                for (int k = 0; k < 3; ++k) indices.push_back(unsigned(triangles.faceIndices[size_t(3 * f + k)]));
        if (indices.empty()) continue;
        const size_t share = std::max<size_t>(1, size_t(double(targetTriangles) * double(indices.size() / 3) / total));
        std::vector<unsigned> out(indices.size());
        out.resize(meshopt_simplify(out.data(), indices.data(), indices.size(), positions, triangles.positions.size(),
                                    sizeof(glm::vec3), share * 3, 1.0f));
        if (out.empty()) out = indices;  // never lose a material
        kept.insert(kept.end(), out.begin(), out.end());
        keptMaterials.insert(keptMaterials.end(), out.size() / 3, int(m));
    }
    // The vertices the kept triangles use, with their texture coordinates.
    std::vector<unsigned> remap(triangles.positions.size());
    const size_t used =
        meshopt_optimizeVertexFetchRemap(remap.data(), kept.data(), kept.size(), triangles.positions.size());
    mesh::PolygonMesh out;
    out.sourcePath = triangles.sourcePath;
    out.materials = triangles.materials;
    out.positions.resize(used);
    if (!triangles.uvs.empty()) out.uvs.resize(used);
    if (!triangles.colors.empty()) out.colors.resize(used);
    if (!triangles.normals.empty()) out.normals.resize(used);
    for (size_t v = 0; v < remap.size(); ++v)
        if (remap[v] != ~0u) {
            out.positions[remap[v]] = triangles.positions[v];
            if (!triangles.uvs.empty()) out.uvs[remap[v]] = triangles.uvs[v];
            if (!triangles.colors.empty()) out.colors[remap[v]] = triangles.colors[v];
            if (!triangles.normals.empty()) out.normals[remap[v]] = triangles.normals[v];
        }
    out.faceSizes.assign(kept.size() / 3, 3);
    for (unsigned i : kept) out.faceIndices.push_back(int(remap[i]));
    out.faceMaterials = std::move(keptMaterials);
    return out;
}

namespace {

// One candidate of the textured decimation as it ships: `decimated` in the world frame, its
// normals where the encoding ships them.
std::uintmax_t writeTexturedDecimation(const fit::FitScene& scene, mesh::PolygonMesh decimated,
                                       const std::vector<exporter::EncodedImage>& images,
                                       const VertexEncoding& encoding, const std::filesystem::path& path) {
    const auto normals = encoding.normals ? mesh::shadingNormals(decimated) : std::vector<glm::vec3>{};
    decimated.positions = scene.frame.toWorld(decimated.positions);
    return exporter::writeTexturedGlb(
               path, decimated, normals, images,
               exporter::DracoBits{.position = encoding.positionBits, .normal = encoding.normalBits})
        .bytes;
}

}  // namespace

std::uintmax_t writeWholeTextured(const fit::FitScene& scene, const std::filesystem::path& path) {
    std::uintmax_t textureBytes = 0;
    return writeTexturedDecimation(scene, decimateTextured(scene.reference, scene.reference.faceCount()),
                                   ScaledTextures(*scene.reference.materials).at(1, textureBytes), VertexEncoding{},
                                   path);
}

Quality texturedDecimationBaseline(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                                   const BaselineSettings& settings) {
    const auto output = settings.dir / "decimated.glb";
    Decimations decimations(scene.reference, decimateTextured);
    ScaledTextures textures(*scene.reference.materials);
    const Shipped shipped =
        bestScale(programs, scene, budget, output, textures, {.positionBits = 14, .normals = true},
                  [&](const VertexEncoding& encoding, const auto& images, int triangles) {
                      throwIfStopRequested();
                      return writeTexturedDecimation(scene, decimations.at(triangles), images, encoding, output);
                  });
    return scored(programs, scene, output, shipped, budget, settings);
}

std::optional<Quality> texturedGltfpackBaseline(gl::ProgramCache& programs, const fit::FitScene& scene,
                                                std::uintmax_t budget, const BaselineSettings& settings) {
    const auto gltfpack = io::findProgram("gltfpack");
    if (!gltfpack) return std::nullopt;
    const auto input = settings.dir / "gltfpack_input.glb", output = settings.dir / "gltfpack.glb";
    mesh::PolygonMesh world = scene.reference;
    world.positions = scene.frame.toWorld(world.positions);
    const auto normals = mesh::shadingNormals(scene.reference);
    // The input holds the images at one scale, with normals or not: written again when that changes.
    std::optional<std::vector<std::vector<unsigned char>>> writtenImages;
    bool writtenNormals = false;
    auto imageBytes = [](const std::vector<exporter::EncodedImage>& images) {
        std::vector<std::vector<unsigned char>> bytes;
        for (const auto& image : images) bytes.push_back(image.bytes);
        return bytes;
    };
    std::vector<std::string> flags{"-cc"};
    auto ship = [&](const VertexEncoding& encoding, const std::vector<exporter::EncodedImage>& images, int triangles) {
        if (auto bytes = imageBytes(images); bytes != writtenImages || encoding.normals != writtenNormals) {
            exporter::writeTexturedGlb(input, world, encoding.normals ? normals : std::vector<glm::vec3>{}, images,
                                       /*draco=*/false);
            writtenImages = std::move(bytes);
            writtenNormals = encoding.normals;
        }
        return runGltfpack(*gltfpack, input, output, double(triangles) / double(scene.reference.faceCount()), encoding,
                           flags);
    };
    const VertexEncoding start{.positionBits = 14, .normals = true, .normalBits = kGltfpackNormalBits};
    ScaledTextures textures(*scene.reference.materials);
    Shipped shipped = bestScale(programs, scene, budget, output, textures, start, ship);
    if (shipped.bytes > budget) {  // as the plain baseline: -sa when -si alone cannot get there
        flags.push_back("-sa");
        shipped = bestScale(programs, scene, budget, output, textures, start, ship);
    }
    std::filesystem::remove(input);
    Quality q = scored(programs, scene, output, shipped, budget, settings);
    q.details["command"] = gltfpackCommand(shipped.choice.encoding, flags) + " (textures scaled by subdfit)";
    return q;
}

}  // namespace subdfit::simplify
