#include "simplify/simplify_plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "simplify/bake/atlas_bake.h"
#include "simplify/cage/initial_cage.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {
namespace {

// The budget search's largest cage: a dense bare cage ships cheaply, and its limit surface can
// shade closer than heights on a coarse one, so the search must be able to reach one. Past
// subdiv::kDenseCageFaces a cage is drawn at a shallower isolation level, which keeps it affordable.
constexpr int kMostBudgetFaces = 16 * kDefaultFaces;
// Past this many faces the fit of a budget's cage takes proportionally fewer steps (unless
// --steps was given): the search's bake of a dense cage is already close, and --budget should
// cost about what a fit of this many faces does.
constexpr int kMostFullyFittedFaces = 2 * kDefaultFaces;
// The fewest faces a quad remesh is asked for (a remesh of a handful of quads is no cage).
constexpr int kFewestQuadFaces = 16;

// The bake route of a cage (normalised frame) with the run's own maps.
BakeRoute bakeRouteOf(const mesh::PolygonMesh& cage, const fit::FitOptions& fit) {
    return {.cage = cage,
            .effects = fit.maps,
            .resolution = fit.mapResolution,
            .bits = fit.mapBits,
            .positionBits = fit.positionBits,
            .appearanceResolution = fit.appearanceResolution,
            .appearanceQuality = fit.appearanceQuality,
            .appearanceAtlas = fit.appearanceAtlas,
            .shadingNormal = fit.shadingNormal};
}

}  // namespace

SimplifyPlan planByFaces(const SimplifyOptions& o, fit::FitOptions fitOptions, fit::FitScene& scene,
                         const mesh::PolygonMesh& reference) {
    scene.setCage(initialCage(reference, {.faces = o.faces.value_or(kDefaultFaces), .shape = o.cageShape}));
    BakeRoute route = bakeRouteOf(scene.cage, fitOptions);
    return {.fit = std::move(fitOptions), .bakeRoute = std::move(route), .budget = std::nullopt};
}

