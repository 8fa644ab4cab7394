#include "simplify/bake/bake.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/parallel_invoke.h>

#include "geometry/normal_casting.h"
#include "geometry/surface_queries.h"
#include "mesh/material_sampling.h"
#include "simplify/bake/atlas_bake.h"
#include "mesh/mesh_geometry.h"
#include "subdiv/limit_evaluator.h"
#include "util/interrupt.h"
#include "util/parallel_for.h"
#include "util/sparse_least_squares.h"

namespace subdfit::simplify {
namespace {

// Where a node is baked: the first tile that holds it.
struct NodeSite {
    int face = -1, i = 0, j = 0;
};

std::vector<NodeSite> nodeSites(const surface::TexelLayout& layout) {
    std::vector<NodeSite> sites(size_t(layout.nodeCount));
    for (int f = 0; f < layout.ptexFaceCount; ++f)
        for (int j = 0; j <= layout.resolution; ++j)
            for (int i = 0; i <= layout.resolution; ++i) {
                NodeSite& site = sites[size_t(layout.node(f, i, j))];
                if (site.face < 0) site = {f, i, j};
            }
    return sites;
}

// The limit sample at a node; where the derivatives vanish (some extraordinary corners), a
// hair inside the face, as the renderer does.
subdiv::LimitSample sampleAt(const subdiv::LimitEvaluator& limit, const NodeSite& s, int resolution,
                             std::span<const glm::dvec3> points) {
    glm::vec2 uv = glm::vec2(float(s.i), float(s.j)) / float(resolution);
    subdiv::LimitSample sample = limit.evaluate(s.face, uv.x, uv.y, points);
    if (glm::length(glm::cross(sample.dPdu, sample.dPdv)) < 1e-12f) {
        uv = glm::mix(uv, glm::vec2(0.5f), 1e-3f);
        const subdiv::LimitSample inside = limit.evaluate(s.face, uv.x, uv.y, points);
        sample.dPdu = inside.dPdu, sample.dPdv = inside.dPdv;
    }
    return sample;
}

glm::vec3 unitNormal(const glm::vec3& dPdu, const glm::vec3& dPdv, const glm::vec3& fallback) {
    const glm::vec3 n = glm::cross(dPdu, dPdv);
    const float length = glm::length(n);
    return length > 1e-20f ? n / length : fallback;
}

// ∂d/∂u at a node: central differences, across the tile's border too (as the renderer's slope).
glm::vec2 heightGradient(const surface::TexelLayout& layout, const std::vector<float>& d, const NodeSite& s) {
    auto at = [&](int i, int j) { return surface::nodeValueAcross(layout, d, s.face, i, j); };
    const float halfResolution = 0.5f * float(layout.resolution);
    return {(at(s.i + 1, s.j) - at(s.i - 1, s.j)) * halfResolution,
            (at(s.i, s.j + 1) - at(s.i, s.j - 1)) * halfResolution};
}

// How far beyond the nearest point of the reference a node's hit may lie, as a fraction of the
// reach (a cage edge): farther, the ray has passed its own part of the reference for another.
constexpr float kDetour = 0.25f;

// Every node of `layout` on `cage`'s limit surface, cast along its limit normal to the
// reference (geometry/normal_casting.h).
struct NodeHits {
    std::vector<NodeSite> sites;
    std::vector<subdiv::LimitSample> samples;
    std::vector<glm::vec3> normals;
    std::vector<std::optional<geometry::RayHit>> hits;
    float facing = 1.0f;  // which way the reference faces the limit normals (+1: along them)
};

NodeHits castNodes(const mesh::PolygonMesh& cage, const surface::TexelLayout& layout,
                   const geometry::SurfaceQueries& surface, float maxDistance) {
    NodeHits h;
    h.sites = nodeSites(layout);
    const size_t nodes = h.sites.size();
    const subdiv::LimitEvaluator limit(cage);
    const std::vector<glm::dvec3> points = limit.patchPoints(cage.positions);
    h.samples.resize(nodes);
    h.normals.resize(nodes);
    std::vector<glm::vec3> origins(nodes);
    for (size_t n = 0; n < nodes; ++n) {
        if (n % 4096 == 0) throwIfStopRequested();
        if (h.sites[n].face < 0 || !limit.hasSurface(h.sites[n].face, 0.5f, 0.5f)) continue;
        h.samples[n] = sampleAt(limit, h.sites[n], layout.resolution, points);
        h.normals[n] = unitNormal(h.samples[n].dPdu, h.samples[n].dPdv, glm::vec3(0.0f, 0.0f, 1.0f));
        origins[n] = h.samples[n].position;
    }
    geometry::NormalCasts casts =
        geometry::castAlongNormals(surface, origins, h.normals, maxDistance, kDetour * maxDistance);
    h.hits = std::move(casts.hits);
    h.facing = casts.facing;
    return h;
}

// A point of a ptex face, (u, v) in [0, 1]².
struct PtexPoint {
    int face;
    glm::vec2 uv;
};

// Casts from `points` of the cage's limit surface along its normal there to the reference, facing
// as the nodes found it (the cells between the nodes are sampled as the nodes are).
std::vector<std::optional<geometry::RayHit>> castFromLimit(const mesh::PolygonMesh& cage,
                                                           const subdiv::LimitEvaluator& limit,
                                                           const std::vector<PtexPoint>& points,
                                                           const geometry::SurfaceQueries& surface, float maxDistance,
                                                           float facing) {
    std::vector<glm::vec3> origins(points.size()), normals(points.size());
    const std::vector<glm::dvec3> patchPoints = limit.patchPoints(cage.positions);
    parallelFor(0, int(points.size()), [&](int k) {
        const PtexPoint& p = points[size_t(k)];
        const subdiv::LimitSample at = limit.evaluate(p.face, p.uv.x, p.uv.y, patchPoints);
        origins[size_t(k)] = at.position;
        normals[size_t(k)] = unitNormal(at.dPdu, at.dPdv, glm::vec3(0.0f));
    });
    return geometry::castAlongNormals(surface, origins, normals, maxDistance, kDetour * maxDistance, facing).hits;
}

float maxDistanceFor(const BakeOptions& options, const mesh::PolygonMesh& cage) {
    return options.maxDistance > 0.0f ? options.maxDistance : mesh::meanEdgeLength(cage);
}

// Nodes no ray found the reference from take the mean of their found neighbours, spreading
// outwards until every node has a value (a node graph without any found node keeps its own).
void fillMissing(const surface::TexelLayout& layout, std::vector<float>& values, int channels,
                 std::vector<char> found) {
    const auto graph = surface::nodeAdjacency(layout);
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<char> next = found;
        for (size_t n = 0; n < found.size(); ++n) {
            if (found[n]) continue;
            int count = 0;
            std::vector<float> sum(size_t(channels), 0.0f);
            for (int k = graph.offsets[n]; k < graph.offsets[n + 1]; ++k) {
                const size_t m = size_t(graph.neighbors[size_t(k)]);
                if (!found[m]) continue;
                for (int c = 0; c < channels; ++c) sum[size_t(c)] += values[m * size_t(channels) + size_t(c)];
                ++count;
            }
            if (count == 0) continue;
            for (int c = 0; c < channels; ++c) values[n * size_t(channels) + size_t(c)] = sum[size_t(c)] / float(count);
            next[n] = 1;
            changed = true;
        }
        found = std::move(next);
    }
}

// Heights that make the bilinear map (what the renderer and the decoder interpolate between
// nodes) lie on the reference across each cell, not just at its nodes: point samples at the
// nodes alias detail finer than a cell into the whole cell. Rows: every node's own hit and every
// cell centre's hit (a quarter on each corner), solved in the least-squares sense; nodes no ray
// reached stay at 0, and so do the cells around them.
std::vector<float> leastSquaresHeights(const mesh::PolygonMesh& cage, const surface::TexelLayout& layout,
                                       const NodeHits& nodeHits, const geometry::SurfaceQueries& surface,
                                       float maxDistance) {
    const subdiv::LimitEvaluator limit(cage);
    const int t = layout.resolution;
    SparseRows rows;
    std::vector<double> targets, weights;
    std::vector<double> start(size_t(layout.nodeCount), 0.0);
    for (size_t n = 0; n < nodeHits.hits.size(); ++n) {
        if (!nodeHits.hits[n]) continue;
        start[n] = nodeHits.hits[n]->distance;
        rows.add(int(n), 1.0);
        rows.endRow();
        targets.push_back(start[n]);
    }
    // Cell centres whose four corners all found the reference: a corner no ray reached says
    // nothing safe, and the cell's row would set it to four times the centre's height less
    // the other three.
    std::vector<std::array<int, 4>> cells;
    std::vector<PtexPoint> centres;
    for (int f = 0; f < layout.ptexFaceCount; ++f) {
        if (f % 256 == 0) throwIfStopRequested();
        for (int j = 0; j < t; ++j)
            for (int i = 0; i < t; ++i) {
                const std::array<int, 4> corners{layout.node(f, i, j), layout.node(f, i + 1, j),
                                                 layout.node(f, i, j + 1), layout.node(f, i + 1, j + 1)};
                const glm::vec2 centre = (glm::vec2(float(i), float(j)) + 0.5f) / float(t);
                if (std::any_of(corners.begin(), corners.end(), [&](int c) { return !nodeHits.hits[size_t(c)]; }) ||
                    !limit.hasSurface(f, centre.x, centre.y))
                    continue;
                cells.push_back(corners);
                centres.push_back({f, centre});
            }
    }
    const auto hits = castFromLimit(cage, limit, centres, surface, maxDistance, nodeHits.facing);
    for (size_t c = 0; c < cells.size(); ++c) {
        if (!hits[c]) continue;
        for (int node : cells[c]) rows.add(node, 0.25);
        rows.endRow();
        targets.push_back(hits[c]->distance);
    }
    weights.assign(targets.size(), 1.0);
    constexpr double kDamping = 1e-3;  // holds nodes only cells see near their point samples
    const std::vector<double> solved = solveDampedLeastSquares(rows, targets, weights, start, kDamping);
    return {solved.begin(), solved.end()};
}

}  // namespace

