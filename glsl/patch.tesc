#include "bindings.h"
#include "osd_patch_basis"

layout(vertices = 1) out;

flat in int vPatch[];
flat out int tcPatch[];

layout(std430, binding = SUBDFIT_SSBO_PATCH_INFO) readonly buffer PatchInfo { ivec4 patchInfo[]; };

// Segments per base-face edge. Each patch takes its share T / 2^depth (depth counts the
// n-gon split too), so edges shared by patches of different depth get matching vertices:
// the caller keeps T a power of two >= 2^maxDepth, which makes the mesh crack-free.
uniform float uTessLevel;

void main() {
    tcPatch[gl_InvocationID] = vPatch[0];
    ivec4 info = patchInfo[vPatch[0]];
    OsdPatchParam param = OsdPatchParamInit(info.z, info.w, 0.0);
    float level = max(1.0, uTessLevel / float(1 << OsdPatchParamGetDepth(param)));
    gl_TessLevelOuter[0] = level;
    gl_TessLevelOuter[1] = level;
    gl_TessLevelOuter[2] = level;
    gl_TessLevelOuter[3] = level;
    gl_TessLevelInner[0] = level;
    gl_TessLevelInner[1] = level;
}
