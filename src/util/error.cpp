#include "util/error.h"

#include <string>

namespace subdfit {

void checkFailed(const char* expr, const char* file, int line) {
    throw InternalError(std::string("internal check failed: ") + expr + " (" + file + ":" + std::to_string(line) +
                        "): a bug in subdfit, not in the input");
}

}  // namespace subdfit
