#pragma once
// The appearance maps in the reference's own texture space. A textured asset's UV atlas is
// coherent and smooth, so its textures, downscaled, are what the triangle baselines ship; per-face
// tiles of colour code the same content far less compactly. With an atlas, each ptex face
// carries the atlas coordinates of its four corners, the appearance at ptex (u, v) is the
// texture at their bilinear blend, and the appearance "lattice" is the texture's texel grid: one
// node per texel, at the texel's centre.
#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

#include "surface/texel_layout.h"

namespace subdfit::surface {

// The largest atlas: texels per side of its square texture. The one limit the options, the
// .subd reader (codec/atlas_uv_coding.h) and the lattice below all check.
inline constexpr int kMaxAtlasSize = 2048;

struct AppearanceAtlas {
    int size = 0;  // texels per side of the square texture; 0: no atlas (the appearance is on tiles)
    // 4 per ptex face, at ptex (0, 0), (1, 0), (1, 1), (0, 1): glTF texture coordinates (v down
    // the image).
    std::vector<glm::vec2> cornerUvs;

    bool present() const { return size > 0; }
};

// The texel grid of a size × size texture as a TexelLayout: one tile (ptex face 0) of size − 1
// cells whose node (i, j) is texel (i, j) (row j from the top) and value index j·size + i; no
// halo. nodeAdjacency and the per-tile code work on it unchanged.
TexelLayout atlasLattice(int size);

// The point where corner `corner` of ptex face `face` lies ((0, 0), (1, 0), (1, 1), (0, 1), the
// order of cornerUvs) as a node of `corners` = buildTexelLayout(cage, 1): corners that meet
// share it.
int cornerPoint(const TexelLayout& corners, int face, int corner);

// The atlas coordinates of ptex (u, v) on `face`: the bilinear blend of its corners' ((u, v)
// clamped to the face, as the renderer's).
glm::vec2 atlasUvAt(const AppearanceAtlas& atlas, int face, float u, float v);

// How those coordinates change along the face's u and v at (u, v): the columns of the bilinear
// blend's Jacobian (glsl/maps.glsl's atlasUvJacobian).
glm::mat2 atlasUvJacobian(const AppearanceAtlas& atlas, int face, float u, float v);

// glTF's TANGENT for a normal texture in the atlas's coordinates at a surface point with unit
// `normal` and derivatives dPdu, dPdv along the ptex face: xyz along ∂P/∂s (where the surface goes
// as s grows, t held) in the tangent plane, w = ±1 so that cross(normal, xyz) · w points up the
// image (against ∂P/∂t): MikkTSpace's convention, which authored tangents follow, so a viewer
// shades the carried normal texture as on the reference.
// (glsl/patch.frag shades it in the cotangent frame of the gradients of s and t, as it shades the
// reference: the same where the atlas is conformal.) `fallback` where the coordinates do not
// vary over the surface.
glm::vec4 atlasTangent(glm::vec3 normal, glm::vec3 dPdu, glm::vec3 dPdv, const glm::mat2& jacobian, glm::vec4 fallback);

// Where atlas coordinates fall on atlasLattice(size) as its tile's (u, v): texel centres sit at
// (i + ½) / size, and the texture is clamped to its edge texels (glTF CLAMP_TO_EDGE).
glm::vec2 latticeUv(int size, glm::vec2 atlasUv);

}  // namespace subdfit::surface
