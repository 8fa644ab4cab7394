// Binding points shared by the C++ core (src/) and every shader: defined once, here.
#ifndef SUBDFIT_BINDINGS_H
#define SUBDFIT_BINDINGS_H

// Parameter group "vertices": control-vertex positions, 3 floats per base vertex.
#define SUBDFIT_SSBO_THETA 0            // θ
#define SUBDFIT_SSBO_THETA_PLUS 1       // θ + s⊙ε
#define SUBDFIT_SSBO_THETA_MINUS 2      // θ − s⊙ε
#define SUBDFIT_SSBO_GRADIENT 3         // g (float), resolved from the sums of G
#define SUBDFIT_SSBO_MOMENT1 4          // Adam m
#define SUBDFIT_SSBO_MOMENT2 5          // Adam v
#define SUBDFIT_SSBO_GRADIENT_SMOOTH 6  // preconditioned gradient (ping-pong partner of g)
// Adam v shared by a whole group (shared_moment.comp). Shares θ+'s binding point: the update
// passes never read θ±.
#define SUBDFIT_SSBO_GROUP_MOMENT2 SUBDFIT_SSBO_THETA_PLUS

// Subdivision tables (subdiv::PatchSet).
#define SUBDFIT_SSBO_STENCIL_OFFSETS 8
#define SUBDFIT_SSBO_POINTS 11         // base + refined + local points, 3 floats each
#define SUBDFIT_SSBO_SECOND_POINTS 39  // a second set evaluated in the same dispatch (θ− beside θ+)
// The patches tessellated (render::PatchTessellation): each vertex's patch and domain point, the
// vertices evaluated there (position, normal, tangents, ptex face and (u, v)) and the triangles
// the quads between them are split into.
#define SUBDFIT_SSBO_TESSELLATION_SAMPLES 40
#define SUBDFIT_SSBO_SURFACE_VERTICES 41
#define SUBDFIT_SSBO_SURFACE_TRIANGLES 43
// A second surface evaluated beside the first (θ− beside θ+): its vertices and triangles.
#define SUBDFIT_SSBO_SECOND_SURFACE_VERTICES 42
#define SUBDFIT_SSBO_SECOND_SURFACE_TRIANGLES 44
#define SUBDFIT_SSBO_ADJACENCY_OFFSETS 16  // cage vertex -> neighbours (CSR)
#define SUBDFIT_SSBO_ADJACENCY_INDICES 17
#define SUBDFIT_SSBO_LOSS 18  // 256 float slots whose sum is the mean per-pixel loss
// A scored view's loss summed per work group (scene::TargetSet::loss); never beside the SGE pass.
#define SUBDFIT_SSBO_VIEW_LOSS SUBDFIT_SSBO_LOSS
#define SUBDFIT_SSBO_SMOOTH_IN 19     // Jacobi iterate read by the preconditioner
#define SUBDFIT_SSBO_FACE_DELTA 20    // Σ Δ_p/(2ε) per ptex face, then per pair of them (fixed point)
#define SUBDFIT_SSBO_VERTEX_DELTA 46  // per base vertex, the sums of FACE_DELTA it is in (fixed point)

// Map parameter groups (per-face tiles of (T+1)² shared nodes, maps::TexelLayout).
#define SUBDFIT_SSBO_DISPLACEMENT 24           // height per node (θ, θ+ or θ− as the pass needs)
#define SUBDFIT_SSBO_GRADIENT_DISPLACEMENT 26  // the map groups' sums of G (fixed point)
#define SUBDFIT_SSBO_GRADIENT_NORMAL_MAP 27

// Any group's fixed-point gradient sums (glsl/fixed_point.glsl), two uints per parameter.
#define SUBDFIT_SSBO_GRADIENT_SUM 28

// The cage's tangential relaxation (fit/cage_relaxation.h).
#define SUBDFIT_SSBO_RELAX_MODES 29           // per vertex: surface, crease or fixed
#define SUBDFIT_SSBO_RELAX_CORNER_OFFSETS 30  // vertex -> its face corners (CSR)
#define SUBDFIT_SSBO_RELAX_CORNERS 31         // (previous, next) vertex of each corner
// Where each vertex sat among its neighbours in the start cage (low-passed), 3 floats per vertex.
// Shares g's binding point: the relaxation runs after Adam, which has consumed g.
#define SUBDFIT_SSBO_RELAX_REST SUBDFIT_SSBO_GRADIENT

