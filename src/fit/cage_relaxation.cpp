#include "fit/cage_relaxation.h"

#include <algorithm>
#include <map>
#include <set>

#include "bindings.h"
#include "gl/dispatch.h"
#include "mesh/mesh_adjacency.h"

namespace subdfit::fit {
namespace {

const gl::ProgramSpec kRelax{"relax", {{GL_COMPUTE_SHADER, "relax.comp"}}};
const gl::ProgramSpec kProject{"project_gradient", {{GL_COMPUTE_SHADER, "project_gradient.comp"}}};

std::pair<int, int> edgeKey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

}  // namespace

RelaxationTopology relaxationTopology(const mesh::PolygonMesh& cage) {
    const int n = cage.vertexCount();
    RelaxationTopology t;
    const auto adjacency = mesh::vertexAdjacency(cage);

    // Sharp edges: creases with any sharpness, and boundary edges (used by one face).
    std::map<std::pair<int, int>, int> faceUse;
    std::vector<std::vector<std::pair<int, int>>> corners(static_cast<size_t>(n));
    size_t first = 0;
    const std::set<int> holes(cage.tags.holes.begin(), cage.tags.holes.end());
    for (int f = 0; f < cage.faceCount(); ++f) {
        const int size = cage.faceSizes[size_t(f)];
        for (int k = 0; k < size; ++k) {
            const int v = cage.faceIndices[first + size_t(k)];
            const int next = cage.faceIndices[first + size_t((k + 1) % size)];
            const int previous = cage.faceIndices[first + size_t((k + size - 1) % size)];
            ++faceUse[edgeKey(v, next)];
            if (!holes.count(f)) corners[size_t(v)].push_back({previous, next});
        }
        first += size_t(size);
    }
    std::set<std::pair<int, int>> sharp;
    for (const auto& [edge, count] : faceUse)
        if (count == 1) sharp.insert(edge);
    for (const auto& c : cage.tags.creases)
        if (c.sharpness > 0.0f) sharp.insert(edgeKey(c.v0, c.v1));
    std::set<int> cornerTagged;
    for (const auto& c : cage.tags.corners)
        if (c.sharpness > 0.0f) cornerTagged.insert(c.vertex);

    t.modes.assign(size_t(n), RelaxationTopology::Surface);
    t.offsets.push_back(0);
    t.cornerOffsets.push_back(0);
    for (int v = 0; v < n; ++v) {
        std::vector<int> all(adjacency.neighbors.begin() + adjacency.offsets[size_t(v)],
                             adjacency.neighbors.begin() + adjacency.offsets[size_t(v) + 1]);
        std::vector<int> along;
        for (int w : all)
            if (sharp.count(edgeKey(v, w))) along.push_back(w);
        std::vector<int> chosen = all;
        if (cornerTagged.count(v) || corners[size_t(v)].empty() || (!along.empty() && along.size() != 2)) {
            t.modes[size_t(v)] = RelaxationTopology::Fixed;
            chosen.clear();
        } else if (along.size() == 2) {
            t.modes[size_t(v)] = RelaxationTopology::Crease;
            chosen = along;
        }
        t.neighbors.insert(t.neighbors.end(), chosen.begin(), chosen.end());
        t.offsets.push_back(int(t.neighbors.size()));
        for (const auto& [previous, next] : corners[size_t(v)]) t.corners.insert(t.corners.end(), {previous, next});
        t.cornerOffsets.push_back(int(t.corners.size() / 2));
    }
    return t;
}

std::vector<glm::vec3> restOffsets(const mesh::PolygonMesh& cage, const RelaxationTopology& t, int passes) {
    const size_t n = cage.positions.size();
    auto centroidOf = [&](const std::vector<glm::vec3>& values, size_t v) {
        const int begin = t.offsets[v], end = t.offsets[v + 1];
        if (end == begin) return values[v];
        glm::vec3 sum(0.0f);
        for (int k = begin; k < end; ++k) sum += values[size_t(t.neighbors[size_t(k)])];
        return sum / float(end - begin);
    };
    std::vector<glm::vec3> offsets(n);
    for (size_t v = 0; v < n; ++v) offsets[v] = cage.positions[v] - centroidOf(cage.positions, v);
    for (int pass = 0; pass < passes; ++pass) {
        std::vector<glm::vec3> smoothed(n);
        for (size_t v = 0; v < n; ++v) smoothed[v] = 0.5f * (offsets[v] + centroidOf(offsets, v));
        offsets = std::move(smoothed);
    }
    return offsets;
}

CageRelaxation::CageRelaxation(const mesh::PolygonMesh& cage, int restPasses) : vertexCount_(cage.vertexCount()) {
    const RelaxationTopology t = relaxationTopology(cage);
    std::vector<glm::vec3> rest = restPasses >= 0 ? restOffsets(cage, t, restPasses)
                                                  : std::vector<glm::vec3>(cage.positions.size(), glm::vec3(0.0f));
    rest_ = gl::Buffer(GLsizeiptr(rest.size() * sizeof(glm::vec3)));
    rest_.upload(rest.data(), GLsizeiptr(rest.size() * sizeof(glm::vec3)));
    modes_ = gl::Buffer::fromVector(t.modes);
    offsets_ = gl::Buffer::fromVector(t.offsets);
    neighbors_ = gl::Buffer::fromVector(t.neighbors);
    cornerOffsets_ = gl::Buffer::fromVector(t.cornerOffsets);
    corners_ = gl::Buffer::fromVector(t.corners);
    scratch_ = gl::Buffer(GLsizeiptr(vertexCount_) * 3 * GLsizeiptr(sizeof(float)));
}

void CageRelaxation::bindTangentFrame() const {
    modes_.bindStorage(SUBDFIT_SSBO_RELAX_MODES);
    offsets_.bindStorage(SUBDFIT_SSBO_ADJACENCY_OFFSETS);
    neighbors_.bindStorage(SUBDFIT_SSBO_ADJACENCY_INDICES);
    cornerOffsets_.bindStorage(SUBDFIT_SSBO_RELAX_CORNER_OFFSETS);
    corners_.bindStorage(SUBDFIT_SSBO_RELAX_CORNERS);
}

void CageRelaxation::dispatchOverVertices() {
    bindTangentFrame();  // both passes read the same topology
    glDispatchCompute(gl::groupsOf(vertexCount_, 128), 1, 1);
}

void CageRelaxation::apply(gl::ProgramCache& programs, gl::Buffer& theta, float rate) {
    if (rate <= 0.0f) return;
    const auto& program = programs.get(kRelax);
    program.use();
    program.set("uVertexCount", vertexCount_);
    program.set("uRate", rate);
    theta.bindStorage(SUBDFIT_SSBO_SMOOTH_IN);
    scratch_.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
    rest_.bindStorage(SUBDFIT_SSBO_RELAX_REST);
    dispatchOverVertices();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    theta.copyFrom(scratch_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void CageRelaxation::projectGradient(gl::ProgramCache& programs, const gl::Buffer& theta, gl::Buffer& gradient,
                                     float keep) {
    if (keep >= 1.0f) return;
    const auto& program = programs.get(kProject);
    program.use();
    program.set("uVertexCount", vertexCount_);
    program.set("uKeep", keep);
    theta.bindStorage(SUBDFIT_SSBO_THETA);
    gradient.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
    dispatchOverVertices();
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace subdfit::fit
