#pragma once
// What `simplify` ships: its fitted cage only where that wins. Where the reference is already
// light, or a triangle mesh (the reference decimated, Draco- or meshopt-compressed, with its
// materials) ships better at the budget, that triangle mesh ships instead, and report.json's
// `route` says which and why. How much of the comparison is also made is `--compare`'s to say.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "simplify/compare/compare_level.h"
#include "simplify/compare/quality.h"
#include "simplify/compare/triangle_baseline.h"
#include "util/named_enum.h"

namespace subdfit::simplify {

// Without --budget or --faces: a tenth of the reference compressed (what the triangle route ships
// holding all of it), never under kSmallestDefaultBudget, and never over the reference compressed:
// a light reference gets its whole self, which nothing simplified beats.
inline constexpr std::uintmax_t kSmallestDefaultBudget = 16000;
std::uintmax_t defaultBudget(std::uintmax_t compressedReference);

// What shipped and why.
struct Route {
    std::string shipped = "cage";               // "cage", "decimation" or "gltfpack"
    std::filesystem::path path = "asset.subd";  // in the output folder
    std::string why;
};

// A cage's fit gains at most this much over the candidate it starts from on the monitor views
// (docs/results.md): a triangle route ahead of the chosen candidate by more is shipped unfitted.
inline constexpr double kMostFitGainDb = 1.5;

// The triangle route that scores best on the held-out views of those made within the budget,
// with its name; none when none is.
struct TriangleChoice {
    std::string name;
    const Quality* quality = nullptr;
};
TriangleChoice bestTriangleRoute(std::span<const MadeBaseline> made);

// The cage, unless `triangles` scores better on the held-out views at the budget, or the cage
// codes over `budget` (where one was set) and a triangle route fits it.
Route chooseRoute(const Quality& cage, const TriangleChoice& triangles,
                  std::optional<std::uintmax_t> budget = std::nullopt);

// Before any fit: the triangle route, when it holds every triangle of the reference (a cage's
// limit surface only approximates them, and its appearance comes from the same textures), or
// when it leads the chosen cage candidate (`candidateMonitorPsnr`, once the search has chosen
// one) on the monitor views by more than a fit gains.
std::optional<Route> routeBeforeFit(const TriangleChoice& triangles, Holds holds,
                                    std::optional<double> candidateMonitorPsnr);

// The monitor PSNR a cage candidate must reach to be fitted at all: below it, `triangles` leads it
// by more than a fit gains (routeBeforeFit ships them). −∞ where no triangle route fits.
double leastFittedMonitorPsnr(const TriangleChoice& triangles);

// Where no cage fits the budget (`why`): the triangle route, if one does.
std::optional<Route> routeWithoutCage(const TriangleChoice& triangles, const std::string& why);

nlohmann::json toJson(const Route& route);

}  // namespace subdfit::simplify
