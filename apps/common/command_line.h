#pragma once
// How every subdfit program reads its command line: --help prints and exits 0; anything the
// parser refuses is one line on stderr, "PROGRAM: error: ... (see --help)", and exit code 2.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include "fit/fit_options.h"

namespace subdfit::apps {

// Nothing when the program should go on; otherwise the exit code to return from main.
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv, const char* program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "%s: error: %s (see --help)\n", program, e.what());
        return 2;
    }
    return std::nullopt;
}

// What an error says on the command line: the core names an option by its key in report.json
// ("map_resolution"); a user typed its flag ("--map-res").
inline std::string describeError(const std::exception& error) {
    if (const auto* option = dynamic_cast<const OptionError*>(&error)) {
        std::string flag = fit::optionFlag(option->key());
        if (flag.empty()) {  // options outside the fit's table (--faces, --shard, --out) are spelled alike
            flag = "--" + option->key();
            std::replace(flag.begin(), flag.end(), '_', '-');
        }
        return "invalid option: " + flag + " " + option->problem();
    }
    return error.what();
}

}  // namespace subdfit::apps
