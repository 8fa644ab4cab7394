#include "io/atomic_file.h"

#include <fstream>
#include <unistd.h>

#include "util/error.h"

namespace subdfit::io {

void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path&)>& write) {
    // Keep the real extension last: writers such as OpenImageIO pick the format from it.
    auto temporary = destination;
    temporary.replace_filename("." + destination.stem().string() + ".tmp" + std::to_string(getpid()) +
                               destination.extension().string());
    try {
        write(temporary);
        std::filesystem::rename(temporary, destination);
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

void writeTextAtomically(const std::filesystem::path& destination, const std::string& text) {
    writeAtomically(destination, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        out.close();
        if (!out) throw fileError(destination.string(), "could not write");
    });
}

}  // namespace subdfit::io
