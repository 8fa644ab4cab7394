#pragma once
// The options of one `simplify`: on the command line of `subdfit simplify`, and on each line of
// a `subdfit batch` manifest (where they override the batch's own).
#include <CLI/CLI.hpp>

#include "common/fit_cli.h"
#include "simplify/budget_search.h"
#include "util/error.h"
#include "simplify/simplify_job.h"

namespace subdfit::apps {

// Everything but the reference and --out.
inline void addSimplifySettings(CLI::App& app, simplify::SimplifyOptions& options) {
    app.add_option("--faces", options.faces,
                   "triangles of the cage (default " + std::to_string(simplify::kDefaultFaces) +
                       "; with --budget, fixes the cage and the search chooses only the maps)");
    // Checked while parsing, so a bad budget is a usage error naming the flag.
    const CLI::Validator byteSize(
        [](std::string& text) {
            try {
                simplify::parseByteSize(text);
                return std::string();
            } catch (const OptionError& e) {
                return e.problem();
            }
        },
        "BYTES");
    app.add_option_function<std::string>(
           "--budget", [&options](const std::string& text) { options.budget = simplify::parseByteSize(text); },
           "bytes asset.subd may take (20000, 20KB, 1.5MB): chooses the cage, maps and bits to fit them")
        ->check(byteSize);
    addFitSettings(app, options.fit);
}

}  // namespace subdfit::apps
