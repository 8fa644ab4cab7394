// A main for the fuzz targets where libFuzzer is not there (gcc): each argument, a file or a
// folder of files, is read and handed to LLVMFuzzerTestOneInput once, under the sanitizers the
// target was built with. Exits non-zero on the first report (the sanitizers abort) or unreadable
// argument; prints how many inputs ran.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    int runs = 0;
    auto replay = [&](const fs::path& file) {
        std::ifstream in(file, std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
        const size_t size = bytes.size();
        bytes.push_back(0);  // as libFuzzer, never a null pointer, even for an empty input
        LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), size);
        ++runs;
    };
    for (int k = 1; k < argc; ++k) {
        std::error_code ec;
        if (fs::is_directory(argv[k], ec)) {
            for (const auto& entry : fs::recursive_directory_iterator(argv[k]))
                if (entry.is_regular_file()) replay(entry.path());
        } else if (fs::is_regular_file(argv[k], ec)) {
            replay(argv[k]);
        } else {
            std::fprintf(stderr, "%s: not a file or folder\n", argv[k]);
            return 2;
        }
    }
    std::printf("%s: %d inputs replayed\n", argv[0], runs);
    return 0;
}
