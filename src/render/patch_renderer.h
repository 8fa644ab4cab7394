#pragma once
// Draws a cage's limit surface in two passes: a compute pass evaluates the surface (from an SSBO
// of evaluated patch points, and the heights) at the vertices of a fixed tessellation of its
// patches (render/patch_tessellation.h); a raster pass draws those triangles. Writes colour,
// ptex face id and (u,v) (the face id as the colour's alpha into a target laid out so). One
// surface serves every view and every render that differs only in appearance. (Hardware
// tessellation, one GL patch per OpenSubdiv patch, cost llvmpipe ~2 µs of one thread per patch.)
#include <functional>
#include <optional>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "gl/vertex_array.h"
#include "kinds/map_kinds.h"
#include "render/camera.h"
#include "render/height_tiles.h"
#include "render/patch_tessellation.h"
#include "render/render_target.h"
#include "render/shading_model.h"
#include "subdiv/patch_set.h"

namespace subdfit::render {

// Per-texel maps the patch pass can apply (glsl/maps.glsl). Each effect is a bit of the pass's
// shader variant; whoever owns the maps binds their buffers.
struct PatchMaps {
    kinds::MapKinds kinds;         // the maps applied
    bool limitShading = false;     // the heights place the surface, the limit normal shades it
    int resolution = 1;            // cells per ptex-face edge of the geometric maps
    int appearanceResolution = 1;  // ... of the appearance maps
    bool appearanceAtlas = false;  // the appearance lattice is an atlas's texel grid
    bool atlasNormal = false;      // ... carrying the reference's normal texture
    bool carriedOcclusion = false, carriedEmissive = false;  // the appearance lattice carries these
    int appearanceTable = 0;                                 // where their lattice starts in the face-node table
    int haloTable = 0;           // where the geometric lattice's ring across tile edges starts
    std::function<void()> bind;  // the node table and the map values this pass reads
};

class PatchRenderer {
public:
    // `tessLevel`: segments per base-face edge, raised to a power of two that keeps adaptive
    // patches of every depth crack-free (callers with maps ask for at least the map resolution,
    // so that the detail of the maps is actually rasterised).
    PatchRenderer(const subdiv::PatchSet& patches, int tessLevel, ShadingModel shading = ShadingModel::Geometry);

    int tessLevel() const { return tessLevel_; }
    int patchCount() const { return patchCount_; }

    // The surface at the tessellation's vertices, and the triangles it is drawn with.
    struct Surface {
        gl::Buffer vertices, triangles;
    };
    Surface makeSurface() const;
    gl::Buffer makeVertices() const;
    // The surface of `points` (displaced by `maps`' heights, if it has them) into `surface`.
    void evaluate(gl::ProgramCache& programs, const gl::Buffer& points, const Surface& surface,
                  const PatchMaps* maps = nullptr) const;
    // Two surfaces at once, of `points` into `surface` and of `secondPoints` into `secondSurface`
    // with the same `maps` (θ+ and θ− of a vertex turn): one basis evaluated for both, half the
    // dispatches of two evaluate() calls, the same surfaces.
    void evaluatePair(gl::ProgramCache& programs, const gl::Buffer& points, const Surface& surface,
                      const gl::Buffer& secondPoints, const Surface& secondSurface,
                      const PatchMaps* maps = nullptr) const;
    // The same in two halves, for a cage that stays while its heights change: the limit surface
    // of `points` without heights, kept in `limitVertices` (a surface's vertices buffer), and
    // displaced by `maps`' heights into `surface` (the patches not evaluated again). The same
    // surface as evaluate() gives.
    void evaluateLimit(gl::ProgramCache& programs, const gl::Buffer& points, const gl::Buffer& limitVertices) const;
    void displace(gl::ProgramCache& programs, const gl::Buffer& limitVertices, const Surface& surface,
                  const PatchMaps& maps) const;
    // An evaluated surface rasterised; with `maps`, the variant with their effects.
    void rasterize(gl::ProgramCache& programs, const Surface& surface, const Camera& camera, const RenderTarget& target,
                   const PatchMaps* maps = nullptr) const;
    // Both, through a surface made for the call (a one-off render; a fit keeps its surfaces).
    void draw(gl::ProgramCache& programs, const gl::Buffer& points, const Camera& camera, const RenderTarget& target,
              const PatchMaps* maps = nullptr) const;

private:
    // A second set of points and the surface it goes to, evaluated beside the first.
    struct Second {
        const gl::Buffer& points;
        const Surface& surface;
    };
    // The tessellation's vertices of `points` into `vertices` (and `second`'s into its surface's),
    // displaced where `maps` has heights.
    void tessellate(gl::ProgramCache& programs, const gl::Buffer& points, const gl::Buffer& vertices,
                    const PatchMaps* maps, const Second* second = nullptr) const;
    // Binds `maps`' heights laid out for the surface passes.
    void layOutHeights(gl::ProgramCache& programs, const PatchMaps& maps) const;
    // Each quad of an evaluated surface (and of `second`'s) split along its shorter diagonal.
    void split(gl::ProgramCache& programs, const Surface& surface, const Surface* second = nullptr) const;

    int patchCount_, faceCount_, tessLevel_;
    ShadingModel shading_;
    std::vector<SampleRun> runs_;
    int vertexCount_, quadCount_;
    gl::Buffer patchInfo_, patchCvs_, samples_, quads_;
    gl::BufferTexture patchInfoTexture_, patchCvTexture_;  // as the surface pass reads them
    gl::BufferTexture quadsTexture_;                       // as the split reads them
    gl::VertexArray vertexArray_;
    // The surface passes' scratch: the heights they displace by, laid out for them.
    mutable std::optional<HeightTiles> heightTiles_;
};

// The smallest power of two >= max(requested, 2^maxPatchDepth), capped at the GL limit of 64.
int crackFreeTessLevel(int requested, int maxPatchDepth);

}  // namespace subdfit::render
