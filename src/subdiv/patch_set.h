#pragma once
// Everything the GPU needs to draw and differentiate one cage, as plain arrays for SSBO upload.
//
// Index spaces:
// - base vertex: 0 .. baseVertexCount-1, the cage's own vertices (PolygonMesh order).
// - point: 0 .. pointCount-1. Points below baseVertexCount are the base vertices themselves;
//   point baseVertexCount + i is stencil row i (refined vertices of levels 1..max in level
//   order, then the Gregory end-cap local points), a weighted sum of base vertices.
// - ptex face: quads give one, an n-gon gives n (one per corner, Far::PtexIndices order).
//   PatchParam face ids are ptex face ids.
// Holes keep their ptex ids (so ids match OpenSubdiv's) but have no patches and an empty
// face -> vertex list: nothing is drawn there and no gradient is routed through them.
#include <glm/vec4.hpp>
#include <opensubdiv/far/patchParam.h>

#include <memory>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "subdiv/isolation_level.h"

namespace subdfit::subdiv {

struct PatchSetOptions {
    int isolationLevel = kIsolationLevel;  // 1..10: how deep extraordinary vertices and creases are isolated
};

// Far::PatchDescriptor::Type values, the only two a PatchSet holds.
inline constexpr int kRegularPatch = 6;       // bicubic B-spline, 16 CVs
inline constexpr int kGregoryBasisPatch = 9;  // end cap at extraordinary vertices, 20 CVs

inline int patchCvCount(int patchType) { return patchType == kRegularPatch ? 16 : 20; }

struct PatchSet {
    int baseVertexCount = 0;
    int pointCount = 0;  // base + refined + local points; patch CVs index this range
    // Points [baseVertexCount, pointCount) as stencils over base vertices, CSR:
    std::vector<int> stencilOffsets;  // size pointCount - baseVertexCount + 1
    std::vector<int> stencilIndices;  // base vertex indices
    std::vector<float> stencilWeights;
    // Patches, flattened over all patch arrays: {cvOffset into patchCvIndices, patch type,
    // PatchParam field0, PatchParam field1} (the unsigned fields bit-cast to int).
    std::vector<glm::ivec4> patchInfo;
    std::vector<int> patchCvIndices;  // point indices
    int ptexFaceCount = 0;
    std::vector<int> ptexToBaseFace;
    // ptex face -> base vertices with a nonzero weight in any CV of any patch of that face
    // (sorted, unique), CSR:
    std::vector<int> faceVertexOffsets;  // size ptexFaceCount + 1
    std::vector<int> faceVertexIndices;
    int maxPatchDepth = 0;  // deepest PatchParam depth (for crack-free tess levels)

    int patchCount() const { return int(patchInfo.size()); }
    int stencilCount() const { return pointCount - baseVertexCount; }
    OpenSubdiv::Far::PatchParam patchParam(int patch) const {
        return {unsigned(patchInfo[patch].z), unsigned(patchInfo[patch].w)};
    }
};

// Throws subdfit::Error (naming mesh.sourcePath) when the cage cannot be subdivided.
PatchSet buildPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options = {});
// The same, or a copy kept from a call on the same topology (subdiv/table_cache.h).
std::shared_ptr<const PatchSet> cachedPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options = {});

}  // namespace subdfit::subdiv
