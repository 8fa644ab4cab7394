#pragma once
// What a `subdfit fit` or `subdfit simplify` output folder holds, read back from its report.json:
// what shipped (asset.subd, or simplify's triangle route) with its bytes and held-out scores, the reference it was fitted to, and
// (simplify) each baseline's shipped file, measured the same way. Reads no mesh: whoever shows
// or compares them opens what they need.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace subdfit::fit {

struct ShippedEntry {
    std::string name;  // "subdfit", or the baseline's: "decimation", "gltfpack", "bake"
    // Its files, finest first: one per entry today (a chain of levels of detail lists each).
    std::vector<std::filesystem::path> levels;
    std::uintmax_t bytes = 0;                                       // what the budget counts; 0: not said
    double psnrHoldout = std::numeric_limits<double>::quiet_NaN();  // NaN: not measured
    double ssimHoldout = std::numeric_limits<double>::quiet_NaN();
};

struct ResultFolder {
    std::filesystem::path dir;
    // The reference as report.json names it; empty when that file is not there (`notes` says so).
    std::filesystem::path reference;
    nlohmann::json settings = nlohmann::json::object();  // report.json's settings (what the fit ran with)
    std::vector<ShippedEntry> entries;                   // subdfit first, then the baselines in the comparison's order
    std::vector<std::string> notes;                      // what could not be shown and why, one line each
};

// Throws subdfit::Error "DIR: problem" when DIR is not a folder holding a result (report.json and
// what shipped: asset.subd, or the file report.json's `route` names) or its report.json cannot be
// read as a report. Baselines whose file is missing,
// and a reference that has moved, are left out with a note.
ResultFolder readResultFolder(const std::filesystem::path& dir);

}  // namespace subdfit::fit
