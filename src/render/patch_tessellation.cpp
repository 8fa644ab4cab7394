#include "render/patch_tessellation.h"

#include <algorithm>
#include <unordered_map>

namespace subdfit::render {
namespace {

// Where vertex (i, j) of a patch's L × L grid lies on its ptex face, exactly, packed as a key:
// the face, then u and v in units of 2^-20 of the face. A depth-d patch spans 2^-d of the face
// (the split of a non-quad face counts in d); d <= 10 and L <= 64 divide 2^20 without remainder.
std::uint64_t facePointKey(const subdiv::PatchSet& patches, int patch, int i, int j, int level) {
    const auto param = patches.patchParam(patch);
    const int depth = param.GetDepth() - (param.NonQuadRoot() ? 1 : 0);
    const std::uint64_t span = std::uint64_t(1) << (20 - depth);
    const std::uint64_t u = param.GetU() * span + std::uint64_t(i) * span / std::uint64_t(level);
    const std::uint64_t v = param.GetV() * span + std::uint64_t(j) * span / std::uint64_t(level);
    return std::uint64_t(param.GetFaceId()) << 42 | u << 21 | v;
}

}  // namespace

PatchTessellation tessellatePatches(const subdiv::PatchSet& patches, int tessLevel) {
    PatchTessellation t;
    // Patches of one ptex face share the vertices on their common edges: each is evaluated once,
    // by the first patch that reaches it (most of them where deep patches have L = 1). Vertices are
    // never shared across faces: their ptex (u, v) and face differ there.
    std::unordered_map<std::uint64_t, std::uint32_t> vertexAt;
    std::vector<std::uint32_t> grid;
    for (int p = 0; p < patches.patchCount(); ++p) {
        const bool gregory = patches.patchInfo[p].y == subdiv::kGregoryBasisPatch;
        if (t.runs.empty() || t.runs.back().gregory != gregory)
            t.runs.push_back({.first = int(t.samples.size()), .count = 0, .gregory = gregory});
        const int level = std::max(1, tessLevel >> patches.patchParam(p).GetDepth());
        grid.clear();
        for (int j = 0; j <= level; ++j)
            for (int i = 0; i <= level; ++i) {
                const auto [at, added] =
                    vertexAt.try_emplace(facePointKey(patches, p, i, j, level), std::uint32_t(t.samples.size()));
                if (added) t.samples.push_back({p, i | j << 8 | level << 16});
                grid.push_back(at->second);
            }
        const auto at = [&](int i, int j) { return grid[size_t(j * (level + 1) + i)]; };
        for (int j = 0; j < level; ++j)
            for (int i = 0; i < level; ++i)
                t.quads.insert(t.quads.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        t.runs.back().count = int(t.samples.size()) - t.runs.back().first;
    }
    std::erase_if(t.runs, [](const SampleRun& run) { return run.count == 0; });  // all its vertices shared
    return t;
}

}  // namespace subdfit::render
