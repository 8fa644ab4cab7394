// P, where a cage vertex may move along its surface (fit/cage_relaxation.h): the tangent plane
// (normal from the face corners at the vertex) for a surface vertex, the chain direction for a
// crease vertex, nothing for a fixed one. Declares the topology's buffers; the includer defines
// point(v), the vertex's position.
#ifndef SUBDFIT_TANGENT_FRAME_GLSL
#define SUBDFIT_TANGENT_FRAME_GLSL

layout(std430, binding = SUBDFIT_SSBO_RELAX_MODES) readonly buffer Modes { int modes[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_OFFSETS) readonly buffer Offsets { int offsets[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_INDICES) readonly buffer Neighbours { int neighbours[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNER_OFFSETS) readonly buffer CornerOffsets { int cornerOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNERS) readonly buffer Corners { int corners[]; };

vec3 point(int v);

const int kSurfaceVertex = 0, kCreaseVertex = 1, kFixedVertex = 2;

// P d at vertex v.
vec3 tangentialPart(int v, vec3 d) {
    int begin = offsets[v], end = offsets[v + 1];
    if (modes[v] == kFixedVertex || end == begin) return vec3(0.0);
    if (modes[v] == kCreaseVertex) {
        vec3 along = point(neighbours[end - 1]) - point(neighbours[begin]);
        float l = length(along);
        return l > 0.0 ? dot(d, along / l) * (along / l) : vec3(0.0);
    }
    vec3 p = point(v), n = vec3(0.0);
    for (int k = cornerOffsets[v]; k < cornerOffsets[v + 1]; ++k)
        n += cross(point(corners[2 * k + 1]) - p, point(corners[2 * k]) - p);
    float l = length(n);
    return l > 0.0 ? d - dot(d, n / l) * (n / l) : vec3(0.0);
}

#endif
