#pragma once
// What a user asks of a `simplify`: a fit's options (fit/fit_options.h) with simplify's defaults,
// and simplify's own, described once like the fit's: each a row of a table (its key in a batch
// asset's settings, its flag and help, its range). The command line of `simplify`, `batch` and a
// manifest's lines (apps/common/simplify_cli.h) and settingsJson() are made from both tables.
#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "fit/fit_options.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/route.h"
#include "util/named_enum.h"

namespace subdfit::simplify {

// What ships: the better route (auto), or the fitted cage whatever the triangle route scores
// (for a user who needs a subdivision surface to edit or animate). The triangle route is weighed
// and reported either way.
enum class RouteChoice { Auto, Cage };

}  // namespace subdfit::simplify

template <>
struct subdfit::EnumNames<subdfit::simplify::RouteChoice> {
    static constexpr std::array names{std::pair{simplify::RouteChoice::Auto, std::string_view("auto")},
                                      std::pair{simplify::RouteChoice::Cage, std::string_view("cage")}};
};

namespace subdfit::simplify {

// What `simplify` changes of a fit's defaults (with --faces and no budget; a budget's search
// chooses these): a displacement map (shading normals come from its
// derivatives: in every budget search so far a normal map cost more than it gave), at a
// resolution a light asset can afford, shipped compact; and the cage fitted alone for most of
// the run, since the maps are baked onto it and only refined (see simplify_job.cpp).
inline fit::FitOptions simplifyFitDefaults() {
    fit::FitOptions o;
    o.maps = {maps::MapKind::Displacement};
    o.mapResolution = 4;
    o.mapsStart = 0.8f;
    o.compactMaps = true;
    return o;
}

struct SimplifyOptions {
    fit::FitOptions fit = simplifyFitDefaults();  // fit.reference: the dense asset; fit.cage is set by simplify
    std::optional<int> faces;                     // of the cage; none: chosen by the budget
    CageShape cageShape = CageShape::Auto;
    // Bytes what ships may take (simplify/budget_search.h). Without it or `faces`, defaultBudget()
    // of the reference; with `faces` alone, the cage is fitted as asked and the triangle route
    // weighed at its bytes.
    std::optional<std::uintmax_t> budget;
    // With a budget: the file's first bytes, which decode alone to the asset --budget PREFIX
    // ships; the rest, to the budget, refines its heights (simplify/prefix_growth.h).
    std::optional<std::uintmax_t> prefix;
    int surfaceSamples = 100000;  // per side, for Chamfer and Hausdorff
    // Steps of the heights' fit on what the decoder reads (fit/coded_refinement.h), after the fit;
    // 0: none. Off by default: it gains under 0.1 dB held out for its seconds (docs/simplify.md).
    int codedSteps = 0;
    CompareLevel compare = CompareLevel::Full;
    RouteChoice route = RouteChoice::Auto;
};

// The cage's faces with neither --faces nor a budget, and what the budget search's limits are
// scaled from (simplify_plan.cpp).
inline constexpr int kDefaultFaces = 1000;

// The cage sizes --faces takes.
inline constexpr int kLeastFaces = 4, kMostFaces = 1000000;

namespace detail {
// An optional number is "not given" unless set, 0 in the settings; the optional byte count is a size.
using SimplifyMember = std::variant<int SimplifyOptions::*, std::optional<int> SimplifyOptions::*,
                                    std::optional<std::uintmax_t> SimplifyOptions::*, CompareLevel SimplifyOptions::*,
                                    RouteChoice SimplifyOptions::*, CageShape SimplifyOptions::*>;
const std::vector<fit::TableRow<SimplifyMember>>& simplifyOptionTable();
}  // namespace detail

// Calls visit(info, field) for each of simplify's own options (not the fit's), as
// fit::forEachOption does.
template <class Options, class Visitor>
void forEachSimplifyOption(Options& options, Visitor&& visit) {
    fit::forEachRow(detail::simplifyOptionTable(), options, visit);
}

// Throws subdfit::Error ("invalid option: ...") before any work.
void validate(const SimplifyOptions& options);

// The fit's settings (fit::settingsJson) and simplify's own, by key: what tells one batch
// asset's output from another's. An option not given is 0.
nlohmann::json settingsJson(const SimplifyOptions& options);

}  // namespace subdfit::simplify
