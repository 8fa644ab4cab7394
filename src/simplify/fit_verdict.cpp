#include "simplify/fit_verdict.h"

#include "simplify/bake/bake.h"

namespace subdfit::simplify {
namespace {

bool sameParameters(const fit::FitState& a, const fit::FitState& b) {
    if (a.groups.size() != b.groups.size()) return false;
    for (size_t k = 0; k < a.groups.size(); ++k)
        if (a.groups[k].theta != b.groups[k].theta) return false;
    return true;
}

// The bake: the scene's initial cage, `baked` its maps.
void hold(fit::CageFitter& fitter, const fit::FitScene& scene, const surface::SurfaceMaps& baked) {
    fitter.setVertices(scene.cage.positions);
    fit::writeMaps(fitter, baked);
}

surface::SurfaceMaps bakedMaps(fit::FitRun& run) {
    fit::CageFitter& fitter = run.fitter();
    return fitter.maps() ? bakeFor(run.scene().cage, run.scene().reference, *fitter.maps()) : surface::SurfaceMaps{};
}

}  // namespace

void holdTheBake(fit::FitRun& run) { hold(run.fitter(), run.scene(), bakedMaps(run)); }

// The fit's schedule reads single-sample views, and what looks better there can look worse as a
// viewer draws it (the glTF Duck at 10 KB: its atlas fitted, the monitor's loss down 13 %, held
// out 42.55 → 40.82 dB), so the verdict is the choosing views'.
FitVerdict keepTheFitWhereItPays(fit::FitRun& run, gl::ProgramCache& programs) {
    fit::CageFitter& fitter = run.fitter();
    const fit::FitScene& scene = run.scene();
    const fit::CageFitter::State fitted = fitter.state();
    // What θ does not hold: an atlas's corners and the textures carried unfitted.
    const surface::SurfaceMaps fittedMaps = fitter.surfaceMaps();
    const surface::SurfaceMaps baked = bakedMaps(run);
    hold(fitter, scene, baked);
    if (sameParameters(fitter.state(), fitted)) return {.fitShips = false, .fitMoved = false};

    const scene::TargetSet& choosing = scene.choosing(programs);
    FitVerdict verdict{.bakedLoss = fit::score(fitter, choosing).loss};
    fit::writeMaps(fitter, fittedMaps);
    fitter.restore(fitted);  // θ as fitted (writeMaps clamps the colours)
    verdict.fittedLoss = fit::score(fitter, choosing).loss;
    verdict.fitShips = verdict.fittedLoss < verdict.bakedLoss;
    if (!verdict.fitShips) hold(fitter, scene, baked);
    return verdict;
}

}  // namespace subdfit::simplify
