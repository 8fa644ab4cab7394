#include "gl/timestamp_log.h"

#include <algorithm>
#include <chrono>

#include "util/error.h"

namespace subdfit::gl {

TimestampLog::Mark TimestampLog::now(const char* phase) const {
    Mark mark{.phase = phase};
    if (clock_ == PhaseClock::GpuTimestamp) {
        GLuint id = 0;
        glGenQueries(1, &id);
        glQueryCounter(id, GL_TIMESTAMP);
        mark.query.emplace(id);
    } else {
        glFinish();
        mark.hostMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
    }
    return mark;
}

void TimestampLog::begin() {
    rounds_.emplace_back();
    rounds_.back().push_back(now(""));
}

void TimestampLog::mark(const char* phase) {
    SUBDFIT_CHECK(!rounds_.empty());
    rounds_.back().push_back(now(phase));
}

std::vector<std::pair<std::string, std::vector<double>>> TimestampLog::collect() const {
    std::vector<std::pair<std::string, std::vector<double>>> phases;
    for (const auto& round : rounds_) {
        for (auto& [name, ms] : phases) ms.push_back(0.0);
        double previous = 0.0;
        GLuint64 roundStartNs = 0;  // timestamps are counted from the round's start, in integers
        for (size_t k = 0; k < round.size(); ++k) {
            double at = round[k].hostMs;
            if (round[k].query) {
                GLuint64 ns = 0;
                glGetQueryObjectui64v(round[k].query->id(), GL_QUERY_RESULT, &ns);
                if (k == 0) roundStartNs = ns;
                at = double(ns - roundStartNs) * 1e-6;
            }
            if (k > 0) {
                auto it = std::find_if(phases.begin(), phases.end(),
                                       [&](const auto& p) { return p.first == round[k].phase; });
                if (it == phases.end()) {
                    phases.push_back({round[k].phase, std::vector<double>(size_t(&round - rounds_.data()) + 1, 0.0)});
                    it = phases.end() - 1;
                }
                it->second.back() += at - previous;
            }
            previous = at;
        }
    }
    return phases;
}

}  // namespace subdfit::gl
