#include "interleaved_timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bench_common.h"
#include "util/error.h"

namespace subdfit::bench {

std::vector<Samples> timeInterleaved(int rounds, std::span<const std::function<void()>> workloads) {
    const int n = int(workloads.size());
    std::vector<Samples> samples(workloads.size());
    for (int round = 0; round < rounds; ++round)
        for (int k = 0; k < n; ++k) {
            const int w = (round + k) % n;
            const double cpuStart = processCpuSeconds();
            const auto start = std::chrono::steady_clock::now();
            workloads[size_t(w)]();
            const auto end = std::chrono::steady_clock::now();
            samples[size_t(w)].wallMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
            samples[size_t(w)].cpuMs.push_back(1000.0 * (processCpuSeconds() - cpuStart));
        }
    return samples;
}

std::vector<double> perRoundRatios(const std::vector<double>& a, const std::vector<double>& b) {
    SUBDFIT_CHECK(a.size() == b.size());
    std::vector<double> ratios;
    for (size_t k = 0; k < a.size(); ++k)
        if (b[k] > 0.0) ratios.push_back(a[k] / b[k]);
    return ratios;
}

Spread spreadOf(std::vector<double> values) {
    if (values.empty()) return {};
    std::sort(values.begin(), values.end());
    const double n = double(values.size());
    // Linear interpolation between order statistics at fraction q of the way.
    auto quantile = [&](double q) {
        const double at = q * (n - 1.0);
        const size_t below = size_t(std::floor(at));
        const size_t above = std::min(values.size() - 1, below + 1);
        return values[below] + (at - double(below)) * (values[above] - values[below]);
    };
    // The median lies between these order statistics with 95 % confidence (normal approximation
    // to the binomial: n/2 ± 1.96 √n / 2).
    const double halfWidth = 0.98 * std::sqrt(n);
    auto orderStatistic = [&](double rank) { return values[size_t(std::clamp(rank, 0.0, n - 1.0))]; };
    return {quantile(0.5), quantile(0.25), quantile(0.75), orderStatistic(std::floor(n / 2.0 - halfWidth)),
            orderStatistic(std::ceil(n / 2.0 + halfWidth) - 1.0)};
}

}  // namespace subdfit::bench
