#pragma once
// The reference's shading normals carried to the cage through the texture atlas both share. A
// triangle asset shades with its authored NORMALs interpolated across each triangle (and its
// normal texture on top); the cage's smooth limit surface has normals of its own, and where they
// part (a bottle's shoulder, a cap's rim) its highlights fall elsewhere. Atlas coordinates name
// the same surface point on both, so the atlas's normal texture can say, texel by texel, how to
// turn the cage's normal into the reference's.
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {

// The frame in which a renderer without tangents applies a normal texture (glsl/mesh.frag's
// mappedNormal, a cotangent frame): columns (s ∇u, −s ∇v, N), with ∇u and ∇v the gradients of
// the texture coordinates in the plane normal to N and s = 1 / max(|∇u|, |∇v|), so a texel
// (x, y, z) shades with normalize(frame · (x, y, z)). From two tangents dp1, dp2 of the surface
// and the coordinates' changes duv1, duv2 along them; none where those do not span the plane.
std::optional<glm::mat3> normalTextureFrame(glm::vec3 dp1, glm::vec3 dp2, glm::vec2 duv1, glm::vec2 duv2,
                                            glm::vec3 normal);

// Rewrites `texels` (maps.appearanceAtlas.size² texels of a glTF normal texture, rgb in [0, 1]:
// the reference's own, or flat (½, ½, 1)) so that the cage's surface (with maps' displacement,
// if any) shades with the reference's normal wherever both lie at the same atlas coordinates
// within `maxDistance`: each texel t becomes frame_cage⁻¹ · frame_reference · t, averaged over
// a few points in the texel. Texels that no face of the cage reaches keep their value; returns
// which texels it rewrote.
std::vector<char> carryShadingNormals(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                                      const mesh::PolygonMesh& reference, float maxDistance,
                                      std::vector<float>& texels);

}  // namespace subdfit::simplify
