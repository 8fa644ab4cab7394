#pragma once
// Runs an action in a child process with a memory and a time limit, so that a test can say "this
// hostile file is refused within 512 MB and 20 s" without trusting the code under test to stay
// within them: an allocation beyond the limit fails there (std::bad_alloc), a hang is cut short,
// a crash is reported, and the test process itself is never at risk. Under AddressSanitizer
// (whose shadow memory needs the address space) only the time limit applies.
#include <cstddef>
#include <functional>
#include <string>

namespace subdfit::test {

struct BoundedOutcome {
    bool finished = false;  // returned or threw subdfit::Error within the limits
    std::string error;      // the subdfit::Error's message ("" when it returned)
    std::string problem;    // otherwise: "out of memory", "took more than N s", "crashed (signal N)", ...
};

BoundedOutcome runBounded(std::size_t extraBytes, unsigned seconds, const std::function<void()>& action);

// Asserts (gtest) that the action finished within its limits by a one-line refusal naming
// `file` and `problem`.
void expectRefused(const BoundedOutcome& outcome, const std::string& file, const std::string& problem);

}  // namespace subdfit::test
