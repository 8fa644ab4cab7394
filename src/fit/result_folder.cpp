#include "fit/result_folder.h"

#include <algorithm>
#include <cmath>

#include "io/input_file.h"
#include "io/output_folder.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

double numberOr(const nlohmann::json& object, const char* key, double fallback) {
    const auto it = object.find(key);
    return it != object.end() && it->is_number() ? it->get<double>() : fallback;
}

std::uintmax_t bytesOf(double bytes) { return bytes > 0.0 ? std::uintmax_t(bytes) : 0; }

// The baselines' names in the order the comparison shows them, then any other the report has.
std::vector<std::string> baselineOrder(const nlohmann::json& report, const nlohmann::json& baselines) {
    std::vector<std::string> names;
    if (const auto columns = report.find("comparison_columns"); columns != report.end() && columns->is_array())
        for (const auto& column : *columns)
            if (column.is_string() && baselines.contains(column.get<std::string>())) names.push_back(column.get<std::string>());
    for (const auto& [name, value] : baselines.items())
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    return names;
}

}  // namespace

ResultFolder readResultFolder(const std::filesystem::path& dir) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) throw fileError(dir.string(), "not a folder");
    if (!std::filesystem::exists(dir / "report.json", ec))
        throw fileError(dir.string(), "not a subdfit result: no report.json in it");
    if (!std::filesystem::exists(dir / "asset.subd", ec) && !std::filesystem::exists(dir / "asset.glb", ec))
        throw fileError(dir.string(), "not a subdfit result: no asset.subd (nor a triangle route's asset.glb) in it");
    nlohmann::json report;
    try {
        report = nlohmann::json::parse(io::readInputFile(dir / "report.json"));
    } catch (const nlohmann::json::exception& e) {
        throw fileError((dir / "report.json").string(), std::string("not JSON: ") + e.what());
    }
    if (!report.is_object()) throw fileError((dir / "report.json").string(), "not a subdfit report");

    // What shipped: asset.subd, or the triangle mesh simplify's `route` names.
    std::filesystem::path shippedFile = "asset.subd";
    if (const auto route = report.find("route"); route != report.end() && route->is_object() &&
                                                 route->contains("path") && (*route)["path"].is_string()) {
        shippedFile = (*route)["path"].get<std::string>();
        if (!io::isStrictlyInside(dir / shippedFile, dir))
            throw fileError((dir / "report.json").string(), "its route names a file outside the folder");
    }
    if (!std::filesystem::exists(dir / shippedFile, ec))
        throw fileError(dir.string(), "not a subdfit result: no " + shippedFile.string() + " in it");

    ResultFolder folder;
    folder.dir = dir;
    folder.settings = report.value("settings", nlohmann::json::object());
    // simplify's report counts the shipped bytes; a fit's lists what it exported.
    ShippedEntry ours{.name = "subdfit", .levels = {dir / shippedFile}};
    ours.bytes = bytesOf(numberOr(report, "bytes", 0.0));
    if (const auto exports = report.find("exports"); ours.bytes == 0 && exports != report.end() && exports->is_object())
        ours.bytes = bytesOf(numberOr(*exports, "asset.subd", 0.0));
    ours.psnrHoldout = numberOr(report, "psnr_holdout", ours.psnrHoldout);
    ours.ssimHoldout = numberOr(report, "ssim_holdout", ours.ssimHoldout);
    folder.entries.push_back(ours);

    const auto referenceAt = report.find("reference");
    if (referenceAt != report.end() && referenceAt->is_object() && referenceAt->contains("path") &&
        (*referenceAt)["path"].is_string()) {
        const std::filesystem::path reference = (*referenceAt)["path"].get<std::string>();
        if (std::filesystem::is_regular_file(reference, ec)) folder.reference = reference;
        else folder.notes.push_back("the reference " + reference.string() + " is not there (moved, or another working folder)");
    } else {
        folder.notes.push_back("report.json names no reference");
    }

    const auto baselines = report.find("baselines");
    if (baselines == report.end() || !baselines->is_object()) return folder;
    for (const std::string& name : baselineOrder(report, *baselines)) {
        const nlohmann::json& baseline = (*baselines)[name];
        if (!baseline.is_object()) continue;
        if (const auto skipped = baseline.find("skipped"); skipped != baseline.end() && skipped->is_string()) {
            folder.notes.push_back(name + ": " + skipped->get<std::string>());
            continue;
        }
        const auto path = baseline.find("path");
        if (path == baseline.end() || !path->is_string()) {
            folder.notes.push_back(name + ": report.json names no shipped file");
            continue;
        }
        const std::filesystem::path file = dir / path->get<std::string>();
        if (!std::filesystem::is_regular_file(file, ec)) {
            folder.notes.push_back(name + ": " + file.string() + " is not there");
            continue;
        }
        folder.entries.push_back({.name = name, .levels = {file}, .bytes = bytesOf(numberOr(baseline, "bytes", 0.0)),
                                  .psnrHoldout = numberOr(baseline, "psnr_holdout", std::nan("")),
                                  .ssimHoldout = numberOr(baseline, "ssim_holdout", std::nan(""))});
    }
    return folder;
}

}  // namespace subdfit::fit
