// A vertex of the evaluated surface, and its record of 16 floats (four vec4s): position, normal,
// ∂P/∂u, ∂P/∂v, ptex (u, v), ptex face (its int's bits). surface.vert reads the records as
// vertex attributes (render::PatchRenderer's layout).
#ifndef SUBDFIT_SURFACE_VERTEX_GLSL
#define SUBDFIT_SURFACE_VERTEX_GLSL

struct SurfacePoint {
    vec3 position, normal, tangentU, tangentV;
    int ptexFace;
    vec2 ptexUv;
};

layout(std430, binding = SUBDFIT_SSBO_SURFACE_VERTICES) writeonly buffer SurfaceVertices { float surfaceVertices[]; };
#ifdef SUBDFIT_SURFACE_PAIR
// A second surface's vertices, evaluated beside the first (θ− beside θ+).
layout(std430, binding = SUBDFIT_SSBO_SECOND_SURFACE_VERTICES) writeonly buffer SecondSurfaceVertices { float secondSurfaceVertices[]; };
#endif

float[16] surfaceRecord(SurfacePoint p) {
    return float[16](p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z, p.tangentU.x,
                     p.tangentU.y, p.tangentU.z, p.tangentV.x, p.tangentV.y, p.tangentV.z, p.ptexUv.x, p.ptexUv.y,
                     intBitsToFloat(p.ptexFace), 0.0);
}

void storeSurfaceVertex(int k, SurfacePoint p) {
    float record[16] = surfaceRecord(p);
    for (int c = 0; c < 16; ++c) surfaceVertices[16 * k + c] = record[c];
}

#ifdef SUBDFIT_SURFACE_PAIR
void storeSecondSurfaceVertex(int k, SurfacePoint p) {
    float record[16] = surfaceRecord(p);
    for (int c = 0; c < 16; ++c) secondSurfaceVertices[16 * k + c] = record[c];
}
#endif

// A record read back through an RGBA32F buffer texture over the records.
SurfacePoint loadSurfaceVertex(samplerBuffer records, int k) {
    vec4 a = texelFetch(records, 4 * k), b = texelFetch(records, 4 * k + 1);
    vec4 c = texelFetch(records, 4 * k + 2), d = texelFetch(records, 4 * k + 3);
    SurfacePoint p;
    p.position = a.xyz;
    p.normal = vec3(a.w, b.xy);
    p.tangentU = vec3(b.zw, c.x);
    p.tangentV = c.yzw;
    p.ptexUv = d.xy;
    p.ptexFace = floatBitsToInt(d.z);
    return p;
}
#endif
