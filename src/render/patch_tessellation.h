#pragma once
// A fixed tessellation of a cage's patches: where each vertex lies in its patch's domain and the
// triangles between them. Each patch has L = max(1, T / 2^depth) segments per edge, so patches
// of every depth meet vertex for vertex along their edges (T a power of two >= 2^maxDepth):
// the mesh is crack-free, and patches of one ptex face share the vertices they have in common.
// glsl/tessellate.comp evaluates the surface at these vertices, and
// glsl/triangulate.comp splits each quad along its shorter diagonal there.
#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

#include "subdiv/patch_set.h"

namespace subdfit::render {

// Consecutive vertices of patches of one kind, evaluated by one shader variant.
struct SampleRun {
    int first = 0, count = 0;
    bool gregory = false;  // Gregory-basis end caps, else regular B-spline patches
};

struct PatchTessellation {
    // Per vertex: the patch that evaluates it, and i | j << 8 | L << 16 for its domain point
    // (i / L, j / L) there.
    std::vector<glm::ivec2> samples;
    // 4 vertex indices each: (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) of their patch.
    std::vector<std::uint32_t> quads;
    std::vector<SampleRun> runs;  // in patch order, each kind together
};

// `tessLevel`: segments per base-face edge, a power of two of at most 64.
PatchTessellation tessellatePatches(const subdiv::PatchSet& patches, int tessLevel);

}  // namespace subdfit::render
