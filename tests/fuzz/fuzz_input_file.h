#pragma once
// The loaders read paths (they name the file in every error), so each input goes through a file
// in memory-backed /dev/shm, named with the extension the loader dispatches on.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

inline std::string writeFuzzInput(const uint8_t* data, size_t size, const char* extension) {
    const std::string path = "/dev/shm/subdfit_fuzz_" + std::to_string(getpid()) + extension;
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return path;
}
