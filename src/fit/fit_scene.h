#pragma once
// What every fit works on, built the same way by `subdfit fit`, `subdfit simplify` and the
// viewer: the cage and the reference in the normalised frame of the reference, the reference's
// renderer, and the training and held-out target images. Needs a current GL context.
#include <memory>

#include "fit/cage_fitter.h"
#include "fit/fit_options.h"
#include "fit/fit_report.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"
#include "scene/target_set.h"

namespace subdfit::fit {

// The views that choose and judge what ships (`choosing`, `holdout`) are drawn as a viewer shows
// them: 4 × 4 samples a pixel, box-filtered (scene/target_set.h); a choice made on single samples
// favours what aliases as the targets do. The fit itself compares single samples, whose ids its
// gradient needs.
inline constexpr int kViewerSupersampling = 4;

class FitScene {
public:
    // Loads options.cage and options.reference. Throws subdfit::Error "path: problem".
    FitScene(const ResolvedFitOptions& options, gl::ProgramCache& programs);
    // From meshes already in memory (world units; the reference need not be triangulated).
    FitScene(const ResolvedFitOptions& options, gl::ProgramCache& programs, mesh::PolygonMesh cageWorld,
             const mesh::PolygonMesh& referenceWorld);

    // Another cage (world units) on the same reference and targets: `simplify` renders its
    // targets once and then tries several cages.
    void setCage(mesh::PolygonMesh cageWorld);

    scene::SceneFrame frame;       // around the reference
    render::ShadingModel shading;  // options.shading, "auto" resolved from the reference
    mesh::PolygonMesh cageWorld;   // as given, for writing results back with its tags and order
    mesh::PolygonMesh cage;        // normalised
    mesh::PolygonMesh reference;   // normalised, triangulated
    render::MeshRenderer referenceRenderer;
    scene::TargetSet training;
    // Another rotation of the view lattice, so no held-out view coincides with a training view;
    // supersampled (kViewerSupersampling).
    scene::TargetSet holdout;
    // A third, for the step schedule (fit/step_schedule.h): when the fit decides on its own
    // progress, it must not look at the views it is judged on. Single samples, as it fits.
    scene::TargetSet monitor;
    // The monitor's cameras supersampled, as a viewer shows them: what simplify chooses on (the
    // budget search's candidates, the triangle route's encodings, whether a cage is fitted).
    // Drawn on first use: a fit alone never asks for them.
    const scene::TargetSet& choosing(gl::ProgramCache& programs) const;

private:
    struct Checked {};
    mutable std::unique_ptr<scene::TargetSet> choosing_;
    FitScene(const FitOptions& options, gl::ProgramCache& programs, mesh::PolygonMesh cageWorld,
             const mesh::PolygonMesh& referenceWorld, Checked);
};

// The fitter settings `options` ask for on `cage` (normalised frame) under `shading`: the vertex
// ε and learning rate are turned from fractions of its mean edge into scene units, and a scene
// with materials gets the appearance maps its shading reads.
CageFitSettings fitSettings(const FitOptions& options, const mesh::PolygonMesh& cage,
                            render::ShadingModel shading = render::ShadingModel::Geometry);

// Segments per face edge that draw `cage` (normalised frame) at `resolution` with its mean edge
// cut into pieces of at most `pixels` pixels (at least 1).
int screenSegments(const mesh::PolygonMesh& cage, int resolution, float pixels);

// The options that ask for the vertex ε and learning rate `vertices` holds (fitSettings's inverse:
// options count them in fractions of `cage`'s mean edge, the group in scene units), e.g. after
// someone set them by hand. One that fitSettings(options, cage) already gives stays as given,
// so a value clamped to its pixel cap does not turn into another fraction.
FitOptions withVertexRates(FitOptions options, const mesh::PolygonMesh& cage, const optim::GroupSettings& vertices);

// How a fit of `reference` shades (--shading, or what its materials call for), and the maps it
// then has: those of --maps, and with a material the appearance maps that shading reads.
render::ShadingModel shadingOf(const FitOptions& options, const mesh::PolygonMesh& reference);
maps::MapEffects mapEffectsOf(const FitOptions& options, render::ShadingModel shading);

// Mean loss and PSNR of whatever `draw` draws over every view of `targets` (no SSIM: what a
// choice between candidates reads), and of the fitter's current scene.
ViewSetScore score(const scene::TargetSet& targets, const scene::TargetSet::Draw& draw);
ViewSetScore score(CageFitter& fitter, const scene::TargetSet& targets);

// The held-out score of whatever `draw` draws over every view of `holdout`, drawn as its targets
// were (supersampled when they are).
HoldoutScore scoreHoldout(const scene::TargetSet& holdout, const scene::TargetSet::Draw& draw);
HoldoutScore scoreHoldout(CageFitter& fitter, const scene::TargetSet& holdout);

}  // namespace subdfit::fit
