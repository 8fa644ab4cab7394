#include "simplify/budget_search.h"
#include "fit/fit_run.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "export/subd_format.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/initial_cage.h"
#include "util/error.h"
#include "util/interrupt.h"

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

std::string describe(const BudgetCandidate& c) {
    char line[160];
    std::snprintf(line, sizeof line, "%6d faces, maps %-19s T=%d, %2d bits: %8ju bytes", c.faces,
                  maps::toString(c.maps).c_str(), c.mapResolution, c.mapBits, c.bytes);
    std::string text = line;
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
    exporter::SubdAsset decoded;
};

Shipped ship(const mesh::PolygonMesh& cageWorld, surface::SurfaceMaps maps, int mapBits, int appearanceQuality,
             float frameScale) {
    for (float& d : maps.displacement) d /= frameScale;  // heights in world units, as shipped
    const auto precision = exporter::SubdPrecision::forMapBits(mapBits, appearanceQuality > 0 ? appearanceQuality : exporter::SubdPrecision{}.appearanceQuality);
    auto encoded = std::make_shared<const std::vector<unsigned char>>(
        exporter::encodeSubd(exporter::shippableAsset(cageWorld, maps, precision.positionBits), precision));
    return {encoded, exporter::decodeSubd(*encoded, "budget candidate")};
}

// The decoded candidate in a fitter of its own, drawn as the fit would draw it.
std::unique_ptr<fit::CageFitter> drawnAsFitted(gl::ProgramCache& programs, const fit::FitScene& scene,
                                               const exporter::SubdAsset& shipped) {
    mesh::PolygonMesh cage = shipped.cage;
    cage.positions = scene.frame.toNormalized(cage.positions);
    surface::SurfaceMaps maps = shipped.maps;
    for (float& d : maps.displacement) d *= scene.frame.scale;
    fit::CageFitSettings rendering;
    rendering.shading = scene.shading;
    rendering.mapEffects = {.displacement = maps.hasDisplacement(), .normalMap = maps.hasNormal(),
                            .baseColor = maps.hasBaseColor(), .metallicRoughness = maps.hasMetallicRoughness()};
    rendering.maps.resolution = std::max(maps.layout.resolution, 1);
    rendering.maps.appearanceResolution = std::max(maps.appearanceLayout.resolution, 1);
    rendering.maps.appearanceAtlas = maps.appearanceAtlas.size;
    rendering.maps.shadingNormal = maps.shadingNormal;
    auto fitter = std::make_unique<fit::CageFitter>(programs, cage, rendering);
    fit::writeMaps(*fitter, maps);
    return fitter;
}

// Its mean loss over the views of each of `viewSets`.
double lossOn(fit::CageFitter& fitter, std::initializer_list<const scene::TargetSet*> viewSets) {
    double weighted = 0.0;
    int views = 0;
    for (const scene::TargetSet* viewSet : viewSets) {
        weighted += fit::score(fitter, *viewSet).loss * viewSet->size();
        views += viewSet->size();
    }
    return weighted / views;
}

// Within this fraction of the lowest monitor loss, fewer bytes win: a difference that small is
// within the monitor's own noise ...
constexpr double kLossTolerance = 0.02;
// ... but only where the bytes saved are worth it: at least this many times the loss given up,
// both relative (a few bytes saved are not worth a loss near the tolerance).
constexpr double kBytesPerLoss = 5.0;
// Four monitor views rank candidates this close to the lowest no better than chance: those
// within this fraction are scored again on the training views too, and the choice among them is
// made on that score.
constexpr double kNearTie = 0.2;

// A candidate within the budget, the cage it was built on and its asset as shipped.
struct Fitting {
    BudgetCandidate candidate;
    std::shared_ptr<const mesh::PolygonMesh> cageWorld;
    std::shared_ptr<const std::vector<unsigned char>> encoded;
    size_t tried;  // its place in Findings::tried
};

double monitored(const BudgetCandidate& c) { return c.monitorLoss; }
double settled(const BudgetCandidate& c) { return c.settledLoss; }

// Of those `keep` accepts, the one of lowest `loss` (none if it accepts none).
template <class Keep, class Loss>
const Fitting* lowestOf(const std::vector<Fitting>& fitting, Keep keep, Loss loss) {
    const Fitting* lowest = nullptr;
    for (const Fitting& f : fitting)
        if (keep(f.candidate) && (!lowest || loss(f.candidate) < loss(lowest->candidate))) lowest = &f;
    return lowest;
}

