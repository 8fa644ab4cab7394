#include "simplify/budget_search.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "export/subd_format.h"
#include "simplify/bake.h"
#include "simplify/initial_cage.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

// A decimated cage costs about this many bytes per triangle in asset.subd (Draco connectivity
// and 14-bit positions; 2.8 KB for a 1 000-triangle bunny cage): where the ladder starts.
constexpr double kBytesPerCageFace = 2.5;
constexpr double kLadderStep = 1.6;
constexpr int kLadderLength = 7;
constexpr int kFewestFaces = 24;

std::string describe(const BudgetCandidate& c) {
    char line[160];
    std::snprintf(line, sizeof line, "%6d faces, maps %-19s T=%d, %2d bits: %8ju bytes", c.faces,
                  maps::toString(c.maps).c_str(), c.mapResolution, c.mapBits, c.bytes);
    std::string text = line;
    if (c.monitorLoss > 0.0) {
        std::snprintf(line, sizeof line, ", monitor loss %.4g", c.monitorLoss);
        text += line;
    }
    return text;
}

// A candidate as it ships: encoded (its bytes) and decoded again (what is judged).
struct Shipped {
    std::uintmax_t bytes = 0;
    exporter::SubdAsset decoded;
};

Shipped ship(const mesh::PolygonMesh& cageWorld, surface::SurfaceMaps maps, int mapBits, float frameScale) {
    for (float& d : maps.displacement) d /= frameScale;  // heights in world units, as shipped
    const exporter::SubdPrecision precision{.displacementBits = mapBits, .normalBits = std::min(mapBits, 10)};
    const auto bytes = exporter::encodeSubd(exporter::shippableAsset(cageWorld, maps, precision.positionBits), precision);
    return {bytes.size(), exporter::decodeSubd(bytes, "budget candidate")};
}

// The decoded candidate rendered on the monitor views.
double monitorLoss(gl::ProgramCache& programs, const fit::FitScene& scene, const exporter::SubdAsset& shipped) {
    mesh::PolygonMesh cage = shipped.cage;
    cage.positions = scene.frame.toNormalized(cage.positions);
    const surface::SurfaceMaps& maps = shipped.maps;
    fit::CageFitSettings rendering;
    rendering.mapEffects = {.displacement = maps.hasDisplacement(), .normalMap = maps.hasNormal()};
    rendering.maps.resolution = std::max(maps.layout.resolution, 1);
    fit::CageFitter fitter(programs, cage, rendering);
    if (auto* g = rendering.mapEffects.any() ? fitter.maps()->displacement() : nullptr) {
        std::vector<float> heights = maps.displacement;
        for (float& d : heights) d *= scene.frame.scale;
        g->write(heights);
    }
    if (auto* g = rendering.mapEffects.any() ? fitter.maps()->normalMap() : nullptr) g->write(maps.normal);
    return fit::score(fitter, scene.monitor).loss;
}

}  // namespace

std::vector<int> faceCountsFor(std::uintmax_t budget, int referenceTriangles, int mostFaces) {
    const double largest = std::min({double(budget) / kBytesPerCageFace, 0.5 * double(referenceTriangles), double(mostFaces)});
    std::vector<int> counts;
    for (double f = largest; f >= kFewestFaces && int(counts.size()) < kLadderLength; f /= kLadderStep)
        counts.push_back(int(std::lround(f)));
    if (counts.empty()) counts.push_back(std::min(kFewestFaces, std::max(referenceTriangles, 4)));
    return counts;
}

BudgetChoice searchBudget(gl::ProgramCache& programs, const fit::FitScene& scene,
                          const mesh::PolygonMesh& referenceWorld, const BudgetSearch& search,
                          const std::function<void(const std::string&)>& say) {
    BudgetChoice choice;
    bool found = false;
    auto consider = [&](const BudgetCandidate& c, const mesh::PolygonMesh& cageWorld) {
        choice.tried.push_back(c);
        if (say) say(describe(c) + (c.bytes > search.budget ? " (over budget)" : ""));
        if (c.bytes > search.budget) return;
        if (c.maps.any() && (!choice.bestWithMaps || c.monitorLoss < choice.bestWithMaps->monitorLoss)) {
            choice.bestWithMaps = c;
            choice.bestWithMapsCage = cageWorld;
        }
        if (found && c.monitorLoss >= choice.chosen.monitorLoss) return;
        choice.chosen = c;
        choice.cageWorld = cageWorld;
        found = true;
    };
    // Geometry first: a normal map alone would buy image quality with no surface distance.
    std::vector<maps::MapEffects> mapChoices;
    if (search.allowedMaps.displacement) mapChoices.push_back({.displacement = true});
    if (search.allowedMaps.displacement && search.allowedMaps.normalMap)
        mapChoices.push_back({.displacement = true, .normalMap = true});

    for (int faces : search.faceCounts) {
        throwIfStopRequested();
        mesh::PolygonMesh cageWorld;
        try {
            cageWorld = initialCage(referenceWorld, {.faces = faces});
        } catch (const Error&) {
            continue;  // too few faces survive: smaller counts will not do better
        }
        mesh::PolygonMesh cage = cageWorld;
        cage.positions = scene.frame.toNormalized(cageWorld.positions);
        const Shipped bareShipped = ship(cageWorld, {}, 0, scene.frame.scale);
        BudgetCandidate bare{.faces = cage.faceCount(), .maps = {}, .mapResolution = 0, .mapBits = 0, .bytes = bareShipped.bytes};
        if (bare.bytes <= search.budget) bare.monitorLoss = monitorLoss(programs, scene, bareShipped.decoded);
        consider(bare, cageWorld);  // over budget, it is listed so the report shows why
        if (bare.bytes > search.budget) continue;
        for (const maps::MapEffects& effects : mapChoices)
            for (int resolution : search.mapResolutions) {
                throwIfStopRequested();
                const auto baked = bakeMaps(cage, scene.reference, {.effects = effects, .resolution = resolution});
                bool fitted = false;
                for (int bits : search.mapBits) {
                    const Shipped shipped = ship(cageWorld, baked, bits, scene.frame.scale);
                    BudgetCandidate c{.faces = cage.faceCount(), .maps = effects, .mapResolution = resolution,
                                      .mapBits = bits, .bytes = shipped.bytes};
                    if (c.bytes <= search.budget) {
                        c.monitorLoss = monitorLoss(programs, scene, shipped.decoded);
                        fitted = true;
                    }
                    consider(c, cageWorld);
                    if (c.bytes > search.budget) break;  // more bits only cost more
                }
                if (!fitted) break;  // finer maps only cost more
            }
    }
    if (!found)
        throw fileError(referenceWorld.sourcePath, "no cage fits in " + std::to_string(search.budget) +
                                                       " bytes (the smallest tried needs " +
                                                       std::to_string(choice.tried.empty() ? 0 : choice.tried.back().bytes) +
                                                       "); raise --budget");
    return choice;
}

nlohmann::json toJson(const BudgetChoice& choice, std::uintmax_t budget) {
    auto candidate = [](const BudgetCandidate& c) {
        nlohmann::json j{{"faces", c.faces}, {"maps", maps::toString(c.maps)}, {"map_resolution", c.mapResolution},
                         {"map_bits", c.mapBits}, {"bytes", c.bytes}};
        if (c.monitorLoss > 0.0) j["monitor_loss"] = c.monitorLoss;
        return j;
    };
    nlohmann::json tried = nlohmann::json::array();
    for (const auto& c : choice.tried) tried.push_back(candidate(c));
    return {{"bytes", budget}, {"chosen", candidate(choice.chosen)}, {"candidates", tried}};
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
