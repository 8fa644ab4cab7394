#include "util/warnings.h"

#include <cstdio>
#include <mutex>

#include "util/printable.h"

namespace subdfit {
namespace {

std::mutex mutex;
WarningSink current;

}  // namespace

void warn(const std::string& message) {
    std::lock_guard lock(mutex);
    if (current) current(message);
    else std::fprintf(stderr, "subdfit: warning: %s\n", printable(message, 4096).c_str());
}

WarningSink setWarningSink(WarningSink sink) {
    std::lock_guard lock(mutex);
    std::swap(current, sink);
    return sink;
}

}  // namespace subdfit
