#pragma once
// A simplify small enough for a test of how it works, not of how well it does: 4 training and 2
// held-out views at 64², `steps` steps on OSMesa, 5 000 surface samples a side. Each test sets
// what it checks on top.
#include <filesystem>

#include "simplify/simplify_job.h"

namespace subdfit::test {

inline simplify::SimplifyOptions smallSimplify(const std::filesystem::path& reference, const std::filesystem::path& out,
                                               int steps) {
    simplify::SimplifyOptions o;
    o.fit.reference = reference;
    o.fit.out = out;
    o.fit.steps = steps;
    o.fit.views = 4;
    o.fit.holdoutViews = 2;
    o.fit.resolution = 64;
    o.fit.glProvider = context::GlProvider::Osmesa;
    o.surfaceSamples = 5000;
    return o;
}

}  // namespace subdfit::test