surface::SurfaceMaps bakeMaps(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                              const BakeOptions& options) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, options.resolution);
    const geometry::SurfaceQueries surface(reference);
    const auto referenceNormals = mesh::shadingNormals(reference);
    const NodeHits nodeHits = castNodes(cage, maps.layout, surface, maxDistanceFor(options, cage));
    const auto& sites = nodeHits.sites;
    const auto& samples = nodeHits.samples;
    const auto& normals = nodeHits.normals;
    const auto& hits = nodeHits.hits;
    const size_t nodes = sites.size();
    std::vector<float> heights(nodes, 0.0f);
    for (size_t n = 0; n < nodes; ++n)
        if (hits[n]) heights[n] = hits[n]->distance;
    if (options.leastSquaresHeights)
        heights = leastSquaresHeights(cage, maps.layout, nodeHits, surface, maxDistanceFor(options, cage));
    if (options.effects.has(maps::MapKind::Displacement)) maps.displacement = heights;
    if (!options.effects.has(maps::MapKind::NormalMap)) return maps;

    // The renderer shades the displaced surface (when there is one) and tilts its normal by the
    // map: express the reference normal in that surface's frame (T, B, N'), n ∝ x T + y B + N'.
    const std::vector<float> zero(nodes, 0.0f);
    const std::vector<float>& d = options.effects.has(maps::MapKind::Displacement) ? heights : zero;
    maps.normal.assign(2 * nodes, 0.0f);
    for (size_t n = 0; n < nodes; ++n) {
        if (!hits[n]) continue;
        const glm::vec2 g = heightGradient(maps.layout, d, sites[n]);
        const glm::vec3 du = samples[n].dPdu + g.x * normals[n], dv = samples[n].dPdv + g.y * normals[n];
        const glm::vec3 N = unitNormal(du, dv, normals[n]);
        glm::vec3 T = du - N * glm::dot(N, du);
        if (glm::dot(T, T) < 1e-20f) continue;
        T = glm::normalize(T);
        glm::vec3 B = glm::cross(N, T);
        if (glm::dot(B, dv) < 0.0f) B = -B;

        const int tri = hits[n]->triangle;
        const float u = hits[n]->u, v = hits[n]->v;
        auto vertexNormal = [&](int k) { return referenceNormals[size_t(reference.faceIndices[size_t(3 * tri + k)])]; };
        glm::vec3 r = (1.0f - u - v) * vertexNormal(0) + u * vertexNormal(1) + v * vertexNormal(2);
        if (glm::dot(r, N) < 0.0f) r = -r;               // the reference may wind the other way
        const float z = std::max(glm::dot(r, N), 0.2f);  // a map cannot tilt past ~78°
        maps.normal[2 * n] = glm::dot(r, T) / z;
        maps.normal[2 * n + 1] = glm::dot(r, B) / z;
    }
    return maps;
}

}  // namespace subdfit::simplify

