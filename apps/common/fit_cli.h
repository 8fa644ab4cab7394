#pragma once
// The fit options on the command line, registered from the options table (fit/fit_options.h)
// for every app that runs a fit (`fit`, `simplify`, `batch` and its manifest lines, the viewer),
// so that all accept the same flags with the same defaults and help. Each app adds its inputs
// and its own --out.
#include <CLI/CLI.hpp>

#include <type_traits>

#include "context/gl_context.h"
#include "fit/fit_options.h"

namespace subdfit::apps {

// A flag whose words are parsed here, once: the core only ever sees the value.
template <fit::WordOption T>
CLI::Option* addWordOption(CLI::App& app, const fit::OptionInfo& info, T& field) {
    return app
        .add_option_function<std::string>(
            info.flag,
            [&field, &info](const std::string& text) {
                try {
                    fit::readOptionText(info, field, text);
                } catch (const OptionError& e) {
                    throw CLI::ValidationError(info.flag, e.problem());
                }
            },
            info.help)
        ->default_str(fit::optionText(field));
}

// A flag of a command's own (not the fit table's) whose value is one of an enum's words.
template <NamedEnum E>
CLI::Option* addNamedOption(CLI::App& app, const std::string& flag, E& field, const std::string& help) {
    return app
        .add_option_function<std::string>(
            flag,
            [&field, flag](const std::string& text) {
                const auto value = parseNamed<E>(text);
                if (!value) throw CLI::ValidationError(flag, "must be " + namesOf<E>() + ", got '" + text + "'");
                field = *value;
            },
            help)
        ->default_str(std::string(nameOf(field)));
}

// One row's flag, as the type of its field says: a bool is a switch, words are read by
// readOptionText, a number shows its default (or, left to the device, its range).
template <class T>
void addTableOption(CLI::App& app, const fit::OptionInfo& info, T& field) {
    const std::string flag = info.flag;
    if (flag.empty()) return;
    if constexpr (std::is_same_v<T, bool>) {
        app.add_flag(flag, field, info.help);
    } else if constexpr (fit::WordOption<T>) {
        addWordOption(app, info, field);
    } else {
        auto* option = app.add_option(flag, field, info.help);
        if (!info.byDevice) option->capture_default_str();
        else option->check(CLI::Range(info.min, info.max));  // the core takes kByDevice as "not given"; a user may not
    }
}

// Every option of the table that has a flag.
inline void addFitSettings(CLI::App& app, fit::FitOptions& fit) {
    fit::forEachOption(fit, [&](const fit::OptionInfo& info, auto& field) { addTableOption(app, info, field); });
}

// --gl for a command whose options are its own (the benchmarks), as the table's row says it.
inline CLI::Option* addGlProvider(CLI::App& app, context::GlProvider& provider) {
    return addWordOption(app, *fit::findOption("gl"), provider);
}

inline void addFitOptions(CLI::App& app, fit::FitOptions& fit) {
    app.add_option("--cage", fit.cage, "control cage (.obj with OpenSubdiv tags, .gltf, .glb, .drc)")->required();
    app.add_option("--reference", fit.reference, "reference mesh to match (.obj, .gltf, .glb, .drc)")->required();
    addFitSettings(app, fit);
}

}  // namespace subdfit::apps
