#include "subdiv/limit_evaluator.h"

#include <glm/geometric.hpp>

#include <algorithm>

#include "util/error.h"

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

// One point of the refined + local point space, accumulated in double so the reference is
// not limited by the summation order of long end-cap stencils.
glm::dvec3 pointPosition(const Far::StencilTable& stencils, int point, std::span<const glm::vec3> base) {
    const int baseCount = int(base.size());
    if (point < baseCount) return glm::dvec3(base[point]);
    const Far::Stencil row = stencils.GetStencil(point - baseCount);
    glm::dvec3 sum(0.0);
    for (int e = 0; e < row.GetSize(); ++e)
        sum += double(row.GetWeights()[e]) * glm::dvec3(base[row.GetVertexIndices()[e]]);
    return sum;
}

// The limit sample at (ptexFace, u, v), its patch's CVs read through `point`.
template <typename PointAt>
LimitSample sampleThrough(const Far::PatchTable& patches, const Far::PatchMap& patchMap, int ptexFace, float u, float v,
                          const PointAt& point) {
    const Far::PatchTable::PatchHandle& handle = *patchMap.FindPatch(ptexFace, u, v);
    // EvaluateBasis takes the ptex face's (u, v) and already scales the derivative weights by
    // the sub-patch's size, so dP/du here is per unit of the face parameter.
    float wP[20], wDu[20], wDv[20];
    patches.EvaluateBasis(handle, u, v, wP, wDu, wDv);
    const Far::ConstIndexArray cvs = patches.GetPatchVertices(handle);
    glm::dvec3 p(0.0), du(0.0), dv(0.0);
    for (int k = 0; k < cvs.size(); ++k) {
        const glm::dvec3 cv = point(cvs[k]);
        p += double(wP[k]) * cv;
        du += double(wDu[k]) * cv;
        dv += double(wDv[k]) * cv;
    }
    return {glm::vec3(p), glm::vec3(du), glm::vec3(dv)};
}

}  // namespace

LimitEvaluator::LimitEvaluator(const mesh::PolygonMesh& mesh)
    : LimitEvaluator(mesh, {.isolationLevel = drawingIsolationLevel(mesh)}) {}

LimitEvaluator::LimitEvaluator(const mesh::PolygonMesh& mesh, const PatchSetOptions& options)
    : tables_(cachedAdaptiveTables(mesh, options.isolationLevel)) {}

bool LimitEvaluator::hasSurface(int ptexFace, float u, float v) const {
    return ptexFace >= 0 && ptexFace < tables_->ptexFaceCount &&
           tables_->patchMap->FindPatch(ptexFace, u, v) != nullptr;
}

LimitSample LimitEvaluator::evaluate(int ptexFace, float u, float v, std::span<const glm::vec3> basePositions) const {
    SUBDFIT_CHECK(int(basePositions.size()) == baseVertexCount());
    SUBDFIT_CHECK(hasSurface(ptexFace, u, v));
    return sampleThrough(*tables_->patches, *tables_->patchMap, ptexFace, u, v,
                         [&](int point) { return pointPosition(*tables_->stencils, point, basePositions); });
}

std::vector<glm::dvec3> LimitEvaluator::patchPoints(std::span<const glm::vec3> basePositions) const {
    SUBDFIT_CHECK(int(basePositions.size()) == baseVertexCount());
    std::vector<glm::dvec3> points(size_t(tables_->pointCount()));
    for (int point = 0; point < int(points.size()); ++point)
        points[size_t(point)] = pointPosition(*tables_->stencils, point, basePositions);
    return points;
}

LimitSample LimitEvaluator::evaluate(int ptexFace, float u, float v, std::span<const glm::dvec3> patchPoints) const {
    SUBDFIT_CHECK(int(patchPoints.size()) == tables_->pointCount());
    SUBDFIT_CHECK(hasSurface(ptexFace, u, v));
    return sampleThrough(*tables_->patches, *tables_->patchMap, ptexFace, u, v,
                         [&](int point) { return patchPoints[size_t(point)]; });
}

std::vector<LimitEvaluator::BaseWeight> LimitEvaluator::positionWeights(int ptexFace, float u, float v) const {
    SUBDFIT_CHECK(hasSurface(ptexFace, u, v));
    const Far::PatchTable::PatchHandle& handle = *tables_->patchMap->FindPatch(ptexFace, u, v);
    float wP[20];
    tables_->patches->EvaluateBasis(handle, u, v, wP);
    const Far::ConstIndexArray cvs = tables_->patches->GetPatchVertices(handle);
    const int baseCount = baseVertexCount();
    // The CVs' stencils overlap on a few dozen base vertices in some hundreds of terms: they are
    // merged in a dense row of this thread's, which only the vertices touched are cleared from.
    thread_local std::vector<double> row;
    thread_local std::vector<char> seen;
    thread_local std::vector<int> touched;
    if (int(row.size()) < baseCount) row.assign(size_t(baseCount), 0.0), seen.assign(size_t(baseCount), 0);
    touched.clear();
    const auto add = [&](int vertex, double weight) {
        if (!seen[size_t(vertex)]) seen[size_t(vertex)] = 1, touched.push_back(vertex);
        row[size_t(vertex)] += weight;
    };
    for (int k = 0; k < cvs.size(); ++k) {
        if (wP[k] == 0.0f) continue;
        if (cvs[k] < baseCount) {
            add(cvs[k], double(wP[k]));
            continue;
        }
        const Far::Stencil stencil = tables_->stencils->GetStencil(cvs[k] - baseCount);
        for (int e = 0; e < stencil.GetSize(); ++e)
            add(stencil.GetVertexIndices()[e], double(wP[k]) * double(stencil.GetWeights()[e]));
    }
    std::sort(touched.begin(), touched.end());
    std::vector<BaseWeight> merged;
    merged.reserve(touched.size());
    for (int vertex : touched) {
        merged.push_back({vertex, row[size_t(vertex)]});
        row[size_t(vertex)] = 0.0, seen[size_t(vertex)] = 0;
    }
    return merged;
}

std::vector<glm::vec3> evaluatePoints(const PatchSet& set, std::span<const glm::vec3> base) {
    SUBDFIT_CHECK(int(base.size()) == set.baseVertexCount);
    std::vector<glm::vec3> points(base.begin(), base.end());
    points.reserve(set.pointCount);
    for (int row = 0; row < set.stencilCount(); ++row) {
        glm::vec3 sum(0.0f);
        for (int e = set.stencilOffsets[row]; e < set.stencilOffsets[row + 1]; ++e)
            sum += set.stencilWeights[e] * base[set.stencilIndices[e]];
        points.push_back(sum);
    }
    return points;
}

}  // namespace subdfit::subdiv
