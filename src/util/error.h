#pragma once
// One exception type for everything a user can cause or fix: bad files, impossible options,
// a GL context that cannot be had, a shader that does not compile. `main` catches it, prints
// what() as one line and exits non-zero. Broken internal contracts use SUBDFIT_CHECK instead.
#include <stdexcept>
#include <string>

namespace subdfit {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "path: problem" -- every input error names the file it is about.
inline Error fileError(const std::string& path, const std::string& problem) {
    return Error(path + ": " + problem);
}

[[noreturn]] void checkFailed(const char* expr, const char* file, int line);

}  // namespace subdfit

#define SUBDFIT_CHECK(expr) \
    ((expr) ? void(0) : ::subdfit::checkFailed(#expr, __FILE__, __LINE__))
