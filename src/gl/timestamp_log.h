#pragma once
// Timestamps between the phases of a pass: where a step's time goes on the device, apart from the
// CPU that issues the work and the gaps between. Benchmarks attach one; a pass without one records
// nothing.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_handle.h"

namespace subdfit::gl {

// How a phase's end is read. A GPU's GL_TIMESTAMP query is its own clock, the work left to run as
// it would. llvmpipe writes a timestamp when its rasterizer next flushes, phases later than the
// one it ends; there the host's clock after glFinish is the honest one, though waiting for each
// phase serialises them (their sum exceeds the pass's wall time).
enum class PhaseClock { GpuTimestamp, HostAfterFinish };

class TimestampLog {
public:
    explicit TimestampLog(PhaseClock clock = PhaseClock::GpuTimestamp) : clock_(clock) {}

    // Starts a round: the phases marked after it are timed from here.
    void begin();
    // Ends the phase named `phase` (a phase marked twice in a round adds up, e.g. once per view).
    void mark(const char* phase);
    // Per phase in first-seen order, its milliseconds in each round so far (waits for the GPU).
    std::vector<std::pair<std::string, std::vector<double>>> collect() const;

private:
    struct Mark {
        std::optional<GlHandle<QueryTraits>> query{};  // GpuTimestamp
        double hostMs = 0.0;                           // HostAfterFinish
        std::string phase;
    };
    Mark now(const char* phase) const;

    PhaseClock clock_;
    std::vector<std::vector<Mark>> rounds_;
};

}  // namespace subdfit::gl
