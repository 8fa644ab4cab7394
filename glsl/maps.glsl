// Bilinear lookup in a per-face node tile (surface::TexelLayout): ptex (u,v) of `face` falls in
// cell (i, j) of T×T; the four corner nodes and their weights. Clamped, because rasterised
// (u,v) strays ~1e-3 outside [0,1] at face edges. The geometric maps (displacement, normal) and
// the appearance maps (base colour, metallic-roughness) have lattices of their own, whose face
// tables sit one after the other in one buffer, read as a buffer texture (a gather, where
// llvmpipe reads storage lane after lane).
layout(binding = SUBDFIT_UNIT_FACE_NODES) uniform isamplerBuffer faceNodes;

int faceNode(int index) { return texelFetch(faceNodes, index).x; }

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
    m.nodes = ivec4(faceNode(base), faceNode(base + 1), faceNode(base + n + 1), faceNode(base + n + 2));
    m.weights = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    m.fraction = f;
    return m;
}

#ifdef SUBDFIT_APPEARANCE_ATLAS
// The appearance in the reference's texture space (surface/appearance_atlas.h): ptex (u, v) of
// `face` -> the bilinear blend of its corners' atlas coordinates t -> the texel grid, a one-tile
// lattice of n = size − 1 cells whose nodes are the texel centres (i + ½) / size, clamped to the
// edge texels as glTF's CLAMP_TO_EDGE.
layout(binding = SUBDFIT_UNIT_APPEARANCE_UVS) uniform samplerBuffer appearanceUvs;  // 4 corners a ptex face

// The atlas coordinates of `face`'s corners.
mat4x2 atlasCorners(int face) {
    int k = 4 * face;
    return mat4x2(texelFetch(appearanceUvs, k).xy, texelFetch(appearanceUvs, k + 1).xy, texelFetch(appearanceUvs, k + 2).xy,
                  texelFetch(appearanceUvs, k + 3).xy);
}

vec2 atlasUv(int face, vec2 uv) {
    vec2 c = clamp(uv, 0.0, 1.0);
    mat4x2 t = atlasCorners(face);
    return mix(mix(t[0], t[1], c.x), mix(t[3], t[2], c.x), c.y);
}

// How the atlas coordinates change along the ptex face's u and v at (u, v): the columns of the
// bilinear blend's Jacobian.
mat2 atlasUvJacobian(int face, vec2 uv) {
    vec2 c = clamp(uv, 0.0, 1.0);
    mat4x2 t = atlasCorners(face);
    return mat2(mix(t[1] - t[0], t[2] - t[3], c.y), mix(t[3] - t[0], t[2] - t[1], c.x));
}

MapFootprint atlasFootprint(int face, vec2 uv, int n, int table) {
    return footprint(0, (atlasUv(face, uv) * float(n + 1) - 0.5) / float(n), n, table);
}
#endif

MapFootprint mapFootprint(int face, vec2 uv) { return footprint(face, uv, uMapResolution, 0); }
MapFootprint appearanceFootprint(int face, vec2 uv) {
#ifdef SUBDFIT_APPEARANCE_ATLAS
    return atlasFootprint(face, uv, uAppearanceResolution, uAppearanceTable);
#else
    return footprint(face, uv, uAppearanceResolution, uAppearanceTable);
#endif
}