namespace subdfit::simplify {

namespace {

// The appearance a ray that found the reference reads there: sRGB base colour, roughness, metallic.
std::array<float, 5> appearanceOf(const mesh::MaterialSample& s) {
    return {mesh::linearToSrgb(s.baseColor.r), mesh::linearToSrgb(s.baseColor.g), mesh::linearToSrgb(s.baseColor.b),
            std::clamp(s.roughness, 0.0f, 1.0f), std::clamp(s.metallic, 0.0f, 1.0f)};
}

mesh::MaterialSample materialAt(const mesh::PolygonMesh& reference, const geometry::RayHit& hit) {
    return mesh::sampleMaterial(reference, hit.triangle, hit.u, hit.v);
}

std::array<float, 5> appearanceAt(const mesh::PolygonMesh& reference, const geometry::RayHit& hit) {
    return appearanceOf(materialAt(reference, hit));
}

// Where in each cell the appearance is sampled besides its corners.
constexpr glm::vec2 kCellSamples[] = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0.75f, 0.75f}};

// Node values whose bilinear interpolation (what the renderer draws between nodes) matches the
// material across each cell, not only at the nodes: the nodes' own samples and 2 × 2 more in
// every cell, least squares, as the heights are fitted. A node's point sample alone aliases a
// texture finer than the lattice (a coarse cage's tiles span many of a dense reference's texels).
// `color` and `roughnessMetallic` come in as the point samples (where a node's ray found the
// reference; elsewhere filled in) and go out fitted.
void fitAppearanceAcrossCells(const mesh::PolygonMesh& cage, const surface::TexelLayout& layout,
                              const NodeHits& nodeHits, const mesh::PolygonMesh& reference,
                              const geometry::SurfaceQueries& surface, float maxDistance,
                              std::vector<glm::dvec3>& color, std::vector<glm::dvec2>& roughnessMetallic) {
    const subdiv::LimitEvaluator limit(cage);
    const int t = layout.resolution;
    SparseRows rows;
    std::vector<glm::dvec3> colorTargets;
    std::vector<glm::dvec2> rmTargets;
    auto addRow = [&](const std::array<float, 5>& a) {
        rows.endRow();
        colorTargets.emplace_back(a[0], a[1], a[2]);
        rmTargets.emplace_back(a[3], a[4]);
    };
    for (size_t n = 0; n < nodeHits.hits.size(); ++n)
        if (nodeHits.hits[n]) {  // its own sample, already read
            rows.add(int(n), 1.0);
            rows.endRow();
            colorTargets.push_back(color[n]);
            rmTargets.push_back(roughnessMetallic[n]);
        }
    std::vector<PtexPoint> samples;  // 2 × 2 a cell, in order: face, row, cell, sample
    for (int face = 0; face < layout.ptexFaceCount; ++face) {
        if (face % 256 == 0) throwIfStopRequested();
        if (!limit.hasSurface(face, 0.5f, 0.5f)) continue;
        for (int j = 0; j < t; ++j)
            for (int i = 0; i < t; ++i)
                for (const glm::vec2 f : kCellSamples)
                    samples.push_back({face, (glm::vec2(float(i), float(j)) + f) / float(t)});
    }
    const auto hits = castFromLimit(cage, limit, samples, surface, maxDistance, nodeHits.facing);
    std::vector<std::array<float, 5>> found(samples.size());
    parallelFor(0, int(samples.size()), [&](int k) {
        if (hits[size_t(k)]) found[size_t(k)] = appearanceAt(reference, *hits[size_t(k)]);
    });
    for (size_t k = 0; k < samples.size(); ++k) {
        if (!hits[k]) continue;
        // Which cell and where in it, back from (u, v): a sample sits a quarter cell inside its
        // cell, far beyond what rounding could move it.
        const glm::vec2 x = samples[k].uv * float(t);
        const int i = std::min(int(x.x), t - 1), j = std::min(int(x.y), t - 1), face = samples[k].face;
        const glm::vec2 f = x - glm::vec2(float(i), float(j));
        rows.add(layout.node(face, i, j), double((1.0f - f.x) * (1.0f - f.y)));
        rows.add(layout.node(face, i + 1, j), double(f.x * (1.0f - f.y)));
        rows.add(layout.node(face, i, j + 1), double((1.0f - f.x) * f.y));
        rows.add(layout.node(face, i + 1, j + 1), double(f.x * f.y));
        addRow(found[k]);
    }
    const std::vector<double> weights(rows.rows(), 1.0);
    constexpr double kDamping = 1e-3;  // as the heights: holds nodes few samples see
    tbb::parallel_invoke(
        [&] { color = solveDampedLeastSquares(rows, colorTargets, weights, color, kDamping); },
        [&] { roughnessMetallic = solveDampedLeastSquares(rows, rmTargets, weights, roughnessMetallic, kDamping); });
}

}  // namespace

