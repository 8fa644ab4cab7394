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

// An option out of its range. The core names the option by its key (report.json's, e.g.
// "map_resolution"); the command line turns the key into the flag a user typed.
class OptionError : public Error {
public:
    OptionError(std::string key, const std::string& problem)
        : Error("invalid option: " + key + " " + problem), key_(std::move(key)), problem_(problem) {}
    const std::string& key() const { return key_; }
    const std::string& problem() const { return problem_; }

private:
    std::string key_, problem_;
};

// "path: problem" -- every input error names the file it is about.
inline Error fileError(const std::string& path, const std::string& problem) { return Error(path + ": " + problem); }

// A broken internal contract: a bug, not the input's fault. SUBDFIT_CHECK throws it rather than
// aborting, so that a batch records the asset as failed and goes on to the next, and a run
// stops with its outputs unwritten (their temp files removed) and a non-zero exit.
class InternalError : public std::logic_error {
public:
    using std::logic_error::logic_error;
};

[[noreturn]] void checkFailed(const char* expr, const char* file, int line);

}  // namespace subdfit

#define SUBDFIT_CHECK(expr) ((expr) ? void(0) : ::subdfit::checkFailed(#expr, __FILE__, __LINE__))
