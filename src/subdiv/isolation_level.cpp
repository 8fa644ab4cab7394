#include "subdiv/isolation_level.h"

#include <opensubdiv/sdc/crease.h>

#include <algorithm>
#include <cmath>

namespace subdfit::subdiv {

int drawingIsolationLevel(const mesh::PolygonMesh& cage) {
    if (cage.faceCount() <= kDenseCageFaces) return kIsolationLevel;
    // Only a semi-sharp tag asks for depth: an infinitely sharp one never decays, so no level
    // resolves it, and it is drawn like any irregular vertex, exactly where regular (useInfSharpPatch).
    const auto semiSharp = [](float s) { return s < OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE ? s : 0.0f; };
    float sharpest = 0.0f;
    for (const mesh::Crease& c : cage.tags.creases) sharpest = std::max(sharpest, semiSharp(c.sharpness));
    for (const mesh::Corner& c : cage.tags.corners) sharpest = std::max(sharpest, semiSharp(c.sharpness));
    if (sharpest > 2.0f) return kIsolationLevel;
    const int shallowest = cage.faceCount() > kVeryDenseCageFaces ? 1 : 2;
    return std::max(shallowest, int(std::ceil(sharpest)));
}

}  // namespace subdfit::subdiv
