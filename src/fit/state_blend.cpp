#include "fit/state_blend.h"

#include "util/error.h"

namespace subdfit::fit {

std::vector<float> between(const std::vector<float>& from, const std::vector<float>& to, float t) {
    SUBDFIT_CHECK(from.size() == to.size());
    std::vector<float> out(to.size());
    for (size_t n = 0; n < to.size(); ++n) out[n] = from[n] + t * (to[n] - from[n]);
    return out;
}

FitState between(const FitState& from, const FitState& to, float t) {
    SUBDFIT_CHECK(from.groups.size() == to.groups.size());
    FitState out = to;
    for (size_t g = 0; g < to.groups.size(); ++g)
        out.groups[g].theta = between(from.groups[g].theta, to.groups[g].theta, t);
    return out;
}

float furthestThatHolds(const std::function<bool(float)>& holds, int bisections) {
    float low = 0.0f, high = 1.0f;
    for (int k = 0; k < bisections; ++k) {
        const float mid = 0.5f * (low + high);
        (holds(mid) ? low : high) = mid;
    }
    return low;
}

}  // namespace subdfit::fit
