// Bilinear lookup in a per-face node tile (maps::TexelLayout): ptex (u,v) of `face` falls in
// cell (i, j) of T×T; the four corner nodes and their weights. Clamped, because rasterised
// (u,v) strays ~1e-3 outside [0,1] at face edges.
layout(std430, binding = SUBDFIT_SSBO_FACE_NODES) readonly buffer FaceNodes { int faceNodes[]; };

uniform int uMapResolution;

struct MapFootprint {
    ivec4 nodes;   // (i,j), (i+1,j), (i,j+1), (i+1,j+1)
    vec4 weights;
    vec2 fraction; // position inside the cell, for derivatives
};

MapFootprint mapFootprint(int face, vec2 uv) {
    int n = uMapResolution;
    vec2 x = clamp(uv, 0.0, 1.0) * float(n);
    ivec2 cell = min(ivec2(x), ivec2(n - 1));
    vec2 f = x - vec2(cell);
    int base = face * (n + 1) * (n + 1) + cell.y * (n + 1) + cell.x;
    MapFootprint m;
    m.nodes = ivec4(faceNodes[base], faceNodes[base + 1], faceNodes[base + n + 1], faceNodes[base + n + 2]);
    m.weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    m.fraction = f;
    return m;
}
