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
                   "triangles of the cage, 4..1000000 (default: the budget search's choice; with --budget, fixes the "
                   "cage and the search chooses only the maps; without, the cage is fitted as asked and weighed against "
                   "the triangle route at its bytes)")
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
           "bytes what ships may take, 100 B to 1 TB (20000, 20KB, 1.5MB, 2G): chooses the cage, maps and bits to fit "
           "them, or a triangle mesh where one ships better (default: a tenth of the reference compressed, at least 16 KB)")
        ->check(byteSize);
    addNamedOption(app, "--compare", options.compare,
                   "what is compared beside what ships: none (only what chooses the route), fast (+ the triangle "
                   "baselines' files and scores), full (+ the bake route, surface distances, comparison.png)");
    app.add_option_function<std::string>(
           "--route", [&options](const std::string& text) { options.cageOnly = text == "cage"; },
           "auto: ship the cage only where it wins, else the better triangle mesh (default); cage: ship the fitted cage "
           "whatever the triangle route scores")
        ->check(CLI::IsMember({"auto", "cage"}));
    addFitSettings(app, options.fit);
}

}  // namespace subdfit::apps
