#include "simplify/batch.h"

#include <charconv>
#include <chrono>
#include <fstream>
#include <map>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

namespace fs = std::filesystem;
constexpr const char* kStatusFile = "status.json";

std::string readState(const fs::path& dir) {
    std::ifstream in(dir / kStatusFile);
    if (!in) return "";
    const auto status = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    return status.is_object() && status.contains("state") && status["state"].is_string() ? status["state"].get<std::string>()
                                                                                        : "";
}

void writeStatus(const fs::path& dir, const std::string& state, const nlohmann::json& details = {}) {
    nlohmann::json status = {{"state", state},
                             {"time", std::chrono::duration_cast<std::chrono::seconds>(
                                          std::chrono::system_clock::now().time_since_epoch()).count()}};
    if (details.is_object()) status.update(details);
    io::writeTextAtomically(dir / kStatusFile, status.dump(2) + "\n");
}

}  // namespace

Shard parseShard(const std::string& text) {
    Shard shard;
    const auto slash = text.find('/');
    const char* end = text.data() + text.size();
    const bool ok = slash != std::string::npos &&
                    std::from_chars(text.data(), text.data() + slash, shard.index).ptr == text.data() + slash &&
                    std::from_chars(text.data() + slash + 1, end, shard.count).ptr == end;
    if (!ok || shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
        throw Error("invalid option: --shard must be i/N with 0 <= i < N, got '" + text + "'");
    return shard;
}

std::vector<std::string> uniqueNames(const std::vector<fs::path>& references) {
    std::map<std::string, int> seen;
    std::vector<std::string> names;
    for (const auto& path : references) {
        const std::string stem = path.stem().string().empty() ? "asset" : path.stem().string();
        const int n = ++seen[stem];
        names.push_back(n == 1 ? stem : stem + "_" + std::to_string(n));
    }
    return names;
}

BatchSummary runBatch(const std::vector<BatchItem>& items, const fs::path& out, Shard shard,
                      const fit::FitHooks& hooks, const BatchLog& log) {
    auto say = [&](const std::string& line) { if (log) log(line); };
    BatchSummary summary;
    fs::create_directories(out);
    for (size_t k = 0; k < items.size(); ++k) {
        if (int(k % size_t(shard.count)) != shard.index) {
            ++summary.otherShards;
            continue;
        }
        const BatchItem& item = items[k];
        const fs::path finished = out / item.name, partial = out / (item.name + ".partial");
        if (readState(finished) == "done") {
            ++summary.skipped;
            say(item.name + ": done already, skipped");
            continue;
        }
        if (hooks.cancel && hooks.cancel->load()) {
            summary.interrupted = true;
            break;
        }
        fs::create_directories(partial);
        const bool resuming = fs::exists(partial / "checkpoint.bin");
        say(item.name + (resuming ? ": resuming from its checkpoint" : ": starting"));
        writeStatus(partial, "running", {{"reference", item.options.fit.reference.string()}});

        SimplifyOptions options = item.options;
        options.fit.out = partial;
        options.fit.resume = true;
        try {
            const auto report = runSimplify(options, hooks);
            if (report["interrupted"].get<bool>()) {
                writeStatus(partial, "interrupted", {{"steps", report["steps"]}});
                summary.interrupted = true;
                break;
            }
            writeStatus(partial, "done", {{"psnr_holdout", report["psnr_holdout"]}, {"bytes", report["bytes"]}});
            fs::remove_all(finished);  // a stale folder without a done status
            fs::rename(partial, finished);
            ++summary.finished;
        } catch (const std::exception& e) {
            writeStatus(partial, "failed", {{"error", e.what()}});
            say(item.name + ": failed: " + e.what());
            ++summary.failed;
        }
    }
    return summary;
}

}  // namespace subdfit::simplify
