#pragma once
// The appearance baked into the reference's own texture atlas (surface/appearance_atlas.h): the
// texels are the reference's textures downscaled, as the triangle baselines ship them; each ptex
// face of the cage gets the atlas coordinates of its corners (simplify/bake/atlas_corners.h).
#include <string>

#include "maps/map_effects.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {

// Why `reference` cannot keep its appearance in its atlas (one material whose base colour or
// metallic-roughness is textured through TEXCOORD_0 without a transform, coordinates inside the
// texture, no vertex colours), or "" when it can.
std::string atlasUnsuitability(const mesh::PolygonMesh& reference);

// What of the reference's look its materials (those its faces use) have beyond colours.
struct CarriedLook {
    bool normalTexture = false, occlusion = false, emission = false;
};
CarriedLook carriedLookOf(const mesh::PolygonMesh& reference);

// What of the reference's look an appearance on per-face tiles leaves out, for a warning: its
// normal texture (in its atlas's frame, which tiles do not have) and, without a metallic-roughness
// map to ship it in, its occlusion. "" when nothing is left out.
std::string lostOnTiles(const mesh::PolygonMesh& reference, bool metallicRoughness);

// The texels per side of the reference's largest appearance texture (0: none).
int atlasSourceSize(const mesh::PolygonMesh& reference);

// `effects`' appearance maps on a size × size atlas (size >= 2) and the corner coordinates of
// every ptex face of `cage` (both meshes in the same units). The reference must be suitable.
// With `shadingNormals`, the normal texture (the reference's, or a flat one where it has none)
// also turns the cage's limit normals into the reference's (simplify/bake/atlas_shading_normals.h).
surface::SurfaceMaps bakeAtlasAppearance(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                         maps::MapEffects effects, int size, float maxDistance = 0.0f,
                                         bool shadingNormals = false);

}  // namespace subdfit::simplify
