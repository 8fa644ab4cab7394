#include "simplify/manifest.h"

#include "io/input_file.h"
#include "util/error.h"

namespace subdfit::simplify {

std::vector<std::string> splitManifestLine(const std::string& line) {
    std::vector<std::string> words;
    std::string word;
    bool inWord = false;
    char quote = 0;
    for (const char c : line) {
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t') throw Error("control character in the line");
        if (quote) {
            if (c == quote) quote = 0;
            else word += c;
        } else if (c == '"' || c == '\'') {
            quote = c;
            inWord = true;
        } else if (c == ' ' || c == '\t') {
            if (inWord) words.push_back(std::move(word));
            word.clear();
            inWord = false;
        } else {
            word += c;
            inWord = true;
        }
    }
    if (quote) throw Error(std::string("unterminated ") + quote + " quote");
    if (inWord) words.push_back(std::move(word));
    return words;
}

std::vector<ManifestLine> readManifest(const std::filesystem::path& manifest) {
    constexpr std::uint64_t kMaxManifestBytes = std::uint64_t(64) << 20;
    const std::string name = manifest.string();
    const std::string text = io::readInputFile(manifest, kMaxManifestBytes);
    std::vector<ManifestLine> lines;
    size_t start = 0;
    for (int number = 1; start < text.size(); ++number) {
        const size_t end = std::min(text.find('\n', start), text.size());
        std::string line = text.substr(start, end - start);
        start = end + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto first = line.find_first_not_of(" \t");
        if (first == std::string::npos || line[first] == '#') continue;
        ManifestLine parsed{.number = number};
        try {
            parsed.options = splitManifestLine(line);
        } catch (const Error& e) {
            throw fileError(name + ":" + std::to_string(number), e.what());
        }
        if (parsed.options.empty() || parsed.options.front().empty())
            throw fileError(name + ":" + std::to_string(number), "the line names no reference");
        parsed.reference = parsed.options.front();
        parsed.options.erase(parsed.options.begin());
        parsed.resolved = parsed.reference.is_relative() ? manifest.parent_path() / parsed.reference : parsed.reference;
        lines.push_back(std::move(parsed));
    }
    if (lines.empty()) throw fileError(name, "the manifest names no asset");
    return lines;
}

}  // namespace subdfit::simplify
