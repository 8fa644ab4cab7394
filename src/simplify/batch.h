#pragma once
// `subdfit batch`: many assets, one `simplify` each, built to run unattended and split across
// machines by whatever scheduler is at hand (a Slurm job array, a Kubernetes indexed Job, GNU
// parallel) with no coordination beyond the shared output folder:
//  - asset k of the manifest belongs to shard k mod N: every shard computes the same split;
//  - an asset is worked on in OUT/NAME.partial/ (status.json says running, failed or
//    interrupted, beside the fit's checkpoint) and appears as OUT/NAME/ in one rename once
//    finished, with status.json saying done;
//  - a re-run skips finished assets and resumes the others from their checkpoints.
#include <filesystem>
#include <string>
#include <vector>

#include "simplify/simplify_job.h"

namespace subdfit::simplify {

struct BatchItem {
    std::string name;          // OUT/name: unique within the manifest
    SimplifyOptions options;   // options.fit.out and .resume are set by the batch
};

struct Shard {
    int index = 0, count = 1;
};
// "i/N" with 0 <= i < N. Throws subdfit::Error ("invalid option: ...").
Shard parseShard(const std::string& text);

// Output names from reference paths: the file stem, suffixed _2, _3, ... where stems repeat.
std::vector<std::string> uniqueNames(const std::vector<std::filesystem::path>& references);

struct BatchSummary {
    int finished = 0, skipped = 0, failed = 0, otherShards = 0;
    bool interrupted = false;
};

// Announces each asset it starts or skips.
using BatchLog = std::function<void(const std::string& line)>;

// Runs this shard's items in order. A failing asset is recorded (status failed, with the error)
// and the batch goes on; hooks.cancel stops it after the current asset's checkpoint.
BatchSummary runBatch(const std::vector<BatchItem>& items, const std::filesystem::path& out, Shard shard,
                      const fit::FitHooks& hooks = {}, const BatchLog& log = {});

}  // namespace subdfit::simplify
