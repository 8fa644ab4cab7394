#pragma once
// The tables of the few cages built last, kept by topology (faces, vertex count, tags and level;
// positions play no part in them): simplify draws one cage with several maps, bakes onto it,
// settles it and fits it, each time through a CageFitter or LimitEvaluator of its own, and on a
// dense cage building the tables again costs as much as several renders. Thread-safe; what is
// returned stays valid after it leaves the cache.
#include <memory>

#include "subdiv/adaptive_tables.h"
#include "subdiv/patch_set.h"

namespace subdfit::subdiv {

// As buildPatchSet and buildAdaptiveTables (and throwing as they do), or a copy kept from a
// call on the same topology.
std::shared_ptr<const PatchSet> cachedPatchSet(const mesh::PolygonMesh& mesh, const PatchSetOptions& options);
std::shared_ptr<const AdaptiveTables> cachedAdaptiveTables(const mesh::PolygonMesh& mesh, int isolationLevel);

}  // namespace subdfit::subdiv
