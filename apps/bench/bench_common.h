#pragma once
// Shared bits of the benchmark drivers: timing, peak memory, CSV.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace subdfit::bench {

// Median wall time in milliseconds of `repeats` calls of `work` (which must glFinish itself).
template <class Work>
double medianMilliseconds(int repeats, Work&& work) {
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        work();
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

// Peak resident set size of this process, MiB (VmHWM).
double peakResidentMiB();

// Writes rows (first row = header) as CSV, atomically.
void writeCsv(const std::filesystem::path& path, const std::vector<std::vector<std::string>>& rows);

}  // namespace subdfit::bench
