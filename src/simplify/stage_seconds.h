#pragma once
// Where a simplify's seconds went, stage by stage: report.json's `seconds_by_stage` and what
// `subdfit-bench simplify` prints. A stage may be timed in several pieces; its seconds add up.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace subdfit::simplify {

class StageSeconds {
public:
    // Adds the seconds since the last lap (or since construction) to `stage`.
    void lap(const std::string& stage) {
        const auto now = Clock::now();
        add(stage, std::chrono::duration<double>(now - last_).count());
        last_ = now;
    }
    void add(const std::string& stage, double seconds) {
        for (auto& [name, total] : stages_)
            if (name == stage) {
                total += seconds;
                return;
            }
        stages_.emplace_back(stage, seconds);
    }
    double total() const {
        double sum = 0.0;
        for (const auto& [name, seconds] : stages_) sum += seconds;
        return sum;
    }
    double of(const std::string& stage) const {
        for (const auto& [name, seconds] : stages_)
            if (name == stage) return seconds;
        return 0.0;
    }
    // In the order the stages first ran.
    const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
    nlohmann::json toJson() const {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& [name, seconds] : stages_) j[name] = seconds;
        return j;
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point last_ = Clock::now();
    std::vector<std::pair<std::string, double>> stages_;
};

// Adds the seconds of its own lifetime to `stage` of `seconds`: for stages timed in many small
// pieces among others.
class TimedStage {
public:
    TimedStage(StageSeconds& seconds, std::string stage) : seconds_(seconds), stage_(std::move(stage)) {}
    ~TimedStage() {
        seconds_.add(stage_, std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
    }
    TimedStage(const TimedStage&) = delete;
    TimedStage& operator=(const TimedStage&) = delete;

private:
    StageSeconds& seconds_;
    std::string stage_;
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace subdfit::simplify
