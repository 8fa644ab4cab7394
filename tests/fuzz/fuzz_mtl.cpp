// The MTL reader under libFuzzer: the input is the material library of a fixed textured OBJ
// (whose faces use the materials `a`, `b` and `c`) in a folder of its own that also holds a small
// PNG, an image outside the folder's reach and a symlink pointing out. Any input must give a
// mesh or subdfit::Error; never a crash, a sanitizer report, a read outside the folder (the
// outside image is a FIFO: opening it would block), or an allocation past the run's limit.
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"
#include "util/warnings.h"

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
    const fs::path root = "/dev/shm/subdfit_fuzz_mtl_" + std::to_string(getpid());
    const fs::path dir = root / "asset";
    fs::create_directories(dir);
    write(dir / "m.obj",
          "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
          "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/4\nusemtl c\nf 2/2 3/3 4/4\n");
    subdfit::io::writeImage(dir / "t.png", std::vector<glm::vec4>(4, glm::vec4(1, 0, 0, 1)), 2, 2);
    mkfifo((root / "outside.png").c_str(), 0600);
    std::error_code ec;
    fs::create_symlink("../outside.png", dir / "out.png", ec);
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const auto quiet = subdfit::setWarningSink([](const std::string&) {});
    (void)quiet;
    static const fs::path dir = folder();
    write(dir / "m.mtl", std::string(reinterpret_cast<const char*>(data), size));
    try {
        (void)subdfit::mesh::loadReference(dir / "m.obj");
    } catch (const subdfit::Error&) {}
    return 0;
}
