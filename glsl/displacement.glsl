// A surface point displaced along its normal by the heights (maps.glsl's uMapResolution: T of the
// geometric maps): glsl/tessellate.comp at once, glsl/displace.comp from a kept limit surface.
#ifndef SUBDFIT_DISPLACEMENT_GLSL
#define SUBDFIT_DISPLACEMENT_GLSL
#include "surface_vertex.glsl"

// The heights, one tile of (T + 3)² texels per ptex face: its nodes and the ring across its edges
// (glsl/height_tiles.comp), node (i, j) at texel (i + 1, j + 1) of the tile.
layout(binding = SUBDFIT_UNIT_HEIGHT_TILES) uniform sampler2D heightTiles;
uniform int uTilesPerRow;

// Bilinear, with at most one of u, v up to a cell outside [0, 1] (then in the cell between the
// tile's border and the ring across it).
float heightAt(int face, vec2 uv) {
    int n = uMapResolution;
    vec2 x = clamp(uv * float(n), vec2(-1.0), vec2(float(n + 1)));
    ivec2 cell = ivec2(x.x < 0.0 ? -1 : x.x >= float(n) ? n : min(int(x.x), n - 1),
                       x.y < 0.0 ? -1 : x.y >= float(n) ? n : min(int(x.y), n - 1));
    vec2 f = x - vec2(cell);
    ivec2 node = ivec2(face % uTilesPerRow, face / uTilesPerRow) * (n + 3) + 1 + cell;
    return mix(mix(texelFetch(heightTiles, node, 0).r, texelFetch(heightTiles, node + ivec2(1, 0), 0).r, f.x),
               mix(texelFetch(heightTiles, node + ivec2(0, 1), 0).r, texelFetch(heightTiles, node + ivec2(1, 1), 0).r, f.x),
               f.y);
}

// The height d at a point of a face, and its slopes (∂d/∂u, ∂d/∂v) by central differences half a
// map cell wide, reaching across the tile's border into the neighbouring face's tile, exactly as
// the CPU twin (surface/displaced_surface.cpp): at a node that averages the slopes of the cells
// on either side, so the shading breaks neither at a cell edge nor at a face edge.
struct HeightSample {
    float height;
    vec2 slope;
};

HeightSample heightSample(int face, vec2 uv) {
    vec2 at = clamp(uv, 0.0, 1.0);
    HeightSample d;
    d.height = heightAt(face, at);
    d.slope = vec2(0.0);
#ifndef SUBDFIT_LIMIT_SHADING  // (with it, the limit surface's normal shades: surface::ShadingNormal)
    float h = 0.5 / float(uMapResolution);
    d.slope = vec2(heightAt(face, at + vec2(h, 0.0)) - heightAt(face, at - vec2(h, 0.0)),
                   heightAt(face, at + vec2(0.0, h)) - heightAt(face, at - vec2(0.0, h))) / (2.0 * h);
#endif
    return d;
}

// P' = P + d(u,v) N̂. Shading normal of the displaced surface to first order:
// ∂P'/∂u ≈ ∂P/∂u + (∂d/∂u) N̂ (the d ∂N̂/∂u term is dropped: d is small against curvature).
void displace(inout SurfacePoint p, HeightSample d) {
    vec3 unitN = p.normal;
    p.position += d.height * unitN;
#ifndef SUBDFIT_LIMIT_SHADING
    p.tangentU += d.slope.x * unitN;
    p.tangentV += d.slope.y * unitN;
    vec3 N = cross(p.tangentU, p.tangentV);
    p.normal = dot(N, N) > 0.0 ? normalize(N) : unitN;
#endif
}
#endif
