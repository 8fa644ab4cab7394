#pragma once
// A fit's resumable state on disk: the optimiser state plus a fingerprint of everything that
// must match for a resumed run to continue the same optimisation (inputs and settings).
#include <filesystem>
#include <optional>
#include <string>

#include "fit/fit_state.h"

namespace subdfit::fit {

// Written atomically, so an interrupted write leaves the previous checkpoint intact. The format
// (version in the magic's last byte, a checksum over everything before it) is private to
// subdfit: a checkpoint resumes the build that wrote it or a later one of the same version.
void writeCheckpoint(const std::filesystem::path& path, const std::string& fingerprint, const FitState& state);

// Nothing when there is no file. Throws subdfit::Error naming the file when it is damaged
// (checksum, truncation, counts beyond its size), of another version, or was written for other
// inputs or settings.
std::optional<FitState> readCheckpoint(const std::filesystem::path& path, const std::string& fingerprint);

}  // namespace subdfit::fit
