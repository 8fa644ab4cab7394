#include "view_mode.h"

namespace subdfit::view {

const char* viewModeName(ViewMode mode) {
    switch (mode) {
        case ViewMode::Fit: return "Fit";
        case ViewMode::Target: return "Target (reference)";
        case ViewMode::Difference: return "Difference";
        case ViewMode::FaceId: return "Face id";
        case ViewMode::Uv: return "Patch (u, v)";
        case ViewMode::Displacement: return "Displacement map";
        case ViewMode::NormalMap: return "Normal map";
        case ViewMode::BaseColor: return "Base colour";
        case ViewMode::MetallicRoughness: return "Metallic-roughness";
    }
    return "?";
}

const std::map<std::string, ViewMode>& viewModesByKey() {
    static const std::map<std::string, ViewMode> keys{{"fit", ViewMode::Fit},
                                                      {"target", ViewMode::Target},
                                                      {"difference", ViewMode::Difference},
                                                      {"faces", ViewMode::FaceId},
                                                      {"uv", ViewMode::Uv},
                                                      {"displacement", ViewMode::Displacement},
                                                      {"normal", ViewMode::NormalMap},
                                                      {"base_color", ViewMode::BaseColor},
                                                      {"metallic_roughness", ViewMode::MetallicRoughness}};
    return keys;
}

bool viewModeAvailable(ViewMode mode, maps::MapEffects effects) {
    if (mode == ViewMode::Displacement) return effects.has(maps::MapKind::Displacement);
    if (mode == ViewMode::NormalMap) return effects.has(maps::MapKind::NormalMap);
    if (mode == ViewMode::BaseColor) return effects.has(maps::MapKind::BaseColor);
    if (mode == ViewMode::MetallicRoughness) return effects.has(maps::MapKind::MetallicRoughness);
    return true;
}

bool viewModeNeedsFit(ViewMode mode) { return mode != ViewMode::Target; }

bool viewModeNeedsTarget(ViewMode mode) { return mode == ViewMode::Target || mode == ViewMode::Difference; }

float defaultViewScale(ViewMode mode) {
    switch (mode) {
        case ViewMode::Difference: return 4.0f;     // an error of a quarter of full scale saturates
        case ViewMode::Displacement: return 50.0f;  // ±0.02 of the scene radius saturates
        case ViewMode::NormalMap: return 4.0f;      // tangent offsets of ±0.25 saturate
        default: return 1.0f;
    }
}

std::array<float, kViewModeCount> defaultViewScales() {
    std::array<float, kViewModeCount> scales{};
    for (int m = 0; m < kViewModeCount; ++m) scales[size_t(m)] = defaultViewScale(ViewMode(m));
    return scales;
}

}  // namespace subdfit::view