surface::SurfaceMaps bakeAppearance(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                    const AppearanceBakeOptions& options) {
    if (options.atlas > 0)
        return bakeAtlasAppearance(cage, reference, options.effects, options.atlas, options.maxDistance,
                                   options.shadingNormals);
    surface::SurfaceMaps maps;
    maps.appearanceLayout = surface::buildTexelLayout(cage, options.resolution);
    const geometry::SurfaceQueries surface(reference);
    const float maxDistance = options.maxDistance > 0.0f ? options.maxDistance : mesh::meanEdgeLength(cage);
    const NodeHits nodeHits = castNodes(cage, maps.appearanceLayout, surface, maxDistance);
    const size_t nodes = nodeHits.sites.size();
    std::vector<char> found(nodes, 0);
    std::vector<float> color(3 * nodes, 0.5f), roughnessMetallic(2 * nodes, 0.0f);
    // The reference's emission and occlusion ride along unfitted, point-sampled at the nodes
    // (occlusion only beside a metallic-roughness map: the shipped file packs it in its red).
    const CarriedLook carried = carriedLookOf(reference);
    const bool emission = carried.emission && options.effects.appearance();
    const bool occlusion = carried.occlusion && options.effects.has(maps::MapKind::MetallicRoughness);
    std::vector<float> emissive(emission ? 3 * nodes : 0, 0.0f), occlusions(occlusion ? nodes : 0, 1.0f);
    for (size_t n = 0; n < nodes; ++n) {
        if (!nodeHits.hits[n]) continue;
        const mesh::MaterialSample sample = materialAt(reference, *nodeHits.hits[n]);
        const std::array<float, 5> a = appearanceOf(sample);
        std::copy(a.begin(), a.begin() + 3, color.begin() + 3 * std::ptrdiff_t(n));
        std::copy(a.begin() + 3, a.end(), roughnessMetallic.begin() + 2 * std::ptrdiff_t(n));
        for (int k = 0; emission && k < 3; ++k)
            emissive[3 * n + size_t(k)] = std::clamp(mesh::linearToSrgb(sample.emissive[k]), 0.0f, 1.0f);
        if (occlusion) occlusions[n] = std::clamp(sample.occlusion, 0.0f, 1.0f);
        found[n] = 1;
    }
    fillMissing(maps.appearanceLayout, color, 3, found);
    fillMissing(maps.appearanceLayout, roughnessMetallic, 2, found);
    if (emission) fillMissing(maps.appearanceLayout, emissive, 3, found);
    if (occlusion) fillMissing(maps.appearanceLayout, occlusions, 1, found);
    maps.emissive = std::move(emissive);
    maps.occlusion = std::move(occlusions);
    if (options.acrossCells) {
        std::vector<glm::dvec3> c(nodes);
        std::vector<glm::dvec2> rm(nodes);
        for (size_t n = 0; n < nodes; ++n) {
            c[n] = {color[3 * n], color[3 * n + 1], color[3 * n + 2]};
            rm[n] = {roughnessMetallic[2 * n], roughnessMetallic[2 * n + 1]};
        }
        fitAppearanceAcrossCells(cage, maps.appearanceLayout, nodeHits, reference, surface, maxDistance, c, rm);
        for (size_t n = 0; n < nodes; ++n) {
            for (int k = 0; k < 3; ++k) color[3 * n + size_t(k)] = float(std::clamp(c[n][k], 0.0, 1.0));
            for (int k = 0; k < 2; ++k) roughnessMetallic[2 * n + size_t(k)] = float(std::clamp(rm[n][k], 0.0, 1.0));
        }
    }
    if (options.effects.has(maps::MapKind::BaseColor)) maps.baseColor = std::move(color);
    if (options.effects.has(maps::MapKind::MetallicRoughness)) maps.metallicRoughness = std::move(roughnessMetallic);
    return maps;
}

AppearanceBakeOptions appearanceBakeOf(const maps::MapParameters& parameters) {
    return {.effects = parameters.effects(),
            .resolution = parameters.appearanceLayout().resolution,
            .atlas = parameters.appearanceAtlas().size};
}

surface::SurfaceMaps bakeFor(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                             const maps::MapParameters& parameters) {
    const maps::MapEffects effects = parameters.effects();
    surface::SurfaceMaps maps;
    if (effects.geometric())
        maps = bakeMaps(cage, reference, {.effects = effects, .resolution = parameters.layout().resolution});
    if (effects.appearance()) maps.setAppearance(bakeAppearance(cage, reference, appearanceBakeOf(parameters)));
    return maps;
}

}  // namespace subdfit::simplify
