#include "render/patch_tessellation.h"

#include <algorithm>

namespace subdfit::render {

PatchTessellation tessellatePatches(const subdiv::PatchSet& patches, int tessLevel) {
    PatchTessellation t;
    for (int p = 0; p < patches.patchCount(); ++p) {
        const bool gregory = patches.patchInfo[p].y == subdiv::kGregoryBasisPatch;
        if (t.runs.empty() || t.runs.back().gregory != gregory)
            t.runs.push_back({.first = int(t.samples.size()), .count = 0, .gregory = gregory});
        const int level = std::max(1, tessLevel >> patches.patchParam(p).GetDepth());
        const auto first = std::uint32_t(t.samples.size());
        for (int j = 0; j <= level; ++j)
            for (int i = 0; i <= level; ++i) t.samples.push_back({p, i | j << 8 | level << 16});
        const auto at = [&](int i, int j) { return first + std::uint32_t(j * (level + 1) + i); };
        for (int j = 0; j < level; ++j)
            for (int i = 0; i < level; ++i)
                t.quads.insert(t.quads.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        t.runs.back().count = int(t.samples.size()) - t.runs.back().first;
    }
    return t;
}

}  // namespace subdfit::render
