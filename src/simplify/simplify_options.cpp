#include "simplify/simplify_options.h"

#include <string>
#include <type_traits>

#include "util/error.h"

namespace subdfit::simplify {
namespace detail {

const std::vector<fit::TableRow<SimplifyMember>>& simplifyOptionTable() {
    using S = SimplifyOptions;
    static const std::vector<fit::TableRow<SimplifyMember>> rows = {
        {{.key = "faces",
          .flag = "--faces",
          .help = "faces of the cage, 4..1000000 (default: the budget search's choice; with --budget, fixes the "
                  "cage and the search chooses only the maps; without, the cage is fitted as asked and weighed against "
                  "the triangle route at its bytes)",
          .min = kLeastFaces,
          .max = kMostFaces,
          .setting = true},
         &S::faces},
        {{.key = "cage_shape",
          .flag = "--cage-shape",
          .help =
              "the cage's faces: auto (the budget search's cages are triangles, and its best bare cage is also "
              "remeshed into quads at the same bytes: the better ships), triangles (the reference decimated), quads "
              "(a quad-dominant remesh along the reference's cross field, every cage the search tries) or paired "
              "(the decimated triangles joined in pairs into quads)",
          .setting = true},
         &S::cageShape},
        {{.key = "budget",
          .flag = "--budget",
          .help =
              "bytes what ships may take, 100 B to 1 TB (20000, 20KB, 1.5MB, 2G): chooses the cage, maps and bits to "
              "fit them, or a triangle mesh where one ships better (default: a tenth of the reference compressed, at "
              "least 16 KB)",
          .setting = true},
         &S::budget},
        {{.key = "prefix",
          .flag = "--prefix",
          .help = "with --budget: bytes of the file's first part, 100 B up to the budget, which decodes alone to what "
                  "--budget PREFIX ships; the rest refines its heights to the budget, a file that streams (heights "
                  "alone: an asset with a normal map or an appearance ships as --budget PREFIX would)",
          .setting = true},
         &S::prefix},
        {{.key = "coded_steps",
          .flag = "--coded-steps",
          .help = "at most this many steps fitting the heights as the decoder reads them (which way each rounds), "
                  "after the fit, judged every 25 steps; what ships is replaced where they draw closer within the "
                  "budget (default 0: none; 200 is a run's worth)",
          .min = 0,
          .max = 100000,
          .setting = true},
         &S::codedSteps},
        {{.key = "surface_samples",
          .flag = "",
          .help = "surface samples per side, for Chamfer and Hausdorff",
          .min = 1000,
          .max = 1e9,
          .setting = true},
         &S::surfaceSamples},
        {{.key = "compare",
          .flag = "--compare",
          .help =
              "what is compared beside what ships: none (only what chooses the route), fast (+ the triangle "
              "baselines' files and scores), full (+ the bake route, surface distances, comparison.png), all (+ every "
              "triangle baseline, those that rarely lead too)",
          .setting = true},
         &S::compare},
        {{.key = "route",
          .flag = "--route",
          .help = "auto: ship the cage only where it wins, else the better triangle mesh; cage: ship the fitted cage "
                  "whatever the triangle route scores",
          .setting = true},
         &S::route},
    };
    return rows;
}

}  // namespace detail

void validate(const SimplifyOptions& o) {
    if (o.faces && (*o.faces < kLeastFaces || *o.faces > kMostFaces))
        throw OptionError("faces", "must be in 4..1000000, got " + std::to_string(*o.faces));
    if (o.budget && *o.budget < 100) throw OptionError("budget", "must be at least 100 bytes");
    if (o.prefix && !o.budget) throw OptionError("prefix", "needs --budget: the bytes the whole file grows to");
    if (o.prefix && (*o.prefix < 100 || *o.prefix >= *o.budget))
        throw OptionError("prefix", "must be at least 100 bytes and under the budget (" + std::to_string(*o.budget) +
                                        "), got " + std::to_string(*o.prefix));
    if (o.surfaceSamples < 1000) throw OptionError("surface_samples", "must be >= 1000");
    if (o.fit.appearanceAtlas > 0 && o.fit.maps.has(maps::MapKind::NormalMap))
        throw OptionError("appearance_atlas",
                          "takes heights alone (--maps displacement): the atlas's texture coordinates "
                          "leave the shipped glTF no room for a normal map on tiles");
    fit::validate(o.fit);
}

nlohmann::json settingsJson(const SimplifyOptions& o) {
    nlohmann::json settings = fit::settingsJson(o.fit);
    forEachSimplifyOption(o, [&](const fit::OptionInfo& info, const auto& value) {
        using T = std::decay_t<decltype(value)>;
        if (!info.setting) return;
        if constexpr (fit::WordOption<T>) settings[info.key] = fit::optionText(value);
        else if constexpr (std::is_arithmetic_v<T>) settings[info.key] = value;
        else settings[info.key] = value.value_or(0);  // as a batch asset's identity hashes "not given"
    });
    return settings;
}

}  // namespace subdfit::simplify
