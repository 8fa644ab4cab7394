#include "subdiv/patch_set.h"

#include <opensubdiv/far/ptexIndices.h>

#include <algorithm>
#include <bit>

#include "subdiv/adaptive_tables.h"
#include "subdiv/table_cache.h"
#include "util/error.h"

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

void copyStencils(const Far::StencilTable& table, PatchSet& set) {
    const int rows = table.GetNumStencils();
    set.stencilOffsets.resize(rows + 1);
    for (int i = 0; i < rows; ++i) set.stencilOffsets[i] = table.GetOffsets()[i];
    set.stencilOffsets[rows] = int(table.GetControlIndices().size());
    set.stencilIndices = table.GetControlIndices();
    set.stencilWeights = table.GetWeights();
}

void flattenPatches(const Far::PatchTable& patches, PatchSet& set) {
    for (int array = 0; array < patches.GetNumPatchArrays(); ++array) {
        const Far::PatchDescriptor desc = patches.GetPatchArrayDescriptor(array);
        const int type = int(desc.GetType());
        // Catmark with Gregory-basis end caps gives only these; anything else would need a
        // shader path (and a CPU twin) we do not have.
        SUBDFIT_CHECK(type == kRegularPatch || type == kGregoryBasisPatch);
        const int cvsPerPatch = desc.GetNumControlVertices();
        const Far::ConstIndexArray cvs = patches.GetPatchArrayVertices(array);
        const Far::ConstPatchParamArray params = patches.GetPatchParams(array);
        for (int p = 0; p < patches.GetNumPatches(array); ++p) {
            const Far::PatchParam& param = params[p];
            set.patchInfo.emplace_back(int(set.patchCvIndices.size()), type, std::bit_cast<int>(unsigned(param.field0)),
                                       std::bit_cast<int>(unsigned(param.field1)));
            set.patchCvIndices.insert(set.patchCvIndices.end(), &cvs[p * cvsPerPatch],
                                      &cvs[p * cvsPerPatch] + cvsPerPatch);
            set.maxPatchDepth = std::max(set.maxPatchDepth, int(param.GetDepth()));
        }
    }
}

void mapPtexFaces(const Far::TopologyRefiner& refiner, PatchSet& set) {
    const Far::PtexIndices ptex(refiner);
    const Far::TopologyLevel& base = refiner.GetLevel(0);
    set.ptexFaceCount = ptex.GetNumFaces();
    set.ptexToBaseFace.assign(set.ptexFaceCount, -1);
    for (int face = 0; face < base.GetNumFaces(); ++face) {
        const int size = base.GetFaceVertices(face).size();
        const int first = ptex.GetFaceId(face);
        std::fill_n(set.ptexToBaseFace.begin() + first, size == 4 ? 1 : size, face);
    }
}

// The gradient pass routes a pixel's error to exactly these vertices, so they are the union
// of stencil supports over all CVs of all patches of the face (zero weights left out).
void collectFaceVertices(PatchSet& set) {
    std::vector<std::vector<int>> perFace(set.ptexFaceCount);
    for (int patch = 0; patch < set.patchCount(); ++patch) {
        const glm::ivec4& info = set.patchInfo[patch];
        std::vector<int>& vertices = perFace[set.patchParam(patch).GetFaceId()];
        for (int k = 0; k < patchCvCount(info.y); ++k) {
            const int point = set.patchCvIndices[info.x + k];
            if (point < set.baseVertexCount) {
                vertices.push_back(point);
                continue;
            }
            const int row = point - set.baseVertexCount;
            for (int e = set.stencilOffsets[row]; e < set.stencilOffsets[row + 1]; ++e)
                if (set.stencilWeights[e] != 0.0f) vertices.push_back(set.stencilIndices[e]);
        }
    }
    set.faceVertexOffsets.assign(1, 0);
    set.faceVertexIndices.clear();
    for (std::vector<int>& vertices : perFace) {
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        set.faceVertexIndices.insert(set.faceVertexIndices.end(), vertices.begin(), vertices.end());
        set.faceVertexOffsets.push_back(int(set.faceVertexIndices.size()));
    }
}

}  // namespace

PatchSet buildPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options) {
    // Kept: a cage's limit evaluator (its limit fit, its bakes) has often built them already.
    const std::shared_ptr<const AdaptiveTables> kept = cachedAdaptiveTables(mesh, options.isolationLevel);
    const AdaptiveTables& tables = *kept;
    PatchSet set;
    set.baseVertexCount = tables.baseVertexCount();
    set.pointCount = tables.pointCount();
    copyStencils(*tables.stencils, set);
    flattenPatches(*tables.patches, set);
    mapPtexFaces(*tables.refiner, set);
    collectFaceVertices(set);
    return set;
}

std::shared_ptr<const PatchSet> cachedPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options) {
    static TableCache<PatchSet> cache(kMostCachedPoints, [](const PatchSet& set) { return long(set.pointCount); });
    return cache.get(mesh, options.isolationLevel, [&] { return buildPatchSet(mesh, options); });
}

}  // namespace subdfit::subdiv
