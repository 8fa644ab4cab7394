#pragma once
// Programs compiled on first use, one per variant (Filament's Variant, OpenSubdiv's effect-keyed
// shader cache). A program is declared once by its owner as a ProgramSpec: its stage files and
// the #define each bit of its variant turns on; a pass asks for a variant by bits, never by
// define strings. The run asks only for the variants its scene needs, so the cache's contents
// are exactly the effects that were simulated: `variants()` goes into report.json and tests.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "gl/program.h"

namespace subdfit::gl {

// Bit k selects flagDefines[k] of the program's spec.
using VariantBits = std::uint32_t;

struct ProgramSpec {
    std::string name{};  // e.g. "patch_raster"
    std::vector<ShaderStage> stages{};
    std::vector<std::string> flagDefines{};
};

struct ProgramVariant {
    std::string name;
    std::vector<std::string> files;
    Defines defines;
};

class ProgramCache {
public:
    // `globalDefines` go into every program (what the platform offers, gl/platform_defines.h).
    explicit ProgramCache(Defines globalDefines = {}) : global_(std::move(globalDefines)) {}

    // `values`: defines that carry a number rather than a switch (e.g. a channel count).
    const Program& get(const ProgramSpec& spec, VariantBits variant = 0, const Defines& values = {});

    const std::vector<ProgramVariant>& variants() const { return variants_; }

private:
    Defines global_;
    std::map<std::tuple<std::string, VariantBits, Defines>, std::unique_ptr<Program>> programs_;
    std::vector<ProgramVariant> variants_;
};

}  // namespace subdfit::gl
