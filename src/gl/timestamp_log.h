#pragma once
// GPU timestamps between the phases of a pass (GL_TIMESTAMP queries): where a step's time goes on
// the device, apart from the CPU that issues the work and the gaps between. Benchmarks attach one;
// a pass without one records nothing.
#include <string>
#include <utility>
#include <vector>

#include "gl/gl_handle.h"

namespace subdfit::gl {

class TimestampLog {
public:
    // Starts a round: the phases marked after it are timed from here.
    void begin();
    // Ends the phase named `phase` (a phase marked twice in a round adds up, e.g. once per view).
    void mark(const char* phase);
    // Per phase in first-seen order, its milliseconds in each round so far (waits for the GPU).
    std::vector<std::pair<std::string, std::vector<double>>> collect() const;

private:
    struct Mark {
        GlHandle<QueryTraits> query;
        std::string phase;
    };
    std::vector<std::vector<Mark>> rounds_;
};

}  // namespace subdfit::gl
