#include "util/error.h"

#include <cstdio>
#include <cstdlib>

namespace subdfit {

void checkFailed(const char* expr, const char* file, int line) {
    std::fprintf(stderr, "subdfit: internal check failed: %s (%s:%d)\n", expr, file, line);
    std::abort();
}

}  // namespace subdfit
