#pragma once
// The options of one `simplify`: on the command line of `subdfit simplify`, and on each line of
// a `subdfit batch` manifest (where they override the batch's own).
#include <CLI/CLI.hpp>

#include "common/byte_size.h"
#include "common/fit_cli.h"
#include "simplify/simplify_job.h"

namespace subdfit::apps {

// Everything but the reference and --out.
inline void addSimplifySettings(CLI::App& app, simplify::SimplifyOptions& options) {
    app.add_option("--faces", options.faces,
                   "triangles of the cage, 4..1000000 (default " + std::to_string(simplify::kDefaultFaces) +
                       "; with --budget, fixes the cage and the search chooses only the maps)")
        ->check(CLI::Range(4, 1000000));
    // Checked while parsing, so a bad budget is a usage error naming the flag.
    const CLI::Validator byteSize(
        [](std::string& text) {
            std::string problem;
            return parseByteSize(text, problem) ? std::string() : problem;
        },
        "BYTES");
    app.add_option_function<std::string>(
           "--budget",
           [&options](const std::string& text) {
               std::string problem;
               options.budget = parseByteSize(text, problem).value_or(0);
           },
           "bytes asset.subd may take, 100 B to 1 TB (20000, 20KB, 1.5MB, 2G): chooses the cage, maps and bits to fit them")
        ->check(byteSize);
    addFitSettings(app, options.fit);
}

}  // namespace subdfit::apps
