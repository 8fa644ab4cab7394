#include "simplify/batch.h"

#include <cctype>
#include <charconv>
#include <chrono>
#include <map>

#include "io/atomic_file.h"
#include "io/file_lock.h"
#include "io/input_file.h"
#include "io/output_folder.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/interrupt.h"
#include "util/json_text.h"

namespace subdfit::simplify {
namespace {

namespace fs = std::filesystem;
constexpr const char* kStatusFile = "status.json";

// The status of an asset folder; an empty object when there is none or it does not parse.
nlohmann::json readStatus(const fs::path& dir) {
    try {
        const std::string text = io::readInputFile(dir / kStatusFile, 1 << 20);
        auto status = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
        return status.is_object() ? status : nlohmann::json::object();
    } catch (const Error&) {
        return nlohmann::json::object();
    }
}

std::string stateOf(const nlohmann::json& status) {
    return status.contains("state") && status["state"].is_string() ? status["state"].get<std::string>() : "";
}

void writeStatus(const fs::path& dir, const std::string& state, const nlohmann::json& details) {
    nlohmann::json status = {
        {"state", state},
        {"time", std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
                     .count()}};
    if (details.is_object()) status.update(details);
    io::writeTextAtomically(dir / kStatusFile, jsonText(status, 2));
}

// What an asset folder was made from: the input file (path, size, content) and the settings.
nlohmann::json identityOf(const BatchItem& item) {
    const fs::path& reference = item.options.fit.reference;
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(reference, ec);
    const std::string digest = io::fileDigest(reference);  // throws, naming the file, if it is unreadable
    return {{"input",
             {{"path", (ec ? reference : resolved).string()},
              {"bytes", fs::file_size(reference, ec)},
              {"xxh3_128", digest}}},
            {"settings", settingsJson(item.options)}};
}

// `identity` as status.json holds it once written and read back (a name's bytes that are not
// UTF-8 become U+FFFD: util/json_text.h), so that it compares equal to what a run recorded.
bool sameIdentity(const nlohmann::json& status, const nlohmann::json& identity) {
    const nlohmann::json written = nlohmann::json::parse(jsonText(identity));
    return status.contains("input") && status["input"] == written["input"] && status.contains("settings") &&
           status["settings"] == written["settings"];
}

// Every path an asset touches, checked to lie inside OUT and not to be a symlink someone planted.
struct AssetPaths {
    fs::path finished, partial, lock;

