#include "simplify/route.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util/error.h"

namespace subdfit::simplify {
namespace {

std::string decibels(double db) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f dB", db);
    return text;
}

// A triangle route ships as asset.glb (its .glb as the baseline wrote it).
Route triangleRoute(const TriangleChoice& triangles, std::string why) {
    return {.shipped = triangles.name, .path = "asset.glb", .why = std::move(why)};
}

}  // namespace

std::uintmax_t defaultBudget(std::uintmax_t compressedReference) {
    return std::min(compressedReference, std::max(compressedReference / 10, kSmallestDefaultBudget));
}

TriangleChoice bestTriangleRoute(std::span<const MadeBaseline> made) {
    TriangleChoice best;
    for (const MadeBaseline& b : made) {
        if (b.quality.details.value("over_budget", false)) continue;
        if (!best.quality || b.quality.psnrHoldout > best.quality->psnrHoldout) best = {b.name, &b.quality};
    }
    return best;
}

Route chooseRoute(const Quality& cage, const TriangleChoice& triangles, std::optional<std::uintmax_t> budget) {
    if (!triangles.quality) return {.why = "no triangle route fits the budget"};
    if (budget && cage.bytes > *budget)
        return triangleRoute(triangles, "the cage codes to " + std::to_string(cage.bytes) +
                                            " bytes, over the budget: " + triangles.name +
                                            " ships, the best triangle route within it");
    const double lead = cage.psnrHoldout - triangles.quality->psnrHoldout;
    if (lead >= 0.0)
        return {.why = "the cage leads the best triangle route (" + triangles.name + ") by " + decibels(lead) +
                       " on the held-out views at the budget"};
    return triangleRoute(triangles, triangles.name + " leads the fitted cage by " + decibels(-lead) +
                                        " on the held-out views at the budget");
}

std::optional<Route> routeBeforeFit(const TriangleChoice& triangles, Holds holds,
                                    std::optional<double> candidateMonitorPsnr) {
    if (!triangles.quality) return std::nullopt;
    if (holds == Holds::Whole)
        return triangleRoute(triangles, "the reference fits the budget whole (" +
                                            std::to_string(triangles.quality->bytes) +
                                            " bytes compressed): nothing to simplify");
    if (holds == Holds::EveryTriangle)
        return triangleRoute(triangles,
                             "decimation holds every triangle of the reference within the budget, which a "
                             "cage's limit surface only approximates (" +
                                 triangles.name + " scores best of the triangle routes): no cage tried");
    if (!candidateMonitorPsnr) return std::nullopt;
    const double lead = triangles.quality->details.value("monitor_psnr", 0.0) - *candidateMonitorPsnr;
    if (*candidateMonitorPsnr < leastFittedMonitorPsnr(triangles))
        return triangleRoute(triangles, triangles.name + " leads the best cage candidate by " + decibels(lead) +
                                            " on the monitor views, more than a fit gains (" +
                                            decibels(kMostFitGainDb) + "): no cage fitted");
    return std::nullopt;
}

double leastFittedMonitorPsnr(const TriangleChoice& triangles) {
    if (!triangles.quality) return -INFINITY;
    return triangles.quality->details.value("monitor_psnr", 0.0) - kMostFitGainDb;
}

std::optional<Route> routeWithoutCage(const TriangleChoice& triangles, const std::string& why) {
    if (!triangles.quality) return std::nullopt;
    return triangleRoute(triangles, why + ": " + triangles.name + " ships, the best triangle route within it");
}

nlohmann::json toJson(const Route& route) {
    return {{"shipped", route.shipped}, {"path", route.path.generic_string()}, {"why", route.why}};
}

}  // namespace subdfit::simplify