// Image units of the gradient pass (the renders' colours carry their face ids as alpha), read
// with imageLoad, which costs llvmpipe less than texelFetch (docs/measurements.md).
#define SUBDFIT_IMAGE_COLOR_PLUS 1
#define SUBDFIT_IMAGE_COLOR_MINUS 2
#define SUBDFIT_IMAGE_TARGET 3
#define SUBDFIT_IMAGE_UV_PLUS 4
#define SUBDFIT_IMAGE_UV_MINUS 5
// A target set's supersampled render and the image it is filtered into (scene::TargetSet).
#define SUBDFIT_IMAGE_FINE 6
#define SUBDFIT_IMAGE_FILTERED 7
// Texture units of the gradient pass.
#define SUBDFIT_UNIT_PAIR_REGIONS 26  // ptex face a -> (first slot, log2 slot count) of its pairs' hash
#define SUBDFIT_UNIT_PAIR_SLOTS 27    // (b, pair index) per slot, b = −1 where empty

// The preconditioner's reads (optim::precondition): g, the iterate a sweep starts from (a texel a
// graph node, its channels) and the graph (CSR).
#define SUBDFIT_UNIT_JACOBI_GRADIENT 28
#define SUBDFIT_UNIT_JACOBI_IN 29
#define SUBDFIT_UNIT_ADJACENCY_OFFSETS 30
#define SUBDFIT_UNIT_ADJACENCY_INDICES 31

// The tables that hand G's sums on (scatter_sums.comp): ptex face -> its base vertices (CSR), and
// each pair's two faces.
#define SUBDFIT_UNIT_FACE_VERTEX_OFFSETS 32
#define SUBDFIT_UNIT_FACE_VERTICES 33
#define SUBDFIT_UNIT_PAIR_FACES 34

// The map lattices' face tables, [ptex face][j][i] -> node (maps.glsl), and with an appearance
// atlas (surface/appearance_atlas.h) each ptex face's 4 corners' atlas coordinates.
#define SUBDFIT_UNIT_FACE_NODES 35
#define SUBDFIT_UNIT_APPEARANCE_UVS 36

// Texture units of a reference's material (render/mesh_renderer.h).
#define SUBDFIT_UNIT_BASE_COLOR 8
#define SUBDFIT_UNIT_METALLIC_ROUGHNESS 9
#define SUBDFIT_UNIT_NORMAL 10
#define SUBDFIT_UNIT_OCCLUSION 11
#define SUBDFIT_UNIT_EMISSIVE 12

// The heights laid out one tile per ptex face for the surface pass (render/height_tiles.h): written
// as an image, read as a texture.
#define SUBDFIT_IMAGE_HEIGHT_TILES 0
#define SUBDFIT_UNIT_HEIGHT_TILES 13

// The stencils' control points (θ, or θ+ and θ−), read as buffer textures (render/stencil_evaluator.h).
#define SUBDFIT_UNIT_STENCIL_SOURCE 14
#define SUBDFIT_UNIT_STENCIL_SECOND_SOURCE 15
#define SUBDFIT_UNIT_STENCIL_ENTRIES 16  // (source index, weight's bits) per stencil entry
// The patches' points, read by the surface pass as a buffer texture (render/patch_renderer.h).
#define SUBDFIT_UNIT_PATCH_POINTS 17
#define SUBDFIT_UNIT_PATCH_INFO 18           // ivec4 {cv offset, patch type, param0, param1} per patch
#define SUBDFIT_UNIT_PATCH_CVS 19            // the patches' control point indices, four a texel
#define SUBDFIT_UNIT_PATCH_SECOND_POINTS 40  // a second set's (θ− beside θ+)
// The split's reads (glsl/triangulate.comp): each quad's corners, and the evaluated vertices
// (a record of four RGBA32F texels, its position first).
#define SUBDFIT_UNIT_TESSELLATION_QUADS 37
#define SUBDFIT_UNIT_SURFACE_VERTICES 38
#define SUBDFIT_UNIT_SECOND_SURFACE_VERTICES 41  // a second surface's, split beside the first's
#define SUBDFIT_UNIT_LIMIT_VERTICES 39           // a kept limit surface's vertices, displaced (glsl/displace.comp)

// The map values the patch pass shades with, one texel per node (maps::MapParameters): the
// normal map's tangent-space (x, y); on the appearance lattice sRGB base colour and (roughness,
// metallic); and the reference's textures carried there unchanged (SurfaceMaps): with an atlas
// its normal texture, and its occlusion and emission.
#define SUBDFIT_UNIT_MAP_NORMAL 20
#define SUBDFIT_UNIT_MAP_BASE_COLOR 21
#define SUBDFIT_UNIT_MAP_METALLIC_ROUGHNESS 22
#define SUBDFIT_UNIT_CARRIED_ATLAS_NORMAL 23
#define SUBDFIT_UNIT_CARRIED_OCCLUSION 24
#define SUBDFIT_UNIT_CARRIED_EMISSIVE 25

// Render target attachments.
#define SUBDFIT_ATTACHMENT_COLOR 0
#define SUBDFIT_ATTACHMENT_FACE_ID 1
#define SUBDFIT_ATTACHMENT_PATCH_UV 2

#endif