    AssetPaths(const fs::path& out, const std::string& name)
        : finished(out / name),
          partial(out / (name + ".partial")),
          lock(out / kBatchFolder / "locks" / (name + ".lock")) {
        for (const fs::path* p : {&finished, &partial, &lock}) {
            if (!io::isStrictlyInside(*p, out)) throw fileError(p->string(), "lies outside the batch's output folder");
            std::error_code ec;
            if (fs::is_symlink(fs::symlink_status(*p, ec)))
                throw fileError(p->string(), "is a symbolic link; the batch will not follow it");
        }
    }
};

// Statuses are bookkeeping: failing to write one is reported, never thrown, so that an error
// handler cannot itself fail and stop the batch.
void writeStatusOrSay(const fs::path& dir, const std::string& state, const nlohmann::json& details, const BatchLog& say,
                      const std::string& name) {
    try {
        writeStatus(dir, state, details);
    } catch (const std::exception& e) {
        say(name + ": could not record status '" + state + "': " + e.what());
    }
}

// What became of an asset that neither failed nor was interrupted, and the route it shipped
// (finished now or before; empty when not known).
enum class AssetOutcome { Finished, Skipped, RunningElsewhere };
struct AssetResult {
    AssetOutcome outcome;
    std::string route;
};

// The identity of `item`; of an unreadable input only its path (simplify will say why, in its status).
nlohmann::json identityOrPath(const BatchItem& item) {
    try {
        return identityOf(item);
    } catch (const Interrupted&) {
        throw;
    } catch (const Error&) {
        return nlohmann::json{{"input", {{"path", item.options.fit.reference.string()}}},
                              {"settings", settingsJson(item.options)}};
    }
}

// Simplifies `item` into its partial folder and renames that into place once done; the route it shipped.
std::string simplifyInto(const BatchItem& item, const AssetPaths& paths, const nlohmann::json& identity,
                         const fit::FitHooks& hooks, const BatchLog& say) {
    SimplifyOptions options = item.options;
    options.fit.out = paths.partial;
    options.fit.resume = fs::exists(paths.partial / "checkpoint.bin");
    options.fit.force = true;  // the folder is ours, status.json and all
    say(item.name + (options.fit.resume ? ": resuming from its checkpoint" : ": starting"));
    writeStatus(paths.partial, "running", identity);
    try {
        const auto report = runSimplify(options, hooks);
        nlohmann::json details = identity;
        details.update({{"psnr_holdout", report.subdfit.psnrHoldout},
                        {"bytes", report.subdfit.bytes},
                        {"route", report.route.shipped}});
        writeStatus(paths.partial, "done", details);
        fs::remove_all(paths.finished);  // a stale folder: not done, or from another input
        fs::rename(paths.partial, paths.finished);
        return report.route.shipped;
    } catch (const Interrupted&) {
        writeStatusOrSay(paths.partial, "interrupted", identity, say, item.name);
        throw;
    }
}

// One asset under its lock: skipped when another process holds the lock or when it is done from
// the same input and settings; otherwise simplified, its partial work kept when it is from the
// same input. Throws what the simplify throws.
AssetResult runAsset(const BatchItem& item, const fs::path& out, const fit::FitHooks& hooks, const BatchLog& say) {
    const AssetPaths paths(out, item.name);
    const auto lock = io::FileLock::tryAcquire(paths.lock);
    if (!lock) {
        say(item.name + ": running elsewhere (another process holds its lock), skipped");
        return {AssetOutcome::RunningElsewhere, ""};
    }
    // Under the lock, the folders can only change by our hand.
    const nlohmann::json identity = identityOrPath(item);
    const nlohmann::json finishedStatus = readStatus(paths.finished);
    if (stateOf(finishedStatus) == "done") {
        if (sameIdentity(finishedStatus, identity)) {
            say(item.name + ": done already, skipped");
            const auto route = finishedStatus.find("route");
            return {AssetOutcome::Skipped,
                    route != finishedStatus.end() && route->is_string() ? route->get<std::string>() : ""};
        }
        say(item.name + ": its finished folder was made from another version of the input: redoing it");
    }
    if (fs::exists(paths.partial) && !sameIdentity(readStatus(paths.partial), identity)) {
        say(item.name + ": its partial work was for another version of the input: starting over");
        fs::remove_all(paths.partial);
    }
    fs::create_directories(paths.partial);
    return {AssetOutcome::Finished, simplifyInto(item, paths, identity, hooks, say)};
}

// A failed asset's status, where its work would be, when that folder is ours to write.
void recordFailure(const BatchItem& item, const fs::path& out, const std::exception& e, const BatchLog& say) {
    say(item.name + ": failed: " + e.what());
    const fs::path partial = out / (item.name + ".partial");
    std::error_code ec;
    if (io::isStrictlyInside(partial, out) && !fs::is_symlink(fs::symlink_status(partial, ec))) {
        fs::create_directories(partial, ec);
        // With the input-and-settings record a retry compares, so that it keeps the partial work.
        nlohmann::json details = identityOrPath(item);
        details.update({{"error", e.what()}, {"reference", item.options.fit.reference.string()}});
        writeStatusOrSay(partial, "failed", details, say, item.name);
    }
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
        throw OptionError("shard", "must be i/N with 0 <= i < N, got '" + text + "'");
    return shard;
}

std::string assetName(const std::string& label, const std::string& identity) {
    constexpr size_t kMaxLabel = 64;
    std::string safe;
    for (const char c : label) {
        if (safe.size() == kMaxLabel) break;
        // A leading '.' would hide the folder (or make it . or ..); a leading '-' reads as an option.
        const bool keep =
            std::isalnum(static_cast<unsigned char>(c)) || c == '_' || ((c == '.' || c == '-') && !safe.empty());
        safe += keep && static_cast<unsigned char>(c) < 0x80 ? c : '_';
    }
    if (safe.empty()) safe = "asset";
    return safe + "-" + hexDigits(hash64(identity), 12);
}

std::string assetIdentity(const SimplifyOptions& options) {
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(fs::absolute(options.fit.reference), ec);
    return (ec ? options.fit.reference : resolved).string() + "\n" + jsonText(settingsJson(options));
}

std::vector<std::string> nameItems(std::vector<BatchItem>& items, const std::vector<fs::path>& written) {
    std::vector<std::string> dropped;
    std::map<std::string, int> firstLine;
    std::vector<BatchItem> kept;
    for (size_t k = 0; k < items.size(); ++k) {
        // The label is the path as written, without its extension; a path that climbs out of
        // the manifest's folder or is absolute says little, so only its file name is kept.
        const fs::path path = written[k].lexically_normal();
        const bool local = path.is_relative() && !path.empty() && *path.begin() != "..";
        const std::string label = local ? (path.parent_path() / path.stem()).string() : path.stem().string();
        BatchItem item = std::move(items[k]);
        item.name = assetName(label, assetIdentity(item.options));
        if (const auto [at, fresh] = firstLine.emplace(item.name, item.line); !fresh) {
            dropped.push_back("line " + std::to_string(item.line) + " repeats the asset of line " +
                              std::to_string(at->second) + " (same input and settings): done once");
            continue;
        }
        kept.push_back(std::move(item));
    }
    items = std::move(kept);
    return dropped;
}

BatchSummary runBatch(const std::vector<BatchItem>& items, const fs::path& out, Shard shard, const fit::FitHooks& hooks,
                      const BatchLog& log, bool force) {
    const BatchLog say = [&](const std::string& line) {
        if (log) log(line);
    };
    auto stopRequestedHere = [&] { return stopRequested() || (hooks.cancel && hooks.cancel->load()); };
    io::checkOutputFolder(out, {.ownMarkers = {kBatchFolder}, .force = force});
    fs::create_directories(out / kBatchFolder);

    BatchSummary summary;
    for (size_t k = 0; k < items.size(); ++k) {
        if (int(k % size_t(shard.count)) != shard.index) {
            ++summary.otherShards;
            continue;
        }
        if (stopRequestedHere()) {
            summary.interrupted = true;
            break;
        }
        const BatchItem& item = items[k];
        try {
            const AssetResult result = runAsset(item, out, hooks, say);
            switch (result.outcome) {
                case AssetOutcome::Finished: ++summary.finished; break;
                case AssetOutcome::Skipped: ++summary.skipped; break;
                case AssetOutcome::RunningElsewhere: ++summary.runningElsewhere; break;
            }
            if (!result.route.empty()) ++summary.routes[result.route];
        } catch (const Interrupted& e) {
            say(item.name + ": " + e.what());
            summary.interrupted = true;
            break;
        } catch (const std::exception& e) {
            ++summary.failed;
            recordFailure(item, out, e, say);
        }
    }
    return summary;
}

}  // namespace subdfit::simplify
