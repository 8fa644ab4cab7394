#pragma once
// Everything a resumed fit needs to continue exactly where one stopped: plain data, so that the
// checkpoint format (fit/checkpoint.h) is read and written without a GL context.
#include <cstdint>
#include <vector>

namespace subdfit::fit {

struct GroupState {
    std::vector<float> theta{}, moment1{}, moment2{};
    int adamSteps = 0;
};

struct FitState {
    int steps = 0;
    std::uint32_t samples = 0;
    std::vector<GroupState> groups{};  // in CageFitter::groups() order
};

}  // namespace subdfit::fit
