#include "simplify/budget_search.h"
#include "fit/fit_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <tuple>

#include "codec/subd_format.h"
#include "mesh/mesh_geometry.h"
#include "fit/image_metrics.h"
#include "gl/buffer.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/cage_ladder.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/cage_bakes.h"
#include "simplify/candidate_choice.h"
#include "util/error.h"
#include "util/interrupt.h"
#include "simplify/stage_seconds.h"
#include "subdiv/patch_set.h"

namespace subdfit::simplify {
namespace {

// A rough price of a bare decimated cage in asset.subd, bytes a triangle (Draco connectivity,
// 14-bit positions): where the ladder starts. Each candidate's real bytes are then measured.
constexpr double kBytesPerCageFace = 2.5;
constexpr double kLadderStep = 1.6;
constexpr int kLadderLength = 7;
constexpr int kFewestFaces = 24;
// Appearance kinds (tile resolutions, atlas sizes) whose maps ladder is tried on each cage.
constexpr size_t kMostAppearancesWithMaps = 2;
// Bits per cage coordinate tried below the default 14, finest first: a cage's bytes are mostly
// its positions (Draco connectivity is about a tenth), and the triangle route searches its own.
// None below 10: a step of over a thousandth of the cage's size shows at resolutions above the
// monitor views' that judge it.
constexpr int kFewerPositionBits[] = {12, 11, 10};
constexpr int kFewestPositionBits = kFewerPositionBits[std::size(kFewerPositionBits) - 1];

std::string describe(const BudgetCandidate& c) {
    char line[160];
    std::snprintf(line, sizeof line, "%6d faces, maps %-19s T=%d, %2d bits: %8ju bytes", c.faces,
                  maps::toString(c.maps).c_str(), c.mapResolution, c.mapBits, c.bytes);
    std::string text = line;
    if (c.quadDominant()) text += ", " + std::to_string(c.quads) + " quads";
    if (c.positionBits != codec::SubdPrecision{}.positionBits)
        text += ", " + std::to_string(c.positionBits) + "-bit positions";
    if (c.shadingNormal == surface::ShadingNormal::Limit) text += ", limit-shaded";
    if (c.appearanceAtlas > 0)
        text += ", appearance atlas " + std::to_string(c.appearanceAtlas) + " q" + std::to_string(c.appearanceQuality);
    else if (c.appearanceResolution > 0)
        text += ", appearance T=" + std::to_string(c.appearanceResolution) + " q" + std::to_string(c.appearanceQuality);
    if (c.monitorLoss > 0.0) {
        std::snprintf(line, sizeof line, ", monitor loss %.4g", c.monitorLoss);
        text += line;
    }
    return text;
}

// A candidate as it ships: encoded (its bytes) and decoded again (what is judged).
struct Shipped {
    std::shared_ptr<const std::vector<unsigned char>> encoded;
    codec::SubdAsset decoded;
};

codec::SubdPrecision precisionOf(int mapBits, int appearanceQuality, int positionBits) {
    return codec::SubdPrecision::forMapBits(
        mapBits, appearanceQuality > 0 ? appearanceQuality : codec::SubdPrecision{}.appearanceQuality, positionBits);
}

Shipped ship(const mesh::PolygonMesh& cageWorld, surface::SurfaceMaps maps, int mapBits, int appearanceQuality,
             float frameScale, int positionBits = codec::SubdPrecision{}.positionBits) {
    for (float& d : maps.displacement) d /= frameScale;  // heights in world units, as shipped
    const auto precision = precisionOf(mapBits, appearanceQuality, positionBits);
    auto encoded = std::make_shared<const std::vector<unsigned char>>(
        codec::encodeSubd(codec::shippableAsset(cageWorld, maps, precision.positionBits), precision));
    return {encoded, codec::decodeSubd(*encoded, "budget candidate")};
}

}  // namespace

void prepareToJudge(const mesh::PolygonMesh& cageWorld) {
    try {
        const codec::SubdAsset shipped = ship(cageWorld, {}, 0, 0, 1.0f).decoded;
        subdiv::cachedPatchSet(shipped.cage, {.isolationLevel = subdiv::drawingIsolationLevel(shipped.cage)});
    } catch (const Error&) {}
}

namespace {

// A rung predicted over this many times the budget is not tried: the prediction (map bytes per
// face, measured on another cage) errs by a few per cent.
constexpr double kPredictedOver = 1.25;

// What the search works on, the same for its whole run.
struct SearchInputs {
    gl::ProgramCache& programs;
    const fit::FitScene& scene;
    const mesh::PolygonMesh& referenceWorld;  // what cages are decimated from
    CageLadder& cages;                        // ... built ahead of the search, on a thread of their own
    const BudgetSearch& search;
    const std::function<void(const std::string&)>& say;
};

// What the search has found so far: every candidate tried, in order (the report lists them all),
// and those within the budget.
struct Findings {
    std::vector<BudgetCandidate> tried;
    std::vector<Fitting> fitting;
    StageSeconds phases;  // where the search's seconds went
    // Map bytes a cage face costs, by (map choice, resolution, bits), as last measured.
    std::map<std::tuple<size_t, int, int>, double> mapBytesPerFace;
    // Each appearance's (by its index) bytes a cage face cost on the last cage that baked it,
    // at the lowest quality, and that cage's faces.
    std::map<size_t, std::pair<double, int>> appearanceBytesPerFace;
    bool moreBitsPay = true;  // until a rung's extra bits fail to lower its loss
};

// A cage as tried: in world units (what ships) and in the normalised frame (what maps are baked onto).
struct TriedCage {
    std::shared_ptr<const mesh::PolygonMesh> world;
    mesh::PolygonMesh normalized;
};

// The geometric maps on a candidate: which, their cells per face edge and bits per value (none,
// 0, 0: a bare cage).
struct MapRecipe {
    maps::MapEffects effects;
    int resolution = 0;
    int bits = 0;
};

// The appearance on a candidate: its maps (none in a scene without materials) and the JPEG
// quality they ship at (0: none).
struct Appearance {
    surface::SurfaceMaps maps;
    int quality = 0;
};

bool fits(const BudgetSearch& search, const BudgetCandidate& c) { return c.bytes <= search.budget; }

// `cage` as tried (none stays none).
std::optional<TriedCage> asTried(const SearchInputs& in, std::optional<mesh::PolygonMesh> cage) {
    if (!cage) return std::nullopt;
    auto world = std::make_shared<const mesh::PolygonMesh>(std::move(*cage));
    mesh::PolygonMesh normalized = *world;
    normalized.positions = in.scene.frame.toNormalized(world->positions);
    return TriedCage{std::move(world), std::move(normalized)};
}

// The ladder's k-th cage, or none when too few faces survive decimation.
std::optional<TriedCage> ladderCage(const SearchInputs& in, size_t k) {
    throwIfStopRequested();
    return asTried(in, in.cages.take(k));
}

// A cage of (about) `faces` triangles off the ladder, or none when too few faces survive decimation.
std::optional<TriedCage> cageOf(const SearchInputs& in, int faces, CageShape shape) {
    throwIfStopRequested();
    try {
        return asTried(in, in.cages.source().cage({.faces = faces, .shape = shape}));
    } catch (const Interrupted&) {
        throw;
    } catch (const Error&) {
        return std::nullopt;
    }
}

// Geometry first: a normal map alone would buy image quality with no surface distance.
std::vector<maps::MapEffects> mapChoicesOf(const BudgetSearch& search) {
    std::vector<maps::MapEffects> choices;
    if (search.allowedMaps.has(maps::MapKind::Displacement)) choices.push_back({maps::MapKind::Displacement});
    if (search.allowedMaps.has(maps::MapKind::Displacement) && search.allowedMaps.has(maps::MapKind::NormalMap))
        choices.push_back({maps::MapKind::Displacement, maps::MapKind::NormalMap});
    return choices;
}

// The appearance lattices to try: tiles of each resolution, then atlases of each size (one
// without either in a scene without materials).
std::vector<AppearanceBakeOptions> appearancesOf(const BudgetSearch& search) {
    std::vector<AppearanceBakeOptions> appearances;
    if (!search.appearance.appearance()) appearances.push_back({.resolution = 0});
    else {
        for (int resolution : search.appearanceResolutions)
            appearances.push_back({.effects = search.appearance, .resolution = resolution});
        for (int size : search.appearanceAtlases) appearances.push_back({.effects = search.appearance, .atlas = size});
    }
    return appearances;
}

// A reference of over this many faces a cage face is dense: heights baked onto the cage do not
// copy its facets, and their slopes shade it better than the limit normal (the README demo's and
// the bunny's candidates at 20 KB, every one: the limit-shaded loss 1.4-8x the other).
constexpr double kDenseFacesPerCageFace = 8.0;

// A candidate within the budget, scored on the monitor views as the fit would draw it. Heights
// baked onto a faceted reference copy its facets into the shading, which the limit normal does
// not, but a coarse cage needs the heights' slopes to shade its shape: with heights on a cage of
// about the reference's own density both are judged, and when the limit normal wins, `baked`
// takes its flag and is shipped again with it.
void scoreOnMonitor(const SearchInputs& in, const mesh::PolygonMesh& cageWorld, surface::SurfaceMaps& baked,
                    const Appearance& appearance, BudgetCandidate& c, Shipped& shipped) {
    std::unique_ptr<fit::CageFitter> drawn;
    try {
        drawn = drawnAsFitted(in.programs, in.scene, shipped.decoded);
        c.monitorLoss = fit::score(*drawn, in.scene.choosing(in.programs)).loss;
    } catch (const gl::StorageBlockExceeded& e) {  // not drawable here: never chosen
        c.monitorLoss = std::numeric_limits<double>::infinity();
        if (in.say)
            in.say(std::to_string(c.faces) + " faces at T = " + std::to_string(c.mapResolution) + ": " + e.what());
        return;
    }
    if (!c.maps.has(maps::MapKind::Displacement) ||
        in.scene.reference.faceCount() > kDenseFacesPerCageFace * double(c.faces))
        return;
    drawn->maps()->setShadingNormal(surface::ShadingNormal::Limit);
    if (const double loss = fit::score(*drawn, in.scene.choosing(in.programs)).loss; loss < c.monitorLoss) {
        c.monitorLoss = loss;
        c.shadingNormal = baked.shadingNormal = surface::ShadingNormal::Limit;
        shipped = ship(cageWorld, baked, c.mapBits, appearance.quality, in.scene.frame.scale, c.positionBits);
    }
}

// Records a judged candidate (the report lists them all) and says it; with `cageWorld`, also as
// one that fits, to choose from.
void record(const SearchInputs& in, Findings& found, const BudgetCandidate& c,
            const std::shared_ptr<const mesh::PolygonMesh>& cageWorld,
            const std::shared_ptr<const std::vector<unsigned char>>& encoded) {
    found.tried.push_back(c);
    if (in.say) in.say(describe(c) + (fits(in.search, c) ? "" : " (over budget)"));
    if (cageWorld) found.fitting.push_back({c, cageWorld, encoded, found.tried.size() - 1});
}

// Judges one candidate: the cage with `baked` maps (laid out on it, as `recipe` says) and
// `appearance`, encoded and decoded as it ships, scored when it fits. Every candidate is
// recorded, those over the budget too, so that the report shows why they lost.
BudgetCandidate judge(const SearchInputs& in, Findings& found,
                      const std::shared_ptr<const mesh::PolygonMesh>& cageWorld, surface::SurfaceMaps baked,
                      const MapRecipe& recipe, const Appearance& appearance,
                      int positionBits = codec::SubdPrecision{}.positionBits) {
    baked.setAppearance(appearance.maps);
    std::optional<TimedStage> timed(std::in_place, found.phases, "encode");
    Shipped shipped = ship(*cageWorld, baked, recipe.bits, appearance.quality, in.scene.frame.scale, positionBits);
    timed.emplace(found.phases, "render");
    const bool atlas = appearance.maps.appearanceAtlas.present();
    BudgetCandidate c{.faces = cageWorld->faceCount(),
                      .quads = mesh::quadCount(*cageWorld),
                      .maps = recipe.effects,
                      .mapResolution = recipe.resolution,
                      .mapBits = recipe.bits,
                      .positionBits = positionBits,
                      .appearanceResolution = atlas ? 0 : appearance.maps.appearanceLayout.resolution,
                      .appearanceQuality = appearance.quality,
                      .appearanceAtlas = appearance.maps.appearanceAtlas.size,
                      .bytes = shipped.encoded->size()};
    const bool within = fits(in.search, c);
    if (within) scoreOnMonitor(in, *cageWorld, baked, appearance, c, shipped);
    record(in, found, c, within ? cageWorld : nullptr, shipped.encoded);
    return c;
}

// An appearance on a bare cage that fits the budget.
struct Bare {
    bool inAtlas;
    Appearance appearance;
    BudgetCandidate candidate;
};

// Phase one on a cage: the bare cage with each appearance, at the first quality (best first) at
// which it fits. An appearance that does not fit ends its kind (tiles, atlases): finer ones of
// that kind only cost more. Nor is one baked that two coarser ones of its kind predict over the
// budget: each doubling of the texels adds more bytes than the one before it (it adds four times
// the texels), so the last bytes plus the last increase are the least the next can cost. The
// prediction is read at the lowest quality there is, where the ones before it were judged.
// Nor is one baked that a larger cage predicts over the budget by kPredictedOver: a smaller cage's
// appearance costs at least its faces' share of a larger one's (its faces are larger, its tiles
// or atlas charts hold more detail each, and an atlas's texture does not shrink with the faces).
std::vector<Bare> judgeBare(const SearchInputs& in, Findings& found, const TriedCage& cage,
                            const std::vector<AppearanceBakeOptions>& appearances) {
    std::vector<Bare> bare;
    std::vector<std::uintmax_t> kindBytes;  // of this kind on this cage so far, at the lowest quality
    const auto endKind = [&](size_t& a) {
        while (a + 1 < appearances.size() && (appearances[a + 1].atlas > 0) == (appearances[a].atlas > 0)) ++a;
    };
    const int faces = cage.world->faceCount();
    const auto largerCagePredictsOver = [&](size_t a) {
        const auto measured = found.appearanceBytesPerFace.find(a);
        return measured != found.appearanceBytesPerFace.end() && measured->second.second >= faces &&
               measured->second.first * faces > kPredictedOver * double(in.search.budget);
    };
    for (size_t a = 0; a < appearances.size(); ++a) {
        if (a > 0 && (appearances[a].atlas > 0) != (appearances[a - 1].atlas > 0)) kindBytes.clear();
        if ((kindBytes.size() >= 2 && 2 * kindBytes.back() > kindBytes[kindBytes.size() - 2] + in.search.budget) ||
            largerCagePredictsOver(a)) {
            if (in.say) {
                const bool atlas = appearances[a].atlas > 0;
                char line[96];
                std::snprintf(line, sizeof line,
                              atlas ? "%6d faces, appearance atlas %d" : "%6d faces, appearance T=%d", faces,
                              atlas ? appearances[a].atlas : appearances[a].resolution);
                in.say(std::string(line) + ": predicted over budget, not baked");
            }
            endKind(a);
            continue;
        }
        const bool withAppearance = appearances[a].resolution > 0 || appearances[a].atlas > 0;
        Appearance appearance;
        if (withAppearance) {
            TimedStage timed(found.phases, "bake");
            appearance.maps = bakeAppearance(cage.normalized, in.scene.reference, appearances[a]);
        }
        // Without materials there is no quality to choose (0).
        const std::vector<int> qualities = withAppearance ? in.search.appearanceQualities : std::vector<int>{0};
        BudgetCandidate c;
        for (size_t q = 0; q < qualities.size() && (q == 0 || !fits(in.search, c)); ++q) {
            appearance.quality = qualities[q];
            c = judge(in, found, cage.world, {}, {}, appearance);
        }
        if (appearance.quality == qualities.back()) {
            kindBytes.push_back(c.bytes);
            if (withAppearance) found.appearanceBytesPerFace[a] = {double(c.bytes) / faces, faces};
        } else {
            kindBytes.clear();  // fitted at a higher quality: what the lowest costs is not known
        }
        if (fits(in.search, c)) {
            bare.push_back({appearances[a].atlas > 0, std::move(appearance), c});
            continue;
        }
        endKind(a);
    }
    return bare;
}

// Phase two: the appearances worth maps: not one that another bare one beats in bytes and loss
// alike, and of those the few of lowest loss (maps add about the same to each).
std::vector<const Bare*> worthMaps(const std::vector<Bare>& bare) {
    std::vector<const Bare*> worth;
    for (const Bare& b : bare) {
        const bool dominated = std::any_of(bare.begin(), bare.end(), [&](const Bare& o) {
            const BudgetCandidate &p = o.candidate, &q = b.candidate;
            return p.bytes <= q.bytes && p.monitorLoss <= q.monitorLoss &&
                   (p.bytes < q.bytes || p.monitorLoss < q.monitorLoss);
        });
        if (!dominated) worth.push_back(&b);
    }
    std::sort(worth.begin(), worth.end(),
              [](const Bare* x, const Bare* y) { return x->candidate.monitorLoss < y->candidate.monitorLoss; });
    if (worth.size() > kMostAppearancesWithMaps) worth.resize(kMostAppearancesWithMaps);
    return worth;
}

// Whether the map ladder on a cage of `faces` will likely bake its first rung, so that it is worth
// baking while the bare cage is judged: unless climbMapLadder's prediction (with the bare cage's
// bytes guessed from the bare cages judged so far, per face) would skip it. A wrong guess costs a
// bake on the other core or one made later, never another result.
bool firstRungLikely(const SearchInputs& in, const Findings& found, int faces) {
    double bareBytesPerFace = 0.0;
    for (const BudgetCandidate& c : found.tried)
        if (!c.maps.any() && (bareBytesPerFace == 0.0 || double(c.bytes) / c.faces < bareBytesPerFace))
            bareBytesPerFace = double(c.bytes) / c.faces;
    const auto rung = found.mapBytesPerFace.find(
        std::make_tuple(size_t(0), in.search.mapResolutions.front(), in.search.mapBits.front()));
    if (rung == found.mapBytesPerFace.end() || bareBytesPerFace == 0.0) return true;
    return (bareBytesPerFace + rung->second) * faces <= kPredictedOver * double(in.search.budget);
}

// Past this share of the budget a cage's map ladder has no room left but the cage's position bits.
constexpr double kNearlySpent = 0.9;

// Phase three on a cage: the map ladder on each appearance worth it, each choice of maps at each
// resolution, coarsest first, and at each bit depth while it fits: more bits and finer maps
// only cost more, so a rung over the budget ends its ladder (a resolution's first is judged
// again at the fewest position bits before it does). Maps are baked once per (choice,
// resolution) on the cage. Two rules spare work that cannot pay:
//  - a rung whose bytes the rungs measured on other cages predict well over the budget (map
//    bytes grow in proportion to the faces) ends its ladder unbaked;
//  - once more bits have failed to lower a rung's loss by more than kLossTolerance, no rung
//    tries them again (preferred() would never choose them: more bytes for a loss within it);
//  - a resolution whose loss trails a coarser one's by over kLossTolerance with its rung past
//    kNearlySpent of the budget ends its ladder: a finer map (10-125 % more map bytes on the
//    references) then fits only by taking position bits from the cage, and the loss has turned
//    up already. Short of it, the loss can dip again (catmark_cubes_infsharp's 24 faces at 700
//    bytes: T = 3 trails T = 2 by 10 %, at 67 % of the budget, and T = 8 leads both by 2.2x).
void climbMapLadder(const SearchInputs& in, Findings& found, const TriedCage& cage, const Bare& bare,
                    const std::vector<maps::MapEffects>& mapChoices, CageBakes& bakes) {
    const int faces = cage.world->faceCount();
    for (size_t m = 0; m < mapChoices.size(); ++m) {
        if (bare.inAtlas && mapChoices[m].has(maps::MapKind::NormalMap)) continue;  // an atlas takes heights alone
        double coarserLoss = INFINITY;  // the lowest of the coarser resolutions
        for (int resolution : in.search.mapResolutions) {
            throwIfStopRequested();
            const auto rung = std::make_tuple(m, resolution, in.search.mapBits.front());
            if (const auto measured = found.mapBytesPerFace.find(rung); measured != found.mapBytesPerFace.end()) {
                const double predicted = double(bare.candidate.bytes) + measured->second * faces;
                if (predicted > kPredictedOver * double(in.search.budget)) {
                    if (in.say)
                        in.say(describe(bare.candidate) + ": maps T=" + std::to_string(resolution) +
                               " predicted over budget, not tried");
                    break;
                }
            }
            const surface::SurfaceMaps* baked = nullptr;
            {
                TimedStage timed(found.phases, "bake");
                baked = &bakes.at(m, {.effects = mapChoices[m], .resolution = resolution});
            }
            bool fitted = false;
            double fewerBitsLoss = 0.0, resolutionLoss = INFINITY;  // and the bytes of its lowest
            std::uintmax_t resolutionBytes = 0;
            int positionBits = codec::SubdPrecision{}.positionBits;
            for (int bits : in.search.mapBits) {
                if (fitted && !found.moreBitsPay) break;
                const MapRecipe recipe{.effects = mapChoices[m], .resolution = resolution, .bits = bits};
                BudgetCandidate c = judge(in, found, cage.world, *baked, recipe, bare.appearance, positionBits);
                if (positionBits == codec::SubdPrecision{}.positionBits)
                    found.mapBytesPerFace[std::make_tuple(m, resolution, bits)] =
                        double(c.bytes > bare.candidate.bytes ? c.bytes - bare.candidate.bytes : 0) / faces;
                // The fewest map bits over the budget at full position bits may fit at the fewest
                // position bits (the cage is most of a file's bytes), and more map bits then only there.
                if (!fits(in.search, c) && !fitted && positionBits > kFewestPositionBits) {
                    positionBits = kFewestPositionBits;
                    c = judge(in, found, cage.world, *baked, recipe, bare.appearance, positionBits);
                }
                if (!fits(in.search, c)) break;
                if (fitted && c.monitorLoss > (1.0 - kLossTolerance) * fewerBitsLoss) found.moreBitsPay = false;
                fitted = true;
                fewerBitsLoss = c.monitorLoss;
                if (c.monitorLoss < resolutionLoss) resolutionLoss = c.monitorLoss, resolutionBytes = c.bytes;
            }
            if (!fitted) break;
            if (resolutionLoss > (1.0 + kLossTolerance) * coarserLoss &&
                double(resolutionBytes) > kNearlySpent * double(in.search.budget)) {
                if (in.say)
                    in.say(std::to_string(faces) + " faces: maps finer than T=" + std::to_string(resolution) +
                           " not tried (it trails a coarser map near the budget)");
                break;
            }
            coarserLoss = std::min(coarserLoss, resolutionLoss);
        }
    }
}

// The maps and appearance of `kind` (a candidate judged on another cage, or on this one) baked
// onto `normalized`, as the search bakes every candidate.
struct BakedLike {
    surface::SurfaceMaps maps;
    MapRecipe recipe;
    Appearance appearance;
};

BakedLike bakeLike(const SearchInputs& in, Findings& found, const mesh::PolygonMesh& normalized,
                   const BudgetCandidate& kind) {
    TimedStage timed(found.phases, "bake");
    BakedLike baked;
    baked.recipe = {.effects = kind.maps, .resolution = kind.mapResolution, .bits = kind.mapBits};
    baked.appearance.quality = kind.appearanceQuality;
    if (kind.appearanceResolution > 0 || kind.appearanceAtlas > 0)
        baked.appearance.maps = bakeAppearance(
            normalized, in.scene.reference,
            {.effects = in.search.appearance, .resolution = kind.appearanceResolution, .atlas = kind.appearanceAtlas});
    if (kind.maps.any())
        baked.maps = bakeMaps(normalized, in.scene.reference, {.effects = kind.maps, .resolution = kind.mapResolution});
    return baked;
}

// Phase four: the best so far (of those `keep` takes) with its cage's positions at fewer bits,
// its maps baked again (not the decoded ones: coded twice, they would lose more than the bits
// say), finest first, while the loss stays within kLossTolerance of the 14-bit one: the bytes
// saved are what phase five grows the cage with.
template <class Keep>
void fewerPositionBits(const SearchInputs& in, Findings& found, const Keep& keep) {
    const Fitting* best = preferred(found.fitting, keep, monitored);
    if (!best) return;
    const BudgetCandidate start = best->candidate;  // judging adds to found.fitting: `best` moves
    const std::shared_ptr<const mesh::PolygonMesh> cageWorld = best->cageWorld;
    std::optional<BakedLike> baked;
    for (int bits : kFewerPositionBits) {
        if (bits >= start.positionBits) continue;
        throwIfStopRequested();
        if (!baked) {
            mesh::PolygonMesh normalized = *cageWorld;
            normalized.positions = in.scene.frame.toNormalized(normalized.positions);
            baked = bakeLike(in, found, normalized, start);
        }
        const BudgetCandidate c = judge(in, found, cageWorld, baked->maps, baked->recipe, baked->appearance, bits);
        if (!fits(in.search, c) || c.monitorLoss > (1.0 + kLossTolerance) * start.monitorLoss) break;
    }
}

// How a kind of asset's bytes grow with its faces, bytes ~ faces^exponent: from the two most
// faces of the same maps and appearance tried at one precision. Positions cost less a vertex the
// denser the cage (their prediction improves); connectivity and maps grow in proportion. 1
// (proportional: a growth that undershoots, never overshoots) where unmeasured.
double bytesExponent(const std::vector<BudgetCandidate>& tried, const BudgetCandidate& kind) {
    // By position bits: the two most faces (most, next).
    std::map<int, std::pair<const BudgetCandidate*, const BudgetCandidate*>> largest;
    for (const BudgetCandidate& c : tried) {
        const bool same = c.quadDominant() == kind.quadDominant() && c.maps == kind.maps &&
                          c.mapResolution == kind.mapResolution && c.mapBits == kind.mapBits &&
                          c.appearanceResolution == kind.appearanceResolution &&
                          c.appearanceAtlas == kind.appearanceAtlas && c.bytes > 0;
        if (!same) continue;
        auto& [most, next] = largest[c.positionBits];
        if (!most || c.faces > most->faces) {
            next = most;
            most = &c;
        } else if (c.faces < most->faces && (!next || c.faces > next->faces)) {
            next = &c;
        }
    }
    double exponent = 1.0;
    int spanFaces = 0;
    for (const auto& [bits, pair] : largest) {
        const auto [most, next] = pair;
        if (!next || most->faces < 1.2 * next->faces || most->faces <= spanFaces) continue;
        spanFaces = most->faces;
        exponent = std::log(double(most->bytes) / double(next->bytes)) / std::log(double(most->faces) / next->faces);
    }
    return std::clamp(exponent, 0.7, 1.0);
}

// Phase five: the ladder's steps leave bytes unspent. The preferred kind of asset so far (of
// those `keep` takes) on a cage grown to what the budget holds (bytes ~ faces^bytesExponent),
// shrinking until it fits and growing on while over kGrowthSlack of the budget is left. With
// another `shape` than the ladder's (a quad trial), the same kind on a cage of that shape at the
// same bytes, at least once: a quad has a vertex to itself where a triangle has half of one, so
// it starts from half the faces.
template <class Keep>
void growBest(const SearchInputs& in, Findings& found, const Keep& keep, CageShape shape) {
    constexpr double kGrowthTarget = 0.97, kGrowthSlack = 1.05;
    const Fitting* ladderBest = preferred(found.fitting, keep, monitored);
    if (!ladderBest) return;
    const BudgetCandidate best = ladderBest->candidate;
    bool placed = shape == in.cages.shape();  // a cage of `shape` fits (the ladder's best does)
    int fromFaces = placed ? best.faces : best.faces / 2;
    double exponent = bytesExponent(found.tried, best);
    double scale = std::pow(kGrowthTarget * double(in.search.budget) / double(best.bytes), 1.0 / exponent);
    std::uintmax_t fromBytes = best.bytes;
    // A quad remesh lands a few per cent off the count asked: the next ask allows for the last.
    double builtPerAsked = 1.0;
    for (int attempt = 0; attempt < 3 && (scale > kGrowthSlack || !placed); ++attempt) {
        const int most = std::max(in.search.mostGrownFaces, in.search.faceCounts.front());
        const int faces = std::min(int(std::lround(fromFaces * scale)), most);
        if (placed && faces <= int(fromFaces * 1.05)) break;
        const int asked = std::max(1, int(std::lround(faces / builtPerAsked)));
        const std::optional<TriedCage> cage = [&] {
            TimedStage timed(found.phases, "cages");
            return cageOf(in, asked, shape);
        }();
        if (!cage) break;
        builtPerAsked = double(cage->world->faceCount()) / asked;
        const BakedLike baked = bakeLike(in, found, cage->normalized, best);
        const BudgetCandidate grown =
            judge(in, found, cage->world, baked.maps, baked.recipe, baked.appearance, best.positionBits);
        if (fits(in.search, grown)) {                                // on from it while bytes are left
            if (grown.bytes > fromBytes && grown.faces > fromFaces)  // the exponent as this growth measured it
                exponent = std::clamp(std::log(double(grown.bytes) / double(fromBytes)) /
                                          std::log(double(grown.faces) / double(fromFaces)),
                                      0.7, 1.0);
            fromFaces = grown.faces;
            fromBytes = grown.bytes;
            scale = std::pow(kGrowthTarget * double(in.search.budget) / double(grown.bytes), 1.0 / exponent);
            placed = true;
        } else if (!placed) {  // the other shape's first cage over the budget: shrunk to it
            fromFaces = grown.faces;
            scale = std::pow(kGrowthTarget * double(in.search.budget) / double(grown.bytes), 1.0 / exponent);
        } else {
            scale = 1.0 + 0.6 * (scale - 1.0);
        }
    }
}

// Phase six: the near ties settled on the training views too; the chosen candidate, and the
// best with maps (the bake route at these bytes). Throws when nothing fits.
BudgetChoice settleChoice(const SearchInputs& in, Findings& found) {
    TimedStage timed(found.phases, "settle");
    const auto any = [](const BudgetCandidate&) { return true; };
    const Fitting* lowest = lowestOf(found.fitting, any, monitored);
    const bool fitted = lowest && fit::psnrFromLoss(lowest->candidate.monitorLoss) >= in.search.leastFittedMonitorPsnr;
    SettlingViews settling(in.programs, in.scene);
    const auto choose = [&](auto keep) {
        return fitted ? settle(in.programs, in.scene, settling, found.fitting, keep)
                      : lowestOf(found.fitting, keep, monitored);
    };
    const Fitting* chosen = choose(any);
    if (!chosen)
        throw NoCageFits(in.referenceWorld.sourcePath,
                         "no cage fits in " + std::to_string(in.search.budget) + " bytes (the smallest tried needs " +
                             std::to_string(found.tried.empty() ? 0 : found.tried.back().bytes) + ")");
    BudgetChoice choice;
    choice.chosen = chosen->candidate;
    choice.cageWorld = *chosen->cageWorld;
    if (const Fitting* withMaps =
            in.search.bestWithMaps ? choose([](const BudgetCandidate& c) { return c.maps.any(); }) : nullptr) {
        choice.bestWithMaps = withMaps->candidate;
        choice.bestWithMapsCage = *withMaps->cageWorld;
    }
    for (const Fitting& f : found.fitting) {
        if (f.candidate.settledLoss <= 0.0) continue;
        found.tried[f.tried].settledLoss = f.candidate.settledLoss;
        found.tried[f.tried].settledViews = f.candidate.settledViews;
        if (in.say) {
            char line[80];
            std::snprintf(line, sizeof line, ": loss %.4g on the monitor and %d training views",
                          f.candidate.settledLoss, f.candidate.settledViews);
            in.say(describe(f.candidate) + line);
        }
    }
    choice.tried = std::move(found.tried);
    return choice;
}

}  // namespace

std::vector<int> faceCountsFor(std::uintmax_t budget, int referenceTriangles, int mostFaces) {
    const double largest =
        std::min({double(budget) / kBytesPerCageFace, 0.5 * double(referenceTriangles), double(mostFaces)});
    std::vector<int> counts;
    // Above the ladder, as many faces as the reference has triangles where the budget holds them:
    // a light asset shades best from a cage of its own density. On top of the ladder rather than
    // its start, so that the rungs below stay where they are.
    const double denser = std::min({double(budget) / kBytesPerCageFace, double(referenceTriangles), double(mostFaces)});
    if (denser > 1.25 * largest) counts.push_back(int(std::lround(denser)));
    const size_t above = counts.size();
    for (double f = largest; f >= kFewestFaces && int(counts.size() - above) < kLadderLength; f /= kLadderStep)
        counts.push_back(int(std::lround(f)));
    if (counts.empty()) counts.push_back(std::min(kFewestFaces, std::max(referenceTriangles, 4)));
    return counts;
}

bool bareMayReach(const BudgetCandidate& bare, double loss, std::uintmax_t budget) {
    const double fewestBitsBytes = double(bare.bytes) * kFewestPositionBits / bare.positionBits;
    const double faceGrowth = std::max(1.0, double(budget) / fewestBitsBytes);
    return bare.monitorLoss / (kBareGrowthSlack * faceGrowth) < loss;
}

bool ladderPastItsBest(bool bestHasMaps, const std::vector<double>& cageBests) {
    if (!bestHasMaps) return false;
    int trailing = 0;
    double lowest = INFINITY;
    for (const double loss : cageBests) {
        if (loss < lowest) lowest = loss, trailing = 0;
        else if (loss > kTrailingLoss * lowest) ++trailing;
        else trailing = 0;
    }
    return trailing >= kTrailingCages;
}

BudgetChoice searchBudget(gl::ProgramCache& programs, const fit::FitScene& scene,
                          const mesh::PolygonMesh& referenceWorld, const BudgetSearch& search, CageLadder& cages,
                          const std::function<void(const std::string&)>& say) {
    SUBDFIT_CHECK(cages.size() == search.faceCounts.size());
    Findings found;
    const SearchInputs in{programs, scene, referenceWorld, cages, search, say};
    const std::vector<AppearanceBakeOptions> appearances = appearancesOf(search);
    const std::vector<maps::MapEffects> mapChoices = mapChoicesOf(search);
    std::vector<double> cageBests;  // each judged cage's lowest monitor loss, in ladder order
    for (size_t k = 0; k < cages.size(); ++k) {
        const Fitting* best = lowestOf(
            found.fitting, [](const BudgetCandidate&) { return true; }, monitored);
        if (ladderPastItsBest(best && best->candidate.maps.any(), cageBests)) {
            if (say) say("the ladder's smaller cages trail its best: not tried");
            break;
        }
        const std::optional<TriedCage> cage = [&] {
            TimedStage timed(found.phases, "cages");  // the wait for the builder
            return ladderCage(in, k);
        }();
        if (!cage) continue;  // smaller counts will not do better
        CageBakes bakes(cage->normalized, in.scene.reference);
        if (!mapChoices.empty() && !search.mapResolutions.empty() &&
            firstRungLikely(in, found, cage->world->faceCount()))
            bakes.startAhead(0, {.effects = mapChoices.front(), .resolution = in.search.mapResolutions.front()});
        const size_t judged = found.fitting.size();
        const std::vector<Bare> bare = judgeBare(in, found, *cage, appearances);
        for (const Bare* b : worthMaps(bare)) climbMapLadder(in, found, *cage, *b, mapChoices, bakes);
        double cageBest = INFINITY;
        for (size_t f = judged; f < found.fitting.size(); ++f)
            cageBest = std::min(cageBest, found.fitting[f].candidate.monitorLoss);
        if (std::isfinite(cageBest)) cageBests.push_back(cageBest);
    }
    // The best, and where that has maps the best bare cage too: a bare cage spends fewer position
    // bits on more faces, where maps spend them on heights, and the grown bare cage can lead.
    const auto any = [](const BudgetCandidate&) { return true; };
    const auto bare = [](const BudgetCandidate& c) { return !c.maps.any(); };
    const Fitting* best = preferred(found.fitting, any, monitored);
    const bool bestIsBare = best && bare(best->candidate);
    const Fitting* bestBare = lowestOf(found.fitting, bare, monitored);
    // Judging adds to found.fitting (`best` moves): what is read of it, read first.
    const bool bareMayLead =
        bestIsBare ||
        (best && bestBare && bareMayReach(bestBare->candidate, best->candidate.monitorLoss, search.budget));
    fewerPositionBits(in, found, any);
    growBest(in, found, any, cages.shape());
    if (best && !bestIsBare && bareMayLead) {
        fewerPositionBits(in, found, bare);
        growBest(in, found, bare, cages.shape());
    }
    if (best && !bareMayLead && say)
        say("the best bare cage grown to the budget would still trail the best: not grown, nor tried as quads");
    if (bareMayLead && search.quadTrial && !quadDominant(cages.shape())) growBest(in, found, bare, CageShape::Quads);
    BudgetChoice choice = settleChoice(in, found);
    choice.phases = found.phases;
    return choice;
}

std::vector<int> atlasSizesFor(const mesh::PolygonMesh& reference) {
    if (!atlasUnsuitability(reference).empty()) return {};
    std::vector<int> sizes;
    for (int divisor : {32, 16, 8}) {
        const int size = std::clamp(atlasSourceSize(reference) / divisor, 32, 512);
        if (sizes.empty() || sizes.back() != size) sizes.push_back(size);
    }
    return sizes;
}

BudgetShipment codeWithinBudget(const codec::SubdAsset& asset, std::uintmax_t bytes, std::uintmax_t budget, int mapBits,
                                int positionBits, int appearanceQuality, std::vector<unsigned char>* encoded) {
    BudgetShipment shipment{mapBits, appearanceQuality, bytes};
    if (bytes <= budget) return shipment;
    std::vector<std::pair<int, int>> ladder;  // (bits, quality), coarser and coarser
    // Quality in small steps: a JPEG's bytes fall a few per cent a step, and every byte left is
    // detail lost. Map bits two fewer at most, and never below the ladder's fewest: coarser maps
    // than any the search judged could lose to the bake that fits.
    constexpr int kLowestQuality = 30, kQualityStep = 5;
    const int fewestBits = std::max(mapBits - 2, 4);
    int quality = appearanceQuality;
    if (asset.maps.hasBaseColor() || asset.maps.hasMetallicRoughness())
        while (quality - kQualityStep >= kLowestQuality) ladder.emplace_back(mapBits, quality -= kQualityStep);
    for (int bits = mapBits - 1; bits >= fewestBits; --bits) ladder.emplace_back(bits, quality);
    std::vector<unsigned char> coded;
    for (const auto& [bits, rungQuality] : ladder) {
        const auto precision = codec::SubdPrecision::forMapBits(bits, rungQuality, positionBits);
        coded = codec::encodeSubd(asset, precision);
        shipment = {precision.displacementBits, precision.appearanceQuality, coded.size()};
        if (coded.size() <= budget) break;
    }
    if (encoded) *encoded = std::move(coded);
    return shipment;
}

BudgetShipment shipWithinBudget(const codec::SubdAsset& asset, const std::filesystem::path& subd, std::uintmax_t bytes,
                                std::uintmax_t budget, int mapBits, int positionBits, int appearanceQuality) {
    std::vector<unsigned char> encoded;
    BudgetShipment shipped = codeWithinBudget(asset, bytes, budget, mapBits, positionBits, appearanceQuality, &encoded);
    if (!encoded.empty()) shipped.bytes = io::writeBytes(subd, encoded).bytes;  // else as written
    return shipped;
}

nlohmann::json toJson(const BudgetReport& report) {
    auto candidate = [](const BudgetCandidate& c) {
        nlohmann::json j{
            {"faces", c.faces},      {"maps", maps::toString(c.maps)},  {"map_resolution", c.mapResolution},
            {"map_bits", c.mapBits}, {"position_bits", c.positionBits}, {"bytes", c.bytes}};
        if (c.quads > 0) j["quads"] = c.quads;
        if (c.maps.has(maps::MapKind::Displacement) && c.monitorLoss > 0.0)
            j["shading_normal"] = nameOf(c.shadingNormal);
        if (c.appearanceResolution > 0) j["appearance_resolution"] = c.appearanceResolution;
        if (c.appearanceAtlas > 0) j["appearance_atlas"] = c.appearanceAtlas;
        if (c.appearanceQuality > 0) j["appearance_quality"] = c.appearanceQuality;
        if (c.monitorLoss > 0.0) j["monitor_loss"] = c.monitorLoss;
        if (c.settledLoss > 0.0) {
            j["settled_loss"] = c.settledLoss;
            j["settled_views"] = c.settledViews;
        }
        return j;
    };
    nlohmann::json tried = nlohmann::json::array();
    for (const auto& c : report.tried) tried.push_back(candidate(c));
    nlohmann::json j{{"bytes", report.bytes},
                     {"chosen", candidate(report.chosen)},
                     {"candidates", tried},
                     {"seconds", report.seconds},
                     {"seconds_by_phase", report.phases.toJson()},
                     {"map_bits", report.shipped.mapBits},
                     {"appearance_quality", report.shipped.appearanceQuality},
                     {"over_budget", report.shipped.bytes > report.bytes}};
    if (report.derived) j["derived_from"] = {{"reference_compressed", report.compressedReference}};
    return j;
}

}  // namespace subdfit::simplify
