#include "bench_common.h"

#include <fstream>
#include <sstream>

#include <sys/resource.h>

#include "io/atomic_file.h"

namespace subdfit::bench {

double peakResidentMiB() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
    return 0.0;
}

double processCpuSeconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

void writeCsv(const std::filesystem::path& path, const std::vector<std::vector<std::string>>& rows) {
    std::ostringstream text;
    for (const auto& row : rows) {
        for (size_t i = 0; i < row.size(); ++i) text << (i ? "," : "") << row[i];
        text << "\n";
    }
    io::writeTextAtomically(path, text.str());
}

}  // namespace subdfit::bench