// Of those `keep` accepts, the fewest bytes within kLossTolerance of the lowest `loss` that save
// kBytesPerLoss times the loss they give up.
template <class Keep, class Loss>
const Fitting* preferred(const std::vector<Fitting>& fitting, Keep keep, Loss loss) {
    const Fitting* lowest = lowestOf(fitting, keep, loss);
    if (!lowest) return nullptr;
    const double lowestLoss = loss(lowest->candidate), bytes = double(lowest->candidate.bytes);
    const Fitting* best = lowest;
    for (const Fitting& f : fitting) {
        const double lossGivenUp = loss(f.candidate) / lowestLoss - 1.0, bytesSaved = 1.0 - double(f.candidate.bytes) / bytes;
        if (keep(f.candidate) && lossGivenUp <= kLossTolerance && bytesSaved >= kBytesPerLoss * lossGivenUp &&
            f.candidate.bytes < best->candidate.bytes)
            best = &f;
    }
    return best;
}

// preferred() among those `keep` accepts within kNearTie of the lowest monitor loss, on their
// loss over the monitor and training views (scored here where not yet).
template <class Keep>
const Fitting* settle(gl::ProgramCache& programs, const fit::FitScene& scene, std::vector<Fitting>& fitting, Keep keep) {
    const Fitting* lowest = lowestOf(fitting, keep, monitored);
    if (!lowest) return nullptr;
    const double within = (1.0 + kNearTie) * lowest->candidate.monitorLoss;
    for (Fitting& f : fitting) {
        if (!keep(f.candidate) || f.candidate.monitorLoss > within || f.candidate.settledLoss > 0.0) continue;
        throwIfStopRequested();
        const auto shipped = exporter::decodeSubd(*f.encoded, "budget candidate");
        f.candidate.settledLoss = lossOn(*drawnAsFitted(programs, scene, shipped), {&scene.monitor, &scene.training});
    }
    return preferred(fitting, [&](const BudgetCandidate& c) { return keep(c) && c.settledLoss > 0.0; }, settled);
}

// What the search works on, the same for its whole run.
struct SearchInputs {
    gl::ProgramCache& programs;
    const fit::FitScene& scene;
    const mesh::PolygonMesh& referenceWorld;  // what cages are decimated from
    const BudgetSearch& search;
    const std::function<void(const std::string&)>& say;
};

