#pragma once
// A fit's resumable state on disk: the optimiser state plus a fingerprint of everything that
// must match for a resumed run to continue the same optimisation (inputs and settings).
#include <filesystem>
#include <optional>
#include <string>

#include "fit/cage_fitter.h"

namespace subdfit::fit {

// Written atomically, so an interrupted write leaves the previous checkpoint intact.
void writeCheckpoint(const std::filesystem::path& path, const std::string& fingerprint,
                     const CageFitter::State& state);

// Nothing when there is no file. Throws subdfit::Error naming the file when it is damaged or
// was written for other inputs or settings.
std::optional<CageFitter::State> readCheckpoint(const std::filesystem::path& path, const std::string& fingerprint);

}  // namespace subdfit::fit
