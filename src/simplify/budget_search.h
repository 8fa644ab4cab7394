#pragma once
// `simplify --budget`: which asset to fit so that what ships fits the bytes. A small
// rate-distortion search: cages of several face counts, each bare and with baked maps at a few
// resolutions and bit depths; every candidate is encoded exactly as it would ship (asset.subd:
// its bytes), decoded again and rendered on the monitor views (its loss); where several lie
// within 20 % of the lowest, they are rendered on the training views as well, and of them the
// smallest whose loss is within 2 % of the lowest, saving bytes worth the loss, is fitted. The bake stands in for the
// fit, which starts from it and only improves on it (the fit keeps its best state).
// docs/simplify.md walks through the phases.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec/subd_format.h"
#include "fit/fit_scene.h"
#include "gl/program_cache.h"
#include "maps/map_effects.h"
#include "simplify/budget_candidate.h"
#include "simplify/cage/cage_ladder.h"
#include "simplify/stage_seconds.h"

namespace subdfit::simplify {

struct BudgetSearch {
    std::uintmax_t budget = 0;
    std::vector<int> faceCounts;  // the cages to try (their triangle budgets), largest first
    // The most faces the best candidate's cage may grow to where bytes are left over (0: the
    // ladder's top): the ladder's top is a rough price, a cage's real bytes are measured.
    int mostGrownFaces = 0;
    maps::MapEffects allowedMaps{maps::MapKind::Displacement, maps::MapKind::NormalMap};
    std::vector<int> mapResolutions{2, 3, 4, 6, 8};
    // Bits per map value over its range, fewest first. Four already hold relief within a
    // fraction of a pixel at the budgets users ask for, and cost about a third of eight's bytes
    // (docs/simplify.md); more where the loss says they pay.
    std::vector<int> mapBits{4, 6, 8};
    // A scene with materials: every candidate carries the appearance maps its shading reads
    // (baked, shipped as JPEG), at one of these resolutions and the first of these qualities at
    // which the bare cage fits. More choices make the search several times slower for a tenth
    // of a dB or less.
    maps::MapEffects appearance{};
    std::vector<int> appearanceResolutions{4, 8, 16};
    std::vector<int> appearanceQualities{90};
    // ... or in the reference's own texture atlas at these sizes (simplify/bake/atlas_bake.h), smallest
    // first, where the reference allows (atlasSizesFor); such candidates take heights alone.
    std::vector<int> appearanceAtlases;
    // With a triangle ladder, its best bare cage tried once more as a quad-dominant remesh at the
    // same bytes (--cage-shape auto): the two shapes lead on different references.
    bool quadTrial = false;
    // Whether to settle the best candidate with maps too (the bake baseline's, --compare full).
    bool bestWithMaps = true;
    // The monitor PSNR below which no candidate is fitted (the triangle route ships instead,
    // simplify/route.h): where even the best candidate is below it, which of its near ties is
    // chosen changes nothing, and none is drawn on the training views to settle it.
    double leastFittedMonitorPsnr = -INFINITY;
};

struct BudgetChoice {
    BudgetCandidate chosen;
    mesh::PolygonMesh cageWorld;  // the chosen candidate's cage
    // The best candidate with maps within the budget (the bake route at these bytes), if any and
    // if asked for.
    std::optional<BudgetCandidate> bestWithMaps;
    mesh::PolygonMesh bestWithMapsCage;
    std::vector<BudgetCandidate> tried;
    StageSeconds phases;  // the search's seconds: cages, bake, encode, render, settle
};

// Face counts worth trying for `budget` bytes on a reference of `referenceTriangles`: from what
// the budget could hold as a bare cage (at most `mostFaces` and half the reference's triangles)
// down to ~1/20 of that, at steps of ~1.6x; and first, where the budget holds more, a cage of
// the reference's own triangle count.
std::vector<int> faceCountsFor(std::uintmax_t budget, int referenceTriangles, int mostFaces);

// The ladder's loss at a budget falls as its cages shrink while the bytes they free buy maps,
// then rises: past its lowest the smaller cages cannot pay. True once the best so far has maps
// and the last kTrailingCages of `cageBests` (each judged cage's lowest monitor loss, in ladder
// order, of those with a candidate that fits) each lie over kTrailingLoss times the lowest
// before them. Never before the best has maps: where maps first fit only on small cages, bare
// cages trail on the way to them.
inline constexpr double kTrailingLoss = 1.5;
inline constexpr int kTrailingCages = 2;
bool ladderPastItsBest(bool bestHasMaps, const std::vector<double>& cageBests);

// Whether the cage `bare` (within the budget, judged), coded at the fewest position bits and
// grown to `budget`, may reach a monitor loss below `loss`: the search grows the best bare cage,
// and remeshes it into quads, only then. Grown so, a bare cage's loss fell about as its faces
// grew (1.7-2.4x on the references, 0.86-1.03 times the faces' growth; its quad remesh at most
// 10 % below that: docs/simplify.md); its faces grow as the budget over its bytes at the fewest
// bits, taken as bits in proportion (0.62-0.70 of the 14-bit bytes at 10 measured, 0.71 assumed).
inline constexpr double kBareGrowthSlack = 1.25;
bool bareMayReach(const BudgetCandidate& bare, double loss, std::uintmax_t budget);

// What searchBudget throws when no candidate fits the budget: the reference's path and why, and
// that reason alone (simplify ships a triangle route instead where one fits).
class NoCageFits : public Error {
public:
    NoCageFits(const std::string& path, std::string reason)
        : Error(path + ": " + reason + "; raise --budget"), reason_(std::move(reason)) {}
    const std::string& reason() const { return reason_; }

private:
    std::string reason_;
};

// Runs the search on `scene` (its targets and frame; its cage is not used). `cages` are
// search.faceCounts' cages of `referenceWorld`, started by the caller (as early as it can).
// `say` reports each candidate. Throws NoCageFits (naming the reference) when no candidate
// fits the budget.
BudgetChoice searchBudget(gl::ProgramCache& programs, const fit::FitScene& scene,
                          const mesh::PolygonMesh& referenceWorld, const BudgetSearch& search, CageLadder& cages,
                          const std::function<void(const std::string&)>& say = {});

// Builds, on the calling thread, the drawing tables judging `cageWorld` needs (OpenSubdiv's,
// for the cage as it ships: decoded, its vertices renumbered), into subdiv's table cache: a
// CageLadder's `prepare`, so that the GL thread finds them built. Never throws: whatever fails
// here fails again, and is reported, where the cage is judged.
void prepareToJudge(const mesh::PolygonMesh& cageWorld);

// The atlas sizes worth trying on `reference`: its texture at 1/32, 1/16 and 1/8 of its size (the
// scales the textured triangle baselines reach at tens of KB), 32 to 512 texels; none when its
// appearance cannot stay in its atlas. 1/32 leaves room for heights or a denser cage beside
// several textures at tight budgets.
std::vector<int> atlasSizesFor(const mesh::PolygonMesh& reference);

// What an asset.subd ships at once shipWithinBudget has done: bits per map value, the JPEG
// quality of its appearance images, and its bytes.
struct BudgetShipment {
    int mapBits = 0;
    int appearanceQuality = 0;
    std::uintmax_t bytes = 0;
};

// The fitted maps code differently from the baked ones the search measured (and the search
// does not weigh the appearance maps): where `subd` (`bytes` as written at `mapBits` and
// `appearanceQuality`) is over `budget`, `asset` (what it codes, before coding:
// fit::shippableState; not the file decoded, which would be quantised twice) is coded into it
// again with the appearance images at a lower JPEG quality, then with the heights and normals at
// up to two fewer bits (none below 4), until it fits or the ladder ends.
BudgetShipment shipWithinBudget(const codec::SubdAsset& asset, const std::filesystem::path& subd, std::uintmax_t bytes,
                                std::uintmax_t budget, int mapBits, int positionBits, int appearanceQuality);

// The same coding of `asset` (`bytes` as coded at `mapBits` and `appearanceQuality`) over
// `budget`, nothing written: what it ships at and its bytes (the coarsest rung's where none
// fits), and in `encoded` the file where a coarser rung was coded (else none: `bytes` stand).
BudgetShipment codeWithinBudget(const codec::SubdAsset& asset, std::uintmax_t bytes, std::uintmax_t budget, int mapBits,
                                int positionBits, int appearanceQuality, std::vector<unsigned char>* encoded = nullptr);

// report.json's `budget`: the search and what shipped.
struct BudgetReport {
    std::uintmax_t bytes = 0;                // the budget
    bool derived = false;                    // from the reference (no --budget): route.h's defaultBudget
    std::uintmax_t compressedReference = 0;  // what it was derived from
    BudgetCandidate chosen;
    std::vector<BudgetCandidate> tried;
    double seconds = 0.0;    // the search's
    StageSeconds phases;     // and where they went
    BudgetShipment shipped;  // after the fit
};

// `bytes` (and, derived, `derived_from`: the reference compressed), `chosen`, `candidates`,
// `seconds`, `map_bits` and `appearance_quality` as shipped, and `over_budget`.
nlohmann::json toJson(const BudgetReport& report);

}  // namespace subdfit::simplify
