#include "fit/result_folder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/asset_folder.h"
#include "io/input_file.h"
#include "util/error.h"
#include "util/printable.h"

namespace subdfit::fit {
namespace {

double numberOr(const nlohmann::json& object, const char* key, double fallback) {
    const auto it = object.find(key);
    return it != object.end() && it->is_number() ? it->get<double>() : fallback;
}

// A byte count as a report states it: negative or NaN as none, past what a count holds as the most.
std::uintmax_t bytesOf(double bytes) {
    constexpr std::uintmax_t kMost = std::numeric_limits<std::uintmax_t>::max();
    if (!(bytes > 0.0)) return 0;
    return bytes >= double(kMost) ? kMost : std::uintmax_t(bytes);
}

// A string member of `object`, or nothing (absent, or not a string).
std::optional<std::string> stringAt(const nlohmann::json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_string()) return std::nullopt;
    return it->get<std::string>();
}

// The baselines' names in the order the comparison shows them, then any other the report has.
std::vector<std::string> baselineOrder(const nlohmann::json& report, const nlohmann::json& baselines) {
    std::vector<std::string> names;
    if (const auto columns = report.find("comparison_columns"); columns != report.end() && columns->is_array())
        for (const auto& column : *columns)
            if (column.is_string() && baselines.contains(column.get<std::string>()) &&
                std::find(names.begin(), names.end(), column.get<std::string>()) == names.end())
                names.push_back(column.get<std::string>());
    for (const auto& [name, value] : baselines.items())
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    return names;
}

// A file report.json names, relative to the folder: the file it resolves to (symlinks followed)
// when that is a regular file inside the folder, else why not ("" in `problem` when it may be read).
struct NamedFile {
    std::filesystem::path file;
    std::string problem;
};
NamedFile namedFile(const io::AssetFolder& folder, const std::string& name) {
    const std::filesystem::path relative = std::filesystem::path(name).lexically_normal();
    if (name.empty() || relative.is_absolute() || !folder.containsLexically(folder.path() / relative))
        return {.file = {}, .problem = "'" + printable(name) + "' lies outside the result folder"};
    const io::AssetFolder::Resolved resolved = folder.resolve(folder.path() / relative);
    if (resolved.missing) return {.file = {}, .problem = "'" + printable(name) + "' is not there"};
    if (!resolved.problem.empty()) return {.file = {}, .problem = "'" + printable(name) + "' " + resolved.problem};
    return {.file = resolved.file, .problem = {}};
}

// The reference report.json names: the user's input, outside the folder by nature. It is opened
// only when it is still the very file the result was made from (its recorded XXH3-128 digest),
// so that a report cannot make the viewer read any other file.
std::filesystem::path referenceOf(const nlohmann::json& report, std::vector<std::string>& notes) {
    const auto at = report.find("reference");
    const std::optional<std::string> path =
        at != report.end() && at->is_object() ? stringAt(*at, "path") : std::nullopt;
    if (!path) {
        notes.push_back("report.json names no reference");
        return {};
    }
    const std::string shown = printable(*path, 160);
    const std::optional<std::string> digest = stringAt(*at, "xxh3_128");
    if (!digest) {
        notes.push_back("the reference " + shown +
                        " is not opened: report.json records no digest of it (give it with --reference)");
        return {};
    }
    if (const std::string problem = io::inputFileProblem(*path); !problem.empty()) {
        notes.push_back("the reference " + shown + " is not there (moved, or another working folder)");
        return {};
    }
    try {
        if (io::fileDigest(*path) != *digest) {
            notes.push_back("the reference " + shown +
                            " is not the file the result was made from (its digest differs)");
            return {};
        }
    } catch (const Error&) {
        notes.push_back("the reference " + shown + " cannot be read");
        return {};
    }
    return *path;
}

}  // namespace

ResultFolder readResultFolder(const std::filesystem::path& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) throw fileError(dir.string(), "not a folder");
    if (!std::filesystem::exists(dir / "report.json", ec))
        throw fileError(dir.string(), "not a subdfit result: no report.json in it");
    const io::AssetFolder folderFiles(dir / "report.json", "result");
    const std::string reportName = (dir / "report.json").string();
    if (const NamedFile file = namedFile(folderFiles, "report.json"); !file.problem.empty())
        throw fileError(reportName, "not a regular file inside the folder");
    if (!std::filesystem::exists(dir / "asset.subd", ec) && !std::filesystem::exists(dir / "asset.glb", ec))
        throw fileError(dir.string(), "not a subdfit result: no asset.subd (nor a triangle route's asset.glb) in it");
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(io::readInputFile(dir / "report.json"));
    } catch (const nlohmann::json::exception& e) {
        throw fileError(reportName, std::string("not JSON: ") + e.what());
    }
    if (!report.is_object()) throw fileError(reportName, "not a subdfit report");

    // What shipped: asset.subd, or the triangle mesh simplify's `route` names.
    std::string shippedName = "asset.subd";
    if (const auto route = report.find("route"); route != report.end() && route->is_object())
        if (const auto path = stringAt(*route, "path")) shippedName = *path;
    const NamedFile shipped = namedFile(folderFiles, shippedName);
    if (!shipped.problem.empty()) throw fileError(reportName, "what shipped, " + shipped.problem);

    ResultFolder folder;
    folder.dir = dir;
    if (const auto settings = report.find("settings"); settings != report.end()) {
        if (settings->is_object()) folder.settings = *settings;
        else folder.notes.push_back("report.json's settings are not an object: not used");
    }
    // simplify's report counts the shipped bytes; a fit's lists what it exported.
    ShippedEntry ours{.name = "subdfit", .levels = {shipped.file}};
    ours.bytes = bytesOf(numberOr(report, "bytes", 0.0));
    if (const auto exports = report.find("exports"); ours.bytes == 0 && exports != report.end() && exports->is_object())
        ours.bytes = bytesOf(numberOr(*exports, "asset.subd", 0.0));
    ours.psnrHoldout = numberOr(report, "psnr_holdout", ours.psnrHoldout);
    ours.ssimHoldout = numberOr(report, "ssim_holdout", ours.ssimHoldout);
    folder.entries.push_back(ours);
    folder.reference = referenceOf(report, folder.notes);

    const auto baselines = report.find("baselines");
    if (baselines == report.end() || !baselines->is_object()) return folder;
    for (const std::string& name : baselineOrder(report, *baselines)) {
        const nlohmann::json& baseline = (*baselines)[name];
        const std::string shownName = printable(name, 40);
        if (!baseline.is_object()) continue;
        if (const auto skipped = stringAt(baseline, "skipped")) {
            folder.notes.push_back(shownName + ": " + printable(*skipped, 160));
            continue;
        }
        const auto path = stringAt(baseline, "path");
        if (!path) {
            folder.notes.push_back(shownName + ": report.json names no shipped file");
            continue;
        }
        const NamedFile file = namedFile(folderFiles, *path);
        if (!file.problem.empty()) {
            folder.notes.push_back(shownName + ": " + file.problem + ", not shown");
            continue;
        }
        folder.entries.push_back({.name = shownName,
                                  .levels = {file.file},
                                  .bytes = bytesOf(numberOr(baseline, "bytes", 0.0)),
                                  .psnrHoldout = numberOr(baseline, "psnr_holdout", std::nan("")),
                                  .ssimHoldout = numberOr(baseline, "ssim_holdout", std::nan(""))});
    }
    return folder;
}

}  // namespace subdfit::fit
