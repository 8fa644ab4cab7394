#pragma once
// Shared bits of the benchmark drivers: timing, peak memory, CSV.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace subdfit::bench {

// Best (minimum) wall time in milliseconds of `repeats` calls of `work`, which must glFinish
// itself. On a shared, noisy machine other load only ever adds time, so the minimum is the most
// repeatable estimate of what the work itself costs.
template <class Work>
double bestMilliseconds(int repeats, Work&& work) {
    std::vector<double> times;
    for (int i = 0; i < repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        work();
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    return times.front();
}

// Peak resident set size of this process, MiB (VmHWM).
double peakResidentMiB();

// CPU seconds this process has used so far, every thread (llvmpipe's included), user and system:
// on a shared machine, what a run cost beside its wall time.
double processCpuSeconds();

// Writes rows (first row = header) as CSV, atomically.
void writeCsv(const std::filesystem::path& path, const std::vector<std::vector<std::string>>& rows);

}  // namespace subdfit::bench
