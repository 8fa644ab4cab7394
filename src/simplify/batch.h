#pragma once
// `subdfit batch`: many assets, one `simplify` each, built to run unattended over manifests that
// other people wrote, on shared folders, split across machines by whatever scheduler is at hand
// (a Slurm job array, a Kubernetes indexed Job, GNU parallel) with no coordination beyond OUT:
//  - asset k of the manifest belongs to shard k mod N: every shard computes the same split;
//  - each asset has a folder name of its own, made safe from what the manifest says and made
//    unique by a hash of its identity, so no name can leave OUT or meet another asset's;
//  - an asset is worked on in OUT/NAME.partial/ (status.json says running, failed or
//    interrupted, beside the fit's checkpoint) and appears as OUT/NAME/ in one rename once
//    finished, with status.json saying done and which input (path, size, content hash) and
//    settings it was made from;
//  - a process works on an asset only while it holds the asset's lock (OUT/.subdfit/locks/),
//    which dies with it: a second batch on the same OUT skips it as running elsewhere;
//  - a re-run skips assets finished from the same input and settings and resumes the others
//    from their checkpoints.
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "simplify/simplify_job.h"

namespace subdfit::simplify {

struct BatchItem {
    std::string name{};       // OUT/name: from assetName()
    SimplifyOptions options;  // options.fit.out, .resume and .force are set by the batch
    int line = 0;             // where the manifest names it (0: not from a manifest)
};

struct Shard {
    int index = 0, count = 1;
};
// "i/N" with 0 <= i < N. Throws subdfit::Error ("invalid option: ...").
Shard parseShard(const std::string& text);

// A folder name: `label` (the reference as the manifest writes it) with every character but
// [A-Za-z0-9._-] replaced by '_', no leading '.' or '-', at most 64 characters; then '-' and 12 hex
// digits of a hash of `identity` (the resolved input path and the settings). Never ".", "..",
// hidden, or holding a separator, whatever the label.
std::string assetName(const std::string& label, const std::string& identity);

// What tells two assets apart: the reference's resolved absolute path and the settings.
std::string assetIdentity(const SimplifyOptions& options);

// Names every item from its reference as written and its identity, and drops repeats of an
// asset (same resolved input, same settings), keeping the first. Returns a line for each drop.
std::vector<std::string> nameItems(std::vector<BatchItem>& items, const std::vector<std::filesystem::path>& written);

struct BatchSummary {
    int finished = 0, skipped = 0, failed = 0, otherShards = 0, runningElsewhere = 0;
    bool interrupted = false;
    // Of the assets finished or skipped as done: how many shipped each route ("cage",
    // "decimation", "gltfpack"; simplify/route.h).
    std::map<std::string, int> routes;
};

// Announces each asset it starts or skips.
using BatchLog = std::function<void(const std::string& line)>;

// What marks OUT as a batch's own (io::checkOutputFolder).
inline const std::string kBatchFolder = ".subdfit";

// Checks OUT (io::checkOutputFolder; `force` as --force), then runs this shard's items in order.
// A failing asset is recorded (status failed, with the error) and the batch goes on; a stop
// request (hooks.cancel, or the process's, util/interrupt.h) ends it after the current asset's
// checkpoint, with that asset's status interrupted.
BatchSummary runBatch(const std::vector<BatchItem>& items, const std::filesystem::path& out, Shard shard,
                      const fit::FitHooks& hooks = {}, const BatchLog& log = {}, bool force = false);

}  // namespace subdfit::simplify
