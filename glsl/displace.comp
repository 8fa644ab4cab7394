// The tessellation's vertices displaced by the heights, from the limit surface's vertices that
// tessellate.comp evaluated without them (render::PatchRenderer::displace): while the cage stays,
// each set of heights costs this pass instead of the patches' basis again. One thread a vertex.
#include "bindings.h"
#include "maps.glsl"
#include "displacement.glsl"

layout(local_size_x = 64) in;

layout(binding = SUBDFIT_UNIT_LIMIT_VERTICES) uniform samplerBuffer limitVertices;

uniform int uVertexCount;

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= uVertexCount) return;
    SurfacePoint p = loadSurfaceVertex(limitVertices, k);
    displace(p, heightSample(p.ptexFace, p.ptexUv));
    storeSurfaceVertex(k, p);
}
