// The batch manifest reader under libFuzzer: any bytes give lines or subdfit::Error, and every
// line it returns names a reference and holds no control character.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "simplify/manifest.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = "/dev/shm/subdfit_fuzz_manifest_" + std::to_string(getpid()) + ".txt";
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    try {
        for (const auto& line : subdfit::simplify::readManifest(path)) {
            if (line.number < 1 || line.reference.empty()) std::abort();
            for (const auto& word : line.options)
                for (char c : word)
                    if (static_cast<unsigned char>(c) < 0x20 && c != '\t') std::abort();
        }
    } catch (const subdfit::Error&) {}
    return 0;
}
