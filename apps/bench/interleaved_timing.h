#pragma once
// Timing that tells a change from a shared machine's noise: the workloads run in rounds, each
// once per round, taking turns at going first, so that load from other processes falls on all of
// them alike; a ratio is taken within each round and summarised by its median, quartiles and the
// median's 95 % confidence interval. Wall time and the process's CPU time (every thread, the GL
// driver's included) are both recorded.
#include <functional>
#include <span>
#include <vector>

namespace subdfit::bench {

struct Samples {
    std::vector<double> wallMs, cpuMs;  // one per round
};

// Runs each workload once per round for `rounds` rounds, round k starting with workload k mod n.
// Each workload must glFinish itself.
std::vector<Samples> timeInterleaved(int rounds, std::span<const std::function<void()>> workloads);

// a_k / b_k, round by round.
std::vector<double> perRoundRatios(const std::vector<double>& a, const std::vector<double>& b);

struct Spread {
    double median, q1, q3;  // quartiles: the spread of one round's value
    double low, high;       // the median's 95 % confidence interval (order statistics)
};
Spread spreadOf(std::vector<double> values);

}  // namespace subdfit::bench
