#pragma once
// The options of one `simplify`: on the command line of `subdfit simplify`, and on each line of
// a `subdfit batch` manifest (where they override the batch's own). Registered from simplify's
// table (simplify/simplify_options.h), then the fit's.
#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <type_traits>

#include "common/byte_size.h"
#include "common/fit_cli.h"
#include "simplify/simplify_options.h"

namespace subdfit::apps {

// A byte size (`--budget`), checked while parsing so that a bad one is a usage error naming the flag.
inline void addByteSizeOption(CLI::App& app, const fit::OptionInfo& info, std::optional<std::uintmax_t>& field) {
    const CLI::Validator byteSize(
        [](std::string& text) {
            std::string problem;
            return parseByteSize(text, problem) ? std::string() : problem;
        },
        "BYTES");
    app.add_option_function<std::string>(
           info.flag,
           [&field](const std::string& text) {
               std::string problem;
               field = parseByteSize(text, problem).value_or(0);
           },
           info.help)
        ->check(byteSize);
}

// Everything but the reference and --out. An optional number has no default to show: not
// given, the run chooses it.
inline void addSimplifySettings(CLI::App& app, simplify::SimplifyOptions& options) {
    simplify::forEachSimplifyOption(options, [&](const fit::OptionInfo& info, auto& field) {
        using T = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<T, std::optional<std::uintmax_t>>) {
            addByteSizeOption(app, info, field);
        } else if constexpr (std::is_same_v<T, std::optional<int>>) {
            app.add_option_function<int>(
                   info.flag, [&field](int value) { field = value; }, info.help)
                ->check(CLI::Range(int(info.min), int(info.max)));
        } else {
            addTableOption(app, info, field);
        }
    });
    addFitSettings(app, options.fit);
}

}  // namespace subdfit::apps
