#pragma once
// The classic bake route, the baseline `simplify` is judged against: displacement and normal
// maps ray-cast from the reference onto the limit surface of a cage, with no optimisation.
// Each map node casts along the limit normal both ways; the nearer hit gives its height, and
// the reference's interpolated normal there, expressed in the displaced surface's tangent frame
// (the frame the renderer and the exported TANGENT use), gives its normal-map value.
#include "surface/surface_maps.h"
#include "maps/map_parameters.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

struct BakeOptions {
    maps::MapEffects effects{maps::MapKind::Displacement, maps::MapKind::NormalMap};
    int resolution = 8;  // cells per ptex-face edge, as surface::TexelLayout
    // Farthest hit taken, in the meshes' units (none: height 0, flat normal); 0 = the cage's
    // mean edge length, since a surface farther than a cage edge is a different part of the
    // reference (the far wall of a hole, the other ear), not the one this face stands for.
    float maxDistance = 0.0f;
    // Heights fitted so that the bilinear map lies on the reference across each cell (node and
    // cell-centre rays, least squares) rather than point-sampled at the nodes.
    bool leastSquaresHeights = true;
};

// `cage` and `reference` (triangulated) in the same units. Only the maps in options.effects
// are filled; the layout is surface::buildTexelLayout(cage, resolution).
surface::SurfaceMaps bakeMaps(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                              const BakeOptions& options);

struct AppearanceBakeOptions {
    maps::MapEffects effects{maps::MapKind::BaseColor, maps::MapKind::MetallicRoughness};
    int resolution = 16;       // cells per ptex-face edge of the appearance lattice
    float maxDistance = 0.0f;  // as BakeOptions
    // Texels per side of an atlas in the reference's own texture space instead of tiles
    // (simplify/bake/atlas_bake.h; the reference must be suitable); 0: tiles.
    int atlas = 0;
    // Tiles: node values fitted so that the lattice matches the material across each cell (the
    // nodes' samples and 2 × 2 more a cell, least squares) rather than point-sampled at the nodes.
    bool acrossCells = true;
    // With an atlas: its normal texture also carries the reference's shading normals
    // (bakeAtlasAppearance). Off by default: it costs bytes and has not paid for them in the
    // budget search (docs/measurements.md).
    bool shadingNormals = false;
};

// The appearance maps (SurfaceMaps::appearanceLayout, baseColor, metallicRoughness) of `cage`:
// each node takes the reference's material where its limit normal meets the reference (the
// texture at the hit's interpolated texture coordinates, times the factors and vertex colours);
// nodes whose rays miss take their neighbours' mean. With options.atlas, bakeAtlasAppearance.
surface::SurfaceMaps bakeAppearance(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                    const AppearanceBakeOptions& options);

// How `parameters`' appearance is baked: onto its lattice, or into its atlas.
AppearanceBakeOptions appearanceBakeOf(const maps::MapParameters& parameters);

// Every map `parameters` has, baked onto `cage` at its layouts: what the bake route ships for
// that cage, and where a fit of it starts.
surface::SurfaceMaps bakeFor(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                             const maps::MapParameters& parameters);

}  // namespace subdfit::simplify