namespace {

// What the budget search tries for `o` on `scene`.
BudgetSearch budgetSearchFor(const SimplifyOptions& o, std::uintmax_t budget, const fit::FitScene& scene) {
    return {
        .budget = budget,
        .faceCounts = budgetFaceCounts(o, budget, scene),
        .mostGrownFaces =
            o.faces ? 0 : std::min(kMostBudgetFaces, scene.reference.faceCount()) / (quadDominant(o.cageShape) ? 2 : 1),
        .allowedMaps = o.fit.maps,
        .appearance = maps::appearanceFor(scene.shading),
        .appearanceQualities = {o.fit.appearanceQuality},
        .appearanceAtlases =
            o.fit.appearanceAtlas > 0 ? std::vector<int>{o.fit.appearanceAtlas} : atlasSizesFor(scene.reference),
        .quadTrial = o.cageShape == CageShape::Auto && !o.faces,
        .bestWithMaps = o.compare >= CompareLevel::Full};
}

// The search's choice into the fit's options: its maps, their resolution, bits and shading
// normal, its appearance; and for a dense cage fewer steps, unless --steps was given.
void applyChoice(const BudgetCandidate& chosen, int cageFaces, bool stepsByDevice, fit::FitOptions& fit) {
    fit.maps = chosen.maps;
    if (chosen.appearanceResolution > 0 || chosen.appearanceAtlas > 0) {
        if (chosen.appearanceResolution > 0) fit.appearanceResolution = chosen.appearanceResolution;
        fit.appearanceAtlas = chosen.appearanceAtlas;
        fit.appearanceQuality = chosen.appearanceQuality;
    }
    fit.positionBits = chosen.positionBits;
    if (chosen.mapResolution > 0) {
        fit.mapResolution = chosen.mapResolution;
        fit.mapBits = chosen.mapBits;
        fit.shadingNormal = chosen.shadingNormal;
        // The search judged this cage with maps baked onto it as it is: the fit refines that
        // from the start (moving the cage first would leave what was judged).
        fit.mapsStart = 0.0f;
    }
    if (stepsByDevice && cageFaces > kMostFullyFittedFaces)
        fit.steps = std::max(1, int(std::lround(double(fit.steps) * kMostFullyFittedFaces / cageFaces)));
}

// The bake route at the budget's bytes: the search's best candidate with maps, as it is; when
// none fits, the chosen cage with the cheapest maps the search tries (reported over budget),
// not the default maps at many times the bytes; with no maps allowed, the chosen cage with the
// run's own.
BakeRoute budgetBakeRoute(const BudgetChoice& choice, const BudgetSearch& search, const fit::FitOptions& fit,
                          const fit::FitScene& scene) {
    if (!choice.bestWithMaps && !search.allowedMaps.geometric()) return bakeRouteOf(scene.cage, fit);
    const BudgetCandidate route = choice.bestWithMaps ? *choice.bestWithMaps
                                                      : BudgetCandidate{.maps = search.allowedMaps,
                                                                        .mapResolution = search.mapResolutions.front(),
                                                                        .mapBits = search.mapBits.front()};
    mesh::PolygonMesh cage = choice.bestWithMaps ? choice.bestWithMapsCage : choice.cageWorld;
    cage.positions = scene.frame.toNormalized(cage.positions);
    const bool appearance = route.appearanceResolution > 0 || route.appearanceAtlas > 0;
    return {.cage = std::move(cage),
            .effects = route.maps,
            .resolution = route.mapResolution,
            .bits = route.mapBits,
            .positionBits = route.positionBits,
            .appearanceResolution = appearance ? route.appearanceResolution : fit.appearanceResolution,
            .appearanceQuality = appearance ? route.appearanceQuality : fit.appearanceQuality,
            .appearanceAtlas = appearance ? route.appearanceAtlas : fit.appearanceAtlas,
            .shadingNormal = route.shadingNormal};
}

}  // namespace

std::vector<int> budgetFaceCounts(const SimplifyOptions& o, std::uintmax_t budget, const fit::FitScene& scene) {
    if (o.faces) return {*o.faces};
    std::vector<int> counts = faceCountsFor(budget, scene.reference.faceCount(), kMostBudgetFaces);
    // A quad has a vertex to itself where a triangle has half of one: about twice the bytes.
    if (quadDominant(o.cageShape))
        for (int& faces : counts) faces = std::max(kFewestQuadFaces, faces / 2);
    return counts;
}

SimplifyPlan planWithinBudget(const SimplifyOptions& o, std::uintmax_t budget, double leastFittedMonitorPsnr,
                              fit::FitOptions fitOptions, gl::ProgramCache& programs, fit::FitScene& scene,
                              const mesh::PolygonMesh& reference, CageLadder& cages,
                              const std::function<void(const std::string&)>& say) {
    BudgetSearch search = budgetSearchFor(o, budget, scene);
    search.leastFittedMonitorPsnr = leastFittedMonitorPsnr;
    if (say) say("budget " + std::to_string(budget) + " bytes: trying candidates");
    const auto searchStarted = std::chrono::steady_clock::now();
    BudgetChoice choice = searchBudget(programs, scene, reference, search, cages, say);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStarted).count();
    applyChoice(choice.chosen, choice.cageWorld.faceCount(), o.fit.steps == fit::kByDevice, fitOptions);
    scene.setCage(choice.cageWorld);
    BakeRoute route = budgetBakeRoute(choice, search, fitOptions, scene);
    return {.fit = std::move(fitOptions),
            .bakeRoute = std::move(route),
            .budget = BudgetReport{.bytes = budget,
                                   .chosen = choice.chosen,
                                   .tried = std::move(choice.tried),
                                   .seconds = seconds,
                                   .phases = choice.phases,
                                   .shipped = {}}};
}

}  // namespace subdfit::simplify
