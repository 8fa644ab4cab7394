#pragma once
// CPU reference for what the GPU draws: the limit surface of a cage evaluated through
// OpenSubdiv's own patch lookup (Far::PatchMap) and basis, on the same tables as PatchSet.
// Slow per call: for bakes, fits of the cage to a reference, exports and checks, not for the
// fitting loop.
#include <glm/vec3.hpp>

#include <memory>
#include <span>
#include <vector>

#include "subdiv/adaptive_tables.h"
#include "subdiv/patch_set.h"

namespace subdfit::subdiv {

struct LimitSample {
    glm::vec3 position{0.0f};
    // Derivatives with respect to the ptex face's (u, v) in [0,1]^2, not the sub-patch's.
    glm::vec3 dPdu{0.0f}, dPdv{0.0f};
};

class LimitEvaluator {
public:
    // At the isolation level the GPU draws `mesh` at (drawingIsolationLevel): what a fit renders,
    // a bake displaces and an export tessellates is then one surface.
    explicit LimitEvaluator(const mesh::PolygonMesh& mesh);
    LimitEvaluator(const mesh::PolygonMesh& mesh, const PatchSetOptions& options);

    int baseVertexCount() const { return tables_->baseVertexCount(); }
    int ptexFaceCount() const { return tables_->ptexFaceCount; }
    // False for holes (no surface there) and ids out of range.
    bool hasSurface(int ptexFace, float u, float v) const;

    // basePositions holds baseVertexCount() positions (the cage may have moved since it was
    // built: topology is fixed, positions are not). Requires hasSurface(ptexFace, u, v).
    LimitSample evaluate(int ptexFace, float u, float v, std::span<const glm::vec3> basePositions) const;

    // Every point the patches read (the base, then each refined and local point) from base
    // positions: for many samples of the same positions, each point's stencil is applied once,
    // not at every sample that reads it. evaluate() on them gives the same bits as on the base.
    std::vector<glm::dvec3> patchPoints(std::span<const glm::vec3> basePositions) const;
    LimitSample evaluate(int ptexFace, float u, float v, std::span<const glm::dvec3> patchPoints) const;

    // The limit position at (ptexFace, u, v) as weights on the base vertices: position =
    // Σ weight · base[vertex], for any positions (the surface is linear in its cage). Each
    // vertex appears once. Requires hasSurface(ptexFace, u, v).
    struct BaseWeight {
        int vertex;
        double weight;
    };
    std::vector<BaseWeight> positionWeights(int ptexFace, float u, float v) const;

private:
    std::shared_ptr<const AdaptiveTables> tables_;  // shared with other evaluators of the same topology
};

// All pointCount points of a PatchSet from base positions: the base copied, then each stencil
// row applied -- the CPU twin of the GPU stencil pass.
std::vector<glm::vec3> evaluatePoints(const PatchSet& set, std::span<const glm::vec3> base);

}  // namespace subdfit::subdiv
