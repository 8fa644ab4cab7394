#pragma once
// The options of one `simplify`: on the command line of `subdfit simplify`, and on each line of
// a `subdfit batch` manifest (where they override the batch's own).
#include <CLI/CLI.hpp>

#include "common/fit_cli.h"
#include "simplify/simplify_job.h"

namespace subdfit::apps {

// Everything but the reference and --out.
inline void addSimplifySettings(CLI::App& app, simplify::SimplifyOptions& options) {
    app.add_option("--faces", options.faces, "triangles of the cage")->capture_default_str();
    addFitSettings(app, options.fit);
}

}  // namespace subdfit::apps
