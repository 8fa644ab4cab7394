#include "io/output_file.h"

#include <fstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::io {

WrittenFile writeOutput(const std::filesystem::path& destination,
                        const std::function<void(const std::filesystem::path&)>& write) {
    io::writeAtomically(destination, write);
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(destination, ec);
    if (ec) throw fileError(destination.string(), "written but cannot be read back: " + ec.message());
    return {destination, size};
}

WrittenFile writeBytes(const std::filesystem::path& destination, std::span<const unsigned char> bytes) {
    return writeOutput(destination, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw fileError(destination.string(), "cannot create the file (is the folder writable?)");
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        out.close();
        if (!out) throw fileError(destination.string(), "could not write (disk full?)");
    });
}

}  // namespace subdfit::io
