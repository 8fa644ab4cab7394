#pragma once
// A shipped asset.subd drawn as a consumer's decoder gets it: the decoded cage's limit surface
// with its maps, tessellated on the GPU by the fitter's own renderer, which is the pass simplify
// scores subdfit and the bake route with, and the surface `subdfit decode` writes as triangles.
#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "render/shading_model.h"
#include "scene/scene_frame.h"

namespace subdfit::fit {

// The shading an asset calls for on its own (no reference to ask): its appearance maps'.
render::ShadingModel shadingOf(const surface::SurfaceMaps& maps);

// `maps` (world units, as readSubd gives them) in `frame`: the heights scaled with the cage.
surface::SurfaceMaps normalizedMaps(surface::SurfaceMaps maps, const scene::SceneFrame& frame);

// The fitter settings that draw `maps` as they ship: their effects, lattices and shading normal.
// `shading` decides which appearance maps are drawn (as a fit under it would have them).
CageFitSettings drawingSettings(const surface::SurfaceMaps& maps, render::ShadingModel shading, int tessLevel);

class ShippedAsset {
public:
    // `asset` in world units, drawn in `frame` at `tessLevel` segments per base-face edge (the
    // renderer's crack-free level at least). Needs a current GL context; `programs` must outlive
    // the object.
    ShippedAsset(gl::ProgramCache& programs, const codec::SubdAsset& asset, const scene::SceneFrame& frame,
                 render::ShadingModel shading, int tessLevel);

    void draw(const render::Camera& camera, const render::RenderTarget& target) { fitter_->render(camera, target); }
    // Rebuilt at another level.
    void setTessLevel(int level);

    // Its renderer, maps and control vertices (the cage's θ), read-only in spirit.
    CageFitter& fitter() { return *fitter_; }
    const mesh::PolygonMesh& cage() const { return cage_; }     // in the frame
    const surface::SurfaceMaps& maps() const { return maps_; }  // in the frame

private:
    void build(int tessLevel);

    gl::ProgramCache& programs_;
    mesh::PolygonMesh cage_;
    surface::SurfaceMaps maps_;
    render::ShadingModel shading_;
    std::unique_ptr<CageFitter> fitter_;
};

}  // namespace subdfit::fit
