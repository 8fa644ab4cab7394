#include "simplify/cage_bakes.h"

namespace subdfit::simplify {

CageBakes::~CageBakes() {
    for (auto& [key, bake] : bakes_)
        if (bake.valid()) bake.wait();
}

void CageBakes::startAhead(size_t choice, const BakeOptions& options) {
    const Key key{choice, options.resolution};
    if (bakes_.count(key)) return;
    bakes_.emplace(
        key, std::async(std::launch::async, [this, options] { return bakeMaps(cage_, reference_, options); }).share());
}

const surface::SurfaceMaps& CageBakes::at(size_t choice, const BakeOptions& options) {
    const Key key{choice, options.resolution};
    auto bake = bakes_.find(key);
    if (bake == bakes_.end()) {
        std::promise<surface::SurfaceMaps> now;
        now.set_value(bakeMaps(cage_, reference_, options));
        bake = bakes_.emplace(key, now.get_future().share()).first;
    }
    return bake->second.get();
}

}  // namespace subdfit::simplify
