// The displacement's heights laid out for the surface pass, one thread per texel: ptex face f's
// tile holds its nodes (i, j) for i, j in [-1, T + 1], node (i, j) at texel (i + 1, j + 1). The
// ring outside [0, T] is the neighbouring tile's node across that edge, or (no neighbour) the
// border cell's slope extended, as surface::nodeValueAcross; the ring's corners are never read.
// Done once per heights, this spares every vertex the node table and its branches, 20 nodes each.
#include "bindings.h"
#include "maps.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SUBDFIT_SSBO_DISPLACEMENT) readonly buffer Displacement { float displacement[]; };
layout(r32f, binding = SUBDFIT_IMAGE_HEIGHT_TILES) uniform writeonly image2D heightTiles;

uniform int uMapHaloTable;  // where the ring of nodes around each tile starts among the face nodes
uniform int uTilesPerRow;
uniform int uFaceCount;

// The height at node (i, j) of `face`'s tile, one of i, j possibly one step outside it: the
// neighbouring tile's node across that edge, or (no neighbour) the border cell's slope extended.
// As surface::nodeValueAcross.
float heightNode(int face, int i, int j) {
    int n = uMapResolution;
    int edge = j < 0 ? 0 : i > n ? 1 : j > n ? 2 : i < 0 ? 3 : -1;
    if (edge < 0) return displacement[faceNode(face * (n + 1) * (n + 1) + j * (n + 1) + i)];
    int across = faceNode(uMapHaloTable + (face * 4 + edge) * (n + 1) + ((edge & 1) == 0 ? i : j));
    if (across >= 0) return displacement[across];
    ivec2 border = clamp(ivec2(i, j), ivec2(0), ivec2(n)), inner = 2 * border - ivec2(i, j);
    return 2.0 * displacement[faceNode(face * (n + 1) * (n + 1) + border.y * (n + 1) + border.x)] -
           displacement[faceNode(face * (n + 1) * (n + 1) + inner.y * (n + 1) + inner.x)];
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    int n = uMapResolution;
    ivec2 tile = texel / (n + 3);
    int face = tile.y * uTilesPerRow + tile.x;
    if (tile.x >= uTilesPerRow || face >= uFaceCount) return;
    ivec2 node = texel - tile * (n + 3) - 1;
    bool corner = (node.x < 0 || node.x > n) && (node.y < 0 || node.y > n);
    imageStore(heightTiles, texel, vec4(corner ? 0.0 : heightNode(face, node.x, node.y)));
}
