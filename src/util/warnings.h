#pragma once
// Warnings: an input that is used, but not quite as written (a crease tag on two vertices that
// share no edge). They go to stderr as "subdfit: warning: ..." unless a program or a test
// routes them elsewhere.
#include <functional>
#include <string>

namespace subdfit {

using WarningSink = std::function<void(const std::string& message)>;

void warn(const std::string& message);

// Returns the previous sink; an empty sink restores stderr.
WarningSink setWarningSink(WarningSink sink);

}  // namespace subdfit
