// The result-folder reader the viewer opens folders with (fit/result_folder.h) under libFuzzer: the
// input is report.json of a folder that also holds asset.subd, a baseline, a symlink pointing out,
// a FIFO and a subfolder, beside a file outside the folder. Any input must give a ResultFolder or
// subdfit::Error; never a crash, a sanitizer report, an entry that resolves outside the folder or
// is not a regular file, a reference the report did not record by its digest, or a note that
// carries a control byte to the terminal.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "fit/result_folder.h"
#include "io/output_folder.h"
#include "util/error.h"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& bytes) {
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(bytes.data(), 1, bytes.size(), f);
        std::fclose(f);
    }
}

// The folder, made once per process.
fs::path folder() {
    const fs::path root = "/dev/shm/subdfit_fuzz_result_" + std::to_string(getpid());
    const fs::path dir = root / "result";
    fs::create_directories(dir / "baselines/sub");
    write(dir / "asset.subd", "SUBD");
    write(dir / "baselines/decimated.glb", "glTF");
    write(root / "outside.obj", "v 0 0 0\n");
    mkfifo((dir / "baselines/fifo.glb").c_str(), 0600);
    std::error_code ec;
    fs::create_symlink("../../outside.obj", dir / "baselines/out.obj", ec);
    fs::create_directory_symlink("..", dir / "baselines/up", ec);
    return fs::canonical(dir);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = folder();
    write(dir / "report.json", std::string(reinterpret_cast<const char*>(data), size));
    try {
        const subdfit::fit::ResultFolder result = subdfit::fit::readResultFolder(dir);
        for (const auto& entry : result.entries)
            for (const auto& file : entry.levels)
                if (!subdfit::io::isStrictlyInside(fs::canonical(file), dir) || !fs::is_regular_file(file))
                    std::abort();
        if (!result.reference.empty()) std::abort();  // no file here has a digest the input could know
        for (const auto& note : result.notes)
            for (char c : note)
                if (static_cast<unsigned char>(c) < 0x20) std::abort();
        if (!result.settings.is_object()) std::abort();
    } catch (const subdfit::Error&) {}
    return 0;
}
