#include "subdiv/adaptive_tables.h"

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include "subdiv/osd_messages.h"
#include "subdiv/table_cache.h"
#include "util/error.h"

namespace subdfit::subdiv {

namespace Far = OpenSubdiv::Far;

int AdaptiveTables::baseVertexCount() const { return refiner->GetLevel(0).GetNumVertices(); }

int AdaptiveTables::pointCount() const { return baseVertexCount() + stencils->GetNumStencils(); }

AdaptiveTables buildAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel) {
    // Level 0 cannot draw non-quad faces; above 10 OpenSubdiv's stencil options (4-bit maxLevel,
    // default 10) and memory use stop making sense.
    if (isolationLevel < 1 || isolationLevel > 10)
        throw Error("subdivision isolation level " + std::to_string(isolationLevel) + " is outside 1..10");

    AdaptiveTables tables;
    tables.refiner = buildTopologyRefiner(mesh);
    OsdMessageScope messages;

    Far::PatchTableFactory::Options patchOptions(isolationLevel);
    patchOptions.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    // Infinitely sharp features become regular patches with a boundary mask instead of being
    // isolated to the maximum level; the refiner must be told the same.
    patchOptions.useInfSharpPatch = true;
    patchOptions.generateVaryingTables = false;
    patchOptions.generateFVarTables = false;
    Far::TopologyRefiner::AdaptiveOptions adaptive = patchOptions.GetRefineAdaptiveOptions();
    adaptive.considerFVarChannels = false;
    tables.refiner->RefineAdaptive(adaptive);

    tables.patches.reset(Far::PatchTableFactory::Create(*tables.refiner, patchOptions));
    if (!tables.patches) throw fileError(meshName(mesh), "OpenSubdiv could not build patches: " + messages.summary());
    tables.patchMap = std::make_unique<const Far::PatchMap>(*tables.patches);
    tables.ptexFaceCount = Far::PtexIndices(*tables.refiner).GetNumFaces();

    Far::StencilTableFactory::Options stencilOptions;
    stencilOptions.generateIntermediateLevels = true;   // patches use vertices of every level
    stencilOptions.factorizeIntermediateLevels = true;  // rows over base vertices only
    stencilOptions.generateControlVerts = false;
    stencilOptions.generateOffsets = true;
    stencilOptions.maxLevel = tables.refiner->GetMaxLevel();
    tables.stencils.reset(Far::StencilTableFactory::Create(*tables.refiner, stencilOptions));

    // End-cap (Gregory basis) points come from the patch table as stencils over base + refined
    // vertices; appending factorizes them onto base vertices, after the refined rows -- the
    // layout osd/mesh.h and glViewer use, and the one patch CV indices assume.
    if (const Far::StencilTable* local = tables.patches->GetLocalPointStencilTable();
        local && local->GetNumStencils() > 0) {
        tables.stencils.reset(Far::StencilTableFactory::AppendLocalPointStencilTable(
            *tables.refiner, tables.stencils.get(), local, /*factorize=*/true));
    }
    if (!tables.stencils) throw fileError(meshName(mesh), "OpenSubdiv could not build stencils: " + messages.summary());

    SUBDFIT_CHECK(tables.pointCount() == tables.refiner->GetNumVerticesTotal() + tables.patches->GetNumLocalPoints());
    return tables;
}

std::shared_ptr<const AdaptiveTables> cachedAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel) {
    static TableCache<AdaptiveTables> cache(kMostCachedPoints,
                                            [](const AdaptiveTables& tables) { return long(tables.pointCount()); });
    return cache.get(mesh, isolationLevel, [&] { return buildAdaptiveTables(mesh, isolationLevel); });
}

}  // namespace subdfit::subdiv
