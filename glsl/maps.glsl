// Bilinear lookup in a per-face node tile (surface::TexelLayout): ptex (u,v) of `face` falls in
// cell (i, j) of T×T; the four corner nodes and their weights. Clamped, because rasterised
// (u,v) strays ~1e-3 outside [0,1] at face edges. The geometric maps (displacement, normal) and
// the appearance maps (base colour, metallic-roughness) have lattices of their own, whose face
// tables sit one after the other in one buffer.
layout(std430, binding = SUBDFIT_SSBO_FACE_NODES) readonly buffer FaceNodes { int faceNodes[]; };

uniform int uMapResolution;         // T of the geometric maps
uniform int uAppearanceResolution;  // T of the appearance maps
uniform int uAppearanceTable;       // where their face table starts in faceNodes

struct MapFootprint {
    ivec4 nodes;   // (i,j), (i+1,j), (i,j+1), (i+1,j+1)
    vec4 weights;
    vec2 fraction; // position inside the cell, for derivatives
};

MapFootprint footprint(int face, vec2 uv, int n, int table) {
    vec2 x = clamp(uv, 0.0, 1.0) * float(n);
    ivec2 cell = min(ivec2(x), ivec2(n - 1));
    vec2 f = x - vec2(cell);
    int base = table + face * (n + 1) * (n + 1) + cell.y * (n + 1) + cell.x;
    MapFootprint m;
    m.nodes = ivec4(faceNodes[base], faceNodes[base + 1], faceNodes[base + n + 1], faceNodes[base + n + 2]);
    m.weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    m.fraction = f;
    return m;
}

MapFootprint mapFootprint(int face, vec2 uv) { return footprint(face, uv, uMapResolution, 0); }
MapFootprint appearanceFootprint(int face, vec2 uv) {
    return footprint(face, uv, uAppearanceResolution, uAppearanceTable);
}
