#pragma once
// Programs keyed by (stage files, defines), compiled on first use (Filament/OpenSubdiv style).
// The run asks only for the variants its scene needs, so the cache's contents are exactly the
// effects that were simulated: `variants()` goes into report.json and into tests.
#include <memory>
#include <string>
#include <vector>

#include "gl/program.h"

namespace subdfit::gl {

struct ProgramVariant {
    std::string name;  // e.g. "patch_raster"
    std::vector<std::string> files;
    Defines defines;
};

class ProgramCache {
public:
    explicit ProgramCache(Defines globalDefines = {}) : global_(std::move(globalDefines)) {}

    const Program& get(const std::string& name, const std::vector<ShaderStage>& stages,
                       const Defines& defines = {});

    const std::vector<ProgramVariant>& variants() const { return variants_; }

private:
    Defines global_;
    std::map<std::string, std::unique_ptr<Program>> programs_;
    std::vector<ProgramVariant> variants_;
};

}  // namespace subdfit::gl
