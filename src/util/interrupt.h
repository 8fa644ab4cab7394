#pragma once
// What SIGINT and SIGTERM mean to subdfit: a stop request for the whole process. Long phases
// (reading inputs, rendering targets, baking, scoring) poll it and unwind with Interrupted, so
// that nothing half-done is left behind; the fit loop polls it between steps and stops at a
// checkpoint. A second signal exits at once, for a user who will not wait.
#include <atomic>
#include <string>

#include "util/error.h"

namespace subdfit {

class Interrupted : public Error {
public:
    explicit Interrupted(const std::string& what = "interrupted") : Error(what) {}
};

// The flag itself, for code that must stop gracefully rather than throw (the fit loop).
std::atomic<bool>& stopRequest();

inline bool stopRequested() { return stopRequest().load(std::memory_order_relaxed); }

inline void throwIfStopRequested() {
    if (stopRequested()) throw Interrupted();
}

// SIGINT and SIGTERM: the first sets the stop request, the second exits with 128 + signal.
void installStopSignals();

}  // namespace subdfit
