#include "manifest.h"

#include <algorithm>

#include "common/command_line.h"
#include "common/simplify_cli.h"
#include "simplify/manifest.h"
#include "util/error.h"

namespace subdfit::apps {

std::vector<simplify::BatchItem> readManifest(const std::filesystem::path& manifest,
                                              const simplify::SimplifyOptions& defaults,
                                              const simplify::BatchLog& log) {
    std::vector<simplify::BatchItem> items;
    std::vector<std::filesystem::path> written;
    for (const simplify::ManifestLine& line : simplify::readManifest(manifest)) {
        simplify::SimplifyOptions options = defaults;
        CLI::App parser{"manifest line"};
        addSimplifySettings(parser, options);
        try {
            std::vector<std::string> args = line.options;
            std::reverse(args.begin(), args.end());  // CLI11 takes a vector last argument first
            parser.parse(args);
            simplify::validate(options);
        } catch (const CLI::Success&) {  // --help, which CLI11 answers by throwing
            throw fileError(manifest.string() + ":" + std::to_string(line.number),
                            "--help is an option of the command line, not of a manifest line");
        } catch (const std::exception& e) {
            throw fileError(manifest.string() + ":" + std::to_string(line.number), describeError(e));
        }
        options.fit.reference = line.resolved;
        items.push_back({.options = std::move(options), .line = line.number});
        written.push_back(line.reference);
    }
    for (const std::string& dropped : simplify::nameItems(items, written))
        if (log) log(manifest.string() + ": " + dropped);
    return items;
}

}  // namespace subdfit::apps