// What the search has found so far: every candidate tried, in order (the report lists them all),
// and those within the budget.
struct Findings {
    std::vector<BudgetCandidate> tried;
    std::vector<Fitting> fitting;
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

// A cage of (about) `faces` triangles, or none when too few faces survive decimation.
std::optional<TriedCage> cageOf(const SearchInputs& in, int faces) {
    throwIfStopRequested();
    try {
        auto world = std::make_shared<const mesh::PolygonMesh>(initialCage(in.referenceWorld, {.faces = faces}));
        mesh::PolygonMesh normalized = *world;
        normalized.positions = in.scene.frame.toNormalized(world->positions);
        return TriedCage{std::move(world), std::move(normalized)};
    } catch (const Error&) {
        return std::nullopt;
    }
}

// Geometry first: a normal map alone would buy image quality with no surface distance.
std::vector<maps::MapEffects> mapChoicesOf(const BudgetSearch& search) {
    std::vector<maps::MapEffects> choices;
    if (search.allowedMaps.displacement) choices.push_back({.displacement = true});
    if (search.allowedMaps.displacement && search.allowedMaps.normalMap)
        choices.push_back({.displacement = true, .normalMap = true});
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

// A candidate within the budget, scored on the monitor views as the fit would draw it. Heights
// baked onto a faceted reference copy its facets into the shading, which the limit normal does
// not, but a coarse cage needs the heights' slopes to shade its shape: with heights both are
// judged, and when the limit normal wins, `baked` takes its flag and is shipped again with it.
void scoreOnMonitor(const SearchInputs& in, const mesh::PolygonMesh& cageWorld, surface::SurfaceMaps& baked,
                    const Appearance& appearance, BudgetCandidate& c, Shipped& shipped) {
    const auto drawn = drawnAsFitted(in.programs, in.scene, shipped.decoded);
    c.monitorLoss = lossOn(*drawn, {&in.scene.monitor});
    if (!c.maps.displacement) return;
    drawn->maps()->setShadingNormal(surface::ShadingNormal::Limit);
    if (const double loss = lossOn(*drawn, {&in.scene.monitor}); loss < c.monitorLoss) {
        c.monitorLoss = loss;
        c.shadingNormal = baked.shadingNormal = surface::ShadingNormal::Limit;
        shipped = ship(cageWorld, baked, c.mapBits, appearance.quality, in.scene.frame.scale);
    }
}

// Judges one candidate: the cage with `baked` maps (laid out on it, as `recipe` says) and
// `appearance`, encoded and decoded as it ships, scored when it fits. Every candidate is
// recorded, those over the budget too, so that the report shows why they lost.
BudgetCandidate judge(const SearchInputs& in, Findings& found, const std::shared_ptr<const mesh::PolygonMesh>& cageWorld,
                      surface::SurfaceMaps baked, const MapRecipe& recipe, const Appearance& appearance) {
    baked.setAppearance(appearance.maps);
    Shipped shipped = ship(*cageWorld, baked, recipe.bits, appearance.quality, in.scene.frame.scale);
    const bool atlas = appearance.maps.appearanceAtlas.present();
    BudgetCandidate c{.faces = cageWorld->faceCount(), .maps = recipe.effects, .mapResolution = recipe.resolution,
                      .mapBits = recipe.bits, .appearanceResolution = atlas ? 0 : appearance.maps.appearanceLayout.resolution,
                      .appearanceQuality = appearance.quality, .appearanceAtlas = appearance.maps.appearanceAtlas.size,
                      .bytes = shipped.encoded->size()};
    const bool within = fits(in.search, c);
    if (within) scoreOnMonitor(in, *cageWorld, baked, appearance, c, shipped);
    found.tried.push_back(c);
    if (in.say) in.say(describe(c) + (within ? "" : " (over budget)"));
    if (within) found.fitting.push_back({c, cageWorld, shipped.encoded, found.tried.size() - 1});
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
// that kind only cost more.
std::vector<Bare> judgeBare(const SearchInputs& in, Findings& found, const TriedCage& cage,
                            const std::vector<AppearanceBakeOptions>& appearances) {
    std::vector<Bare> bare;
    for (size_t a = 0; a < appearances.size(); ++a) {
        const bool withAppearance = appearances[a].resolution > 0 || appearances[a].atlas > 0;
        Appearance appearance{.maps = withAppearance ? bakeAppearance(cage.normalized, in.scene.reference, appearances[a])
                                                     : surface::SurfaceMaps{}};
        // Without materials there is no quality to choose (0).
        const std::vector<int> qualities = withAppearance ? in.search.appearanceQualities : std::vector<int>{0};
        BudgetCandidate c;
        for (size_t q = 0; q < qualities.size() && (q == 0 || !fits(in.search, c)); ++q) {
            appearance.quality = qualities[q];
            c = judge(in, found, cage.world, {}, {}, appearance);
        }
        if (fits(in.search, c)) {
            bare.push_back({appearances[a].atlas > 0, std::move(appearance), c});
            continue;
        }
        while (a + 1 < appearances.size() && (appearances[a + 1].atlas > 0) == (appearances[a].atlas > 0)) ++a;
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
            return p.bytes <= q.bytes && p.monitorLoss <= q.monitorLoss && (p.bytes < q.bytes || p.monitorLoss < q.monitorLoss);
        });
        if (!dominated) worth.push_back(&b);
    }
    std::sort(worth.begin(), worth.end(), [](const Bare* x, const Bare* y) { return x->candidate.monitorLoss < y->candidate.monitorLoss; });
    if (worth.size() > kMostAppearancesWithMaps) worth.resize(kMostAppearancesWithMaps);
    return worth;
}

// Phase three on a cage: the map ladder on each appearance worth it, each choice of maps at each
// resolution, coarsest first, and at each bit depth while it fits: more bits and finer maps
// only cost more, so a rung over the budget ends its ladder. Maps are baked once per (choice,
// resolution) on the cage.
void climbMapLadder(const SearchInputs& in, Findings& found, const TriedCage& cage, const std::vector<const Bare*>& worth,
                    const std::vector<maps::MapEffects>& mapChoices) {
    std::map<std::pair<size_t, int>, surface::SurfaceMaps> geometric;
    for (const Bare* b : worth) {
        for (size_t m = 0; m < mapChoices.size(); ++m) {
            if (b->inAtlas && mapChoices[m].normalMap) continue;  // an atlas takes heights alone
            for (int resolution : in.search.mapResolutions) {
                throwIfStopRequested();
                auto baked = geometric.find({m, resolution});
                if (baked == geometric.end())
                    baked = geometric.emplace(std::make_pair(m, resolution),
                                              bakeMaps(cage.normalized, in.scene.reference, {.effects = mapChoices[m], .resolution = resolution}))
                                .first;
                bool fitted = false;
                for (int bits : in.search.mapBits) {
                    const MapRecipe recipe{.effects = mapChoices[m], .resolution = resolution, .bits = bits};
                    if (!fits(in.search, judge(in, found, cage.world, baked->second, recipe, b->appearance))) break;
                    fitted = true;
                }
                if (!fitted) break;
            }
        }
    }
}

// Phase four: the ladder's steps leave bytes unspent. The preferred kind of asset so far on a
// cage grown to what the budget holds (bytes grow about in proportion to the faces), shrinking
// until it fits.
void growBest(const SearchInputs& in, Findings& found) {
    const Fitting* ladderBest = preferred(found.fitting, [](const BudgetCandidate&) { return true; }, monitored);
    if (!ladderBest) return;
    const BudgetCandidate best = ladderBest->candidate;
    double scale = 0.97 * double(in.search.budget) / double(best.bytes);
    for (int attempt = 0; attempt < 3 && scale > 1.05; ++attempt, scale = 1.0 + 0.6 * (scale - 1.0)) {
        const int faces = std::min(int(std::lround(best.faces * scale)), in.search.faceCounts.front());
        if (faces <= int(best.faces * 1.05)) break;
        const std::optional<TriedCage> cage = cageOf(in, faces);
        if (!cage) break;
        Appearance appearance;
        appearance.quality = best.appearanceQuality;
        if (best.appearanceResolution > 0 || best.appearanceAtlas > 0)
            appearance.maps = bakeAppearance(cage->normalized, in.scene.reference,
                                             {.effects = in.search.appearance, .resolution = best.appearanceResolution,
                                              .atlas = best.appearanceAtlas});
        const surface::SurfaceMaps baked =
            best.maps.any() ? bakeMaps(cage->normalized, in.scene.reference, {.effects = best.maps, .resolution = best.mapResolution})
                            : surface::SurfaceMaps{};
        const MapRecipe recipe{.effects = best.maps, .resolution = best.mapResolution, .bits = best.mapBits};
        if (fits(in.search, judge(in, found, cage->world, baked, recipe, appearance))) break;
    }
}

// Phase five: the near ties settled on the training views too; the chosen candidate, and the
// best with maps (the bake route at these bytes). Throws when nothing fits.
BudgetChoice settleChoice(const SearchInputs& in, Findings& found) {
    const Fitting* chosen = settle(in.programs, in.scene, found.fitting, [](const BudgetCandidate&) { return true; });
    if (!chosen)
        throw fileError(in.referenceWorld.sourcePath, "no cage fits in " + std::to_string(in.search.budget) +
                                                          " bytes (the smallest tried needs " +
                                                          std::to_string(found.tried.empty() ? 0 : found.tried.back().bytes) +
                                                          "); raise --budget");
    BudgetChoice choice;
    choice.chosen = chosen->candidate;
    choice.cageWorld = *chosen->cageWorld;
    if (const Fitting* withMaps =
            settle(in.programs, in.scene, found.fitting, [](const BudgetCandidate& c) { return c.maps.any(); })) {
        choice.bestWithMaps = withMaps->candidate;
        choice.bestWithMapsCage = *withMaps->cageWorld;
    }
    for (const Fitting& f : found.fitting) {
        if (f.candidate.settledLoss <= 0.0) continue;
        found.tried[f.tried].settledLoss = f.candidate.settledLoss;
        if (in.say) {
            char line[80];
            std::snprintf(line, sizeof line, ": loss %.4g on the monitor and training views", f.candidate.settledLoss);
            in.say(describe(f.candidate) + line);
        }
    }
    choice.tried = std::move(found.tried);
    return choice;
}

}  // namespace

