// The checkpoint reader under libFuzzer, two ways:
//  - raw bytes: any file gives a state or subdfit::Error, never a crash or a huge allocation;
//  - a real checkpoint, built from the input's bytes, with one byte flipped where the input
//    says: it must be refused (checksum) or, if the flip landed nowhere, read back identical.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "fit/checkpoint.h"
#include "util/error.h"

namespace {

const std::string kFingerprint = "{\"fuzz\":1}";

subdfit::fit::FitState stateFrom(const uint8_t* data, size_t size) {
    subdfit::fit::FitState state;
    state.steps = int(size % 1000);
    state.samples = uint32_t(size);
    for (size_t g = 0; g < 1 + size % 3; ++g) {
        subdfit::fit::GroupState group;
        for (size_t i = g; i < size; i += 3) group.theta.push_back(float(data[i]) / 7.0f);
        group.moment1 = group.theta;
        group.moment2.assign(group.theta.size(), 0.5f);
        group.adamSteps = int(g);
        state.groups.push_back(std::move(group));
    }
    return state;
}

bool same(const subdfit::fit::FitState& a, const subdfit::fit::FitState& b) {
    if (a.steps != b.steps || a.samples != b.samples || a.groups.size() != b.groups.size()) return false;
    for (size_t g = 0; g < a.groups.size(); ++g)
        if (a.groups[g].theta != b.groups[g].theta || a.groups[g].moment1 != b.groups[g].moment1 ||
            a.groups[g].moment2 != b.groups[g].moment2 || a.groups[g].adamSteps != b.groups[g].adamSteps)
            return false;
    return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = "/dev/shm/subdfit_fuzz_checkpoint_" + std::to_string(getpid()) + ".bin";
    if (size > 0 && data[0] == 'R' && size >= 5) {
        const auto state = stateFrom(data + 5, size - 5);
        subdfit::fit::writeCheckpoint(path, kFingerprint, state);
        std::ifstream in(path, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        uint32_t where;
        std::memcpy(&where, data + 1, 4);
        bytes[where % bytes.size()] ^= char(1 + where / bytes.size() % 255);
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
        try {
            const auto read = subdfit::fit::readCheckpoint(path, kFingerprint);
            if (!read || !same(*read, state)) std::abort();  // a flipped byte was read as data
        } catch (const subdfit::Error&) {}
        return 0;
    }
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    try {
        (void)subdfit::fit::readCheckpoint(path, kFingerprint);
    } catch (const subdfit::Error&) {}
    return 0;
}
