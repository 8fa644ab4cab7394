#pragma once
// The OpenSubdiv objects behind one cage at one isolation level. PatchSet (for the GPU) and
// LimitEvaluator (the CPU reference) are both derived from these, so they share one index
// space by construction.
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/stencilTable.h>

#include <memory>

#include "subdiv/topology.h"

namespace subdfit::subdiv {

struct AdaptiveTables {
    RefinerPtr refiner;  // refined adaptively
    std::unique_ptr<const OpenSubdiv::Far::PatchTable> patches;
    // One row per point above the base vertices, factorized over base vertices only: row i is
    // point baseVertexCount + i. The points are the refined vertices of levels 1..max (in level
    // order), then the end-cap local points -- the space patch CV indices refer to.
    std::unique_ptr<const OpenSubdiv::Far::StencilTable> stencils;
    // The patch covering a ptex face's (u, v): built once with the tables, not by every
    // evaluator of them (a bake, a map layout, a decode each make one).
    std::unique_ptr<const OpenSubdiv::Far::PatchMap> patchMap;
    int ptexFaceCount = 0;

    int baseVertexCount() const;
    int pointCount() const;  // base vertices + stencil rows
};

// isolationLevel in [1, 10]; throws subdfit::Error for a bad level or a cage OpenSubdiv rejects.
AdaptiveTables buildAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel);
// The same, or the tables kept from a call on the same topology (subdiv/table_cache.h).
std::shared_ptr<const AdaptiveTables> cachedAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel);

}  // namespace subdfit::subdiv
