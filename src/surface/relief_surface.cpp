#include "surface/relief_surface.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mesh/mesh_geometry.h"
#include "mesh/point_welder.h"
#include "subdiv/uniform_refinement.h"
#include "surface/tessellation.h"

namespace subdfit::surface {

namespace {

// One index per position: vertices split only for their texture coordinates (a seam) share one.
std::vector<int> positionIndices(const mesh::PolygonMesh& mesh, float tolerance) {
    mesh::PointWelder welder(tolerance);
    int positions = 0;
    std::vector<int> index(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) index[v] = welder.indexOf(mesh.positions[v], positions);
    return index;
}

// Area-weighted normals of `mesh` as if the vertices of one position (positionIndices) were one:
// a seam moves as one piece, without a crack, and shades alike on both sides.
std::vector<glm::vec3> normalsByPosition(const mesh::PolygonMesh& mesh, const std::vector<int>& position) {
    if (position.empty()) return {};
    mesh::PolygonMesh shape;
    shape.positions.resize(size_t(*std::max_element(position.begin(), position.end()) + 1));
    for (size_t v = 0; v < mesh.positions.size(); ++v) shape.positions[size_t(position[v])] = mesh.positions[v];
    shape.faceSizes = mesh.faceSizes;
    for (int i : mesh.faceIndices) shape.faceIndices.push_back(position[size_t(i)]);
    const std::vector<glm::vec3> normals = mesh::vertexNormals(shape);
    std::vector<glm::vec3> out(mesh.positions.size());
    for (size_t v = 0; v < out.size(); ++v) out[v] = normals[size_t(position[v])];
    return out;
}

// A plane wave, sin(k·p + phase).
struct Wave {
    glm::vec3 k;
    float phase;
};

float sumOfWaves(const std::vector<Wave>& waves, const glm::vec3& p) {
    float sum = 0.0f;
    for (const Wave& wave : waves) sum += std::sin(glm::dot(wave.k, p) + wave.phase);
    return sum;
}

// `count` waves of random directions and phases (isotropic), each of wavelength `wavelength(u)`
// for a uniform u drawn between its direction and its phase.
template <class Wavelength>
std::vector<Wave> randomWaves(int count, std::mt19937& rng, Wavelength wavelength) {
    std::normal_distribution<float> gaussian;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Wave> waves;
    for (int w = 0; w < count; ++w) {
        const glm::vec3 direction = glm::normalize(glm::vec3(gaussian(rng), gaussian(rng), gaussian(rng)) + 1e-6f);
        const float length = wavelength(unit(rng));
        waves.push_back({direction * (2.0f * float(M_PI) / length), 2.0f * float(M_PI) * unit(rng)});
    }
    return waves;
}

// Per vertex, how much of the relief it carries (0..1) so that about `coverage` of the vertices
// carry it: four long waves (a third to two thirds of the diagonal) summed, 0 below their
// (1 - coverage) quantile and 1 above it, but for a fade a tenth of their spread wide across it.
// Empty for coverage >= 1.
std::vector<float> coverageMask(const std::vector<glm::vec3>& positions, float coverage, float diagonal,
                                std::mt19937& rng) {
    if (coverage >= 1.0f || positions.empty()) return {};
    if (coverage <= 0.0f) return std::vector<float>(positions.size(), 0.0f);
    const std::vector<Wave> waves = randomWaves(4, rng, [&](float u) { return (1.0f / 3.0f + u / 3.0f) * diagonal; });
    std::vector<float> field(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) field[v] = sumOfWaves(waves, positions[v]);
    std::vector<float> sorted = field;
    const auto at = [&](float q) {
        const size_t k = std::min(sorted.size() - 1, size_t(std::max(0.0f, q) * float(sorted.size())));
        std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
        return sorted[k];
    };
    const float threshold = at(1.0f - coverage);
    const float margin = std::max(0.1f * (at(0.95f) - at(0.05f)), 1e-6f);  // a flat field: a step
    std::vector<float> mask(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) {
        const float t = std::clamp((field[v] - threshold) / margin + 0.5f, 0.0f, 1.0f);
        mask[v] = t * t * (3.0f - 2.0f * t);
    }
    return mask;
}

}  // namespace

void addRelief(mesh::PolygonMesh& surface, const ReliefOptions& o) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const auto& p : surface.positions) low = glm::min(low, p), high = glm::max(high, p);
    const float diagonal = glm::length(high - low);

    // Plane waves of log-uniform wavelengths: isotropic, band-limited detail.
    std::mt19937 rng(o.seed);
    const std::vector<Wave> waves = randomWaves(o.waves, rng, [&](float u) {
        return o.shortestWavelength * std::pow(o.longestWavelength / o.shortestWavelength, u) * diagonal;
    });
    // A sum of N unit sines has RMS sqrt(N / 2).
    const float scale = o.amplitude * diagonal / std::sqrt(0.5f * float(std::max(o.waves, 1)));
    const std::vector<int> position = positionIndices(surface, 1e-6f * diagonal);
    const auto normals = normalsByPosition(surface, position);
    const std::vector<float> cover = coverageMask(surface.positions, o.coverage, diagonal, rng);
    for (size_t v = 0; v < surface.positions.size(); ++v) {
        const float height = sumOfWaves(waves, surface.positions[v]);
        surface.positions[v] += (cover.empty() ? 1.0f : cover[v]) * scale * height * normals[v];
    }
    // Shaded smooth across seams, as a sculpting tool would export it.
    surface.normals = normalsByPosition(surface, position);
}

mesh::PolygonMesh reliefSurface(const mesh::PolygonMesh& cage, const ReliefOptions& o) {
    // All quads first, so that every ptex tile has the same size and the tessellation no
    // T-junctions (cracks a decimator would take for borders).
    mesh::PolygonMesh surface = limitMesh(subdiv::refinedOnce(cage), std::max(1, o.segments / 2));
    addRelief(surface, o);
    surface.sourcePath = cage.sourcePath + " (relief surface)";
    return surface;
}

}  // namespace subdfit::surface
