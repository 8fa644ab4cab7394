#include "simplify/compare/triangle_encoding.h"

#include <algorithm>
#include <cmath>

#include "fit/fit_scene.h"
#include "mesh/mesh_loader.h"
#include "render/mesh_renderer.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

constexpr int kPositionBitsLadder[] = {14, 12, 11, 10, 9, kFewestPositionBits};
// Fewer bits buy triangles; a dip smaller than this (dB, on the monitor views) is within their
// noise and does not end the ladder (docs/measurements.md).
constexpr double kLadderNoise = 0.1;

}  // namespace

int mostWithinBudget(int fewest, int most, std::uintmax_t budget, const std::function<std::uintmax_t(int)>& ship,
                     std::optional<int> hint) {
    fewest = std::min(fewest, most);
    int lo = fewest, over = most + 1;  // lo fits (once probed); every count from `over` on does not
    std::optional<double> loBytes, overBytes;
    int shipped = -1, width = over - lo, stalled = 0;
    int next = hint ? std::clamp(*hint, fewest, most) : most;
    for (;;) {
        const std::uintmax_t bytes = ship(next);
        shipped = next;
        if (bytes <= budget) {
            lo = next;
            loBytes = double(bytes);
        } else {
            if (next <= fewest) return fewest;  // even the fewest are over: left as shipped
            over = next;
            overBytes = double(bytes);
        }
        if (over - 1 - lo <= std::max(0, lo / 200)) break;
        stalled = 2 * (over - lo) > width ? stalled + 1 : 0;
        width = over - lo;
        double aim = 0.0;
        if (stalled >= 2) aim = lo + 0.5 * (over - lo);
        else if (loBytes && overBytes) aim = lo + (double(budget) - *loBytes) / (*overBytes - *loBytes) * (over - lo);
        else if (overBytes) aim = over * double(budget) / *overBytes;
        else aim = lo * double(budget) / *loBytes;
        next = std::clamp(int(std::floor(aim)), lo + 1, over - 1);
    }
    if (shipped != lo) ship(lo);
    return lo;
}

const mesh::PolygonMesh& Decimations::at(int triangles) {
    if (const auto it = made_.find(triangles); it != made_.end()) return it->second;
    if (made_.size() >= kKept) made_.clear();
    return made_.emplace(triangles, decimate_(source_, triangles)).first->second;
}

nlohmann::json toJson(const VertexEncoding& e) {
    nlohmann::json j{{"position_bits", e.positionBits}, {"normals", e.normals}};
    if (e.normals) j["normal_bits"] = e.normalBits;
    return j;
}

mesh::PolygonMesh readBack(const std::filesystem::path& path, const fit::FitScene& scene) {
    // A file without normals comes back flat, as viewers draw it (the reader's rule for glTF).
    mesh::PolygonMesh m = mesh::triangulated(mesh::loadReference(path));
    m.positions = scene.frame.toNormalized(m.positions);
    return m;
}

double monitorPsnr(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& candidate) {
    const render::MeshRenderer renderer(candidate, scene.shading);
    return fit::score(scene.choosing(programs),
                      [&](const render::Camera& camera, const render::RenderTarget& target) {
                          renderer.draw(programs, camera, target);
                      })
        .psnr;
}

EncodedChoice bestEncoding(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget, int most,
                           const std::filesystem::path& path, const ShipEncoded& ship, VertexEncoding start,
                           std::optional<int> hint) {
    EncodedChoice best;
    bool any = false;
    VertexEncoding last;
    // Scores `encoding` at the most triangles that fit, and keeps it when it beats the best so
    // far (within the budget first); returns its monitor PSNR.
    auto attempt = [&](const VertexEncoding& encoding) {
        throwIfStopRequested();
        std::uintmax_t bytes = 0;
        const int triangles = mostWithinBudget(
            kFewestTriangles, most, budget, [&](int n) { return bytes = ship(encoding, n); }, hint);
        last = encoding;
        const double psnr = monitorPsnr(programs, scene, readBack(path, scene));
        nlohmann::json tried = toJson(encoding);
        tried.update({{"triangles", triangles}, {"bytes", bytes}, {"monitor_psnr", psnr}});
        best.tried.push_back(tried);
        const bool within = bytes <= budget, bestWithin = best.bytes <= budget;
        const bool better = !any || (within && !bestWithin) || (within == bestWithin && psnr > best.monitorPsnr);
        if (better) {
            best.encoding = encoding;
            best.triangles = triangles;
            best.bytes = bytes;
            best.monitorPsnr = psnr;
            hint = triangles;
        }
        any = true;
        return psnr;
    };
    attempt(start);
    VertexEncoding flipped = start;
    flipped.normals = !flipped.normals;
    attempt(flipped);
    for (int bits : kPositionBitsLadder) {
        if (bits >= start.positionBits || bits < kFewestPositionBits) continue;
        VertexEncoding fewer = best.encoding;
        fewer.positionBits = bits;
        const double bestSoFar = best.monitorPsnr;
        if (attempt(fewer) < bestSoFar - kLadderNoise) break;
    }
    if (!(last == best.encoding)) best.bytes = ship(best.encoding, best.triangles);
    return best;
}

}  // namespace subdfit::simplify
