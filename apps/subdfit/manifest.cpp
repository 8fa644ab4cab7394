#include "manifest.h"

#include <fstream>

#include "common/simplify_cli.h"
#include "util/error.h"

namespace subdfit::apps {

std::vector<simplify::BatchItem> readManifest(const std::filesystem::path& manifest,
                                              const simplify::SimplifyOptions& defaults) {
    std::ifstream in(manifest);
    if (!in) throw fileError(manifest.string(), "cannot open the manifest");
    std::vector<simplify::BatchItem> items;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        simplify::SimplifyOptions options = defaults;
        CLI::App parser{"manifest line"};
        parser.add_option("reference", options.fit.reference)->required();
        addSimplifySettings(parser, options);
        try {
            std::vector<std::string> args = CLI::detail::split_up(line);
            std::reverse(args.begin(), args.end());  // CLI11 takes a vector last argument first
            parser.parse(args);
            simplify::validate(options);
        } catch (const std::exception& e) {
            throw fileError(manifest.string() + ":" + std::to_string(number), e.what());
        }
        if (options.fit.reference.is_relative()) options.fit.reference = manifest.parent_path() / options.fit.reference;
        items.push_back({"", std::move(options)});
    }
    if (items.empty()) throw fileError(manifest.string(), "the manifest names no asset");
    std::vector<std::filesystem::path> references;
    for (const auto& item : items) references.push_back(item.options.fit.reference);
    const auto names = simplify::uniqueNames(references);
    for (size_t k = 0; k < items.size(); ++k) items[k].name = names[k];
    return items;
}

}  // namespace subdfit::apps