std::vector<int> faceCountsFor(std::uintmax_t budget, int referenceTriangles, int mostFaces) {
    const double largest = std::min({double(budget) / kBytesPerCageFace, 0.5 * double(referenceTriangles), double(mostFaces)});
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

BudgetChoice searchBudget(gl::ProgramCache& programs, const fit::FitScene& scene,
                          const mesh::PolygonMesh& referenceWorld, const BudgetSearch& search,
                          const std::function<void(const std::string&)>& say) {
    const SearchInputs in{programs, scene, referenceWorld, search, say};
    const std::vector<AppearanceBakeOptions> appearances = appearancesOf(search);
    const std::vector<maps::MapEffects> mapChoices = mapChoicesOf(search);
    Findings found;
    for (int faces : search.faceCounts) {
        const std::optional<TriedCage> cage = cageOf(in, faces);
        if (!cage) continue;  // smaller counts will not do better
        const std::vector<Bare> bare = judgeBare(in, found, *cage, appearances);
        climbMapLadder(in, found, *cage, worthMaps(bare), mapChoices);
    }
    growBest(in, found);
    return settleChoice(in, found);
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

BudgetShipment shipWithinBudget(const std::filesystem::path& subd, std::uintmax_t bytes, std::uintmax_t budget,
                                int mapBits, int appearanceQuality) {
    auto precision = exporter::SubdPrecision::forMapBits(mapBits, appearanceQuality);
    auto shipment = [&] { return BudgetShipment{precision.displacementBits, precision.appearanceQuality, bytes}; };
    if (bytes <= budget) return shipment();
    const exporter::SubdAsset decoded = exporter::readSubd(subd);
    std::vector<std::pair<int, int>> ladder;  // (bits, quality), coarser and coarser
    // Quality in small steps: a JPEG's bytes fall a few per cent a step, and every byte left is
    // detail lost.
    constexpr int kFewestBits = 6, kLowestQuality = 30, kQualityStep = 5;
    int quality = appearanceQuality;
    if (decoded.maps.hasBaseColor() || decoded.maps.hasMetallicRoughness())
        while (quality - kQualityStep >= kLowestQuality) ladder.emplace_back(mapBits, quality -= kQualityStep);
    for (int bits = mapBits - 1; bits >= kFewestBits; --bits) ladder.emplace_back(bits, quality);
    for (size_t k = 0; k < ladder.size(); ++k) {
        precision = exporter::SubdPrecision::forMapBits(ladder[k].first, ladder[k].second);
        const auto encoded =
            exporter::encodeSubd(exporter::shippableAsset(decoded.cage, decoded.maps, precision.positionBits), precision);
        if (encoded.size() <= budget || k + 1 == ladder.size()) {
            bytes = exporter::writeBytes(subd, encoded).bytes;
            if (bytes <= budget) break;
        }
    }
    return shipment();
}

nlohmann::json toJson(const BudgetReport& report) {
    auto candidate = [](const BudgetCandidate& c) {
        nlohmann::json j{{"faces", c.faces}, {"maps", maps::toString(c.maps)}, {"map_resolution", c.mapResolution},
                         {"map_bits", c.mapBits}, {"bytes", c.bytes}};
        if (c.maps.displacement && c.monitorLoss > 0.0) j["shading_normal"] = nameOf(c.shadingNormal);
        if (c.appearanceResolution > 0) j["appearance_resolution"] = c.appearanceResolution;
        if (c.appearanceAtlas > 0) j["appearance_atlas"] = c.appearanceAtlas;
        if (c.appearanceQuality > 0) j["appearance_quality"] = c.appearanceQuality;
        if (c.monitorLoss > 0.0) j["monitor_loss"] = c.monitorLoss;
        if (c.settledLoss > 0.0) j["settled_loss"] = c.settledLoss;
        return j;
    };
    nlohmann::json tried = nlohmann::json::array();
    for (const auto& c : report.tried) tried.push_back(candidate(c));
    return {{"bytes", report.bytes},
            {"chosen", candidate(report.chosen)},
            {"candidates", tried},
            {"seconds", report.seconds},
            {"map_bits", report.shipped.mapBits},
            {"appearance_quality", report.shipped.appearanceQuality},
            {"over_budget", report.shipped.bytes > report.bytes}};
}

std::uintmax_t parseByteSize(const std::string& text) {
    size_t end = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &end);
    } catch (const std::exception&) {
        throw OptionError("budget", "must be bytes with an optional K or M suffix (20000, 20KB), got '" + text + "'");
    }
    std::string unit = text.substr(end);
    for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
    double scale = 0.0;
    if (unit.empty() || unit == "B") scale = 1.0;
    else if (unit == "K" || unit == "KB") scale = 1e3;
    else if (unit == "M" || unit == "MB") scale = 1e6;
    else if (unit == "KIB") scale = 1024.0;
    else if (unit == "MIB") scale = 1024.0 * 1024.0;
    const double bytes = value * scale;
    if (scale == 0.0 || !std::isfinite(bytes))
        throw OptionError("budget", "must be bytes with an optional K or M suffix (20000, 20KB), got '" + text + "'");
    if (bytes < 100.0 || bytes > 1e12)
        throw OptionError("budget", "must be 100 bytes to 1 TB, got '" + text + "'");
    return std::uintmax_t(std::llround(bytes));
}

}  // namespace subdfit::simplify
