#include "bounded_run.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <new>
#include <sstream>

#include "util/error.h"

#if defined(__SANITIZE_ADDRESS__)
#define SUBDFIT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SUBDFIT_TEST_ASAN 1
#endif
#endif

namespace subdfit::test {
namespace {

// The process's address space now, from /proc (the limit is set relative to it).
std::size_t addressSpaceBytes() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmSize:", 0) == 0) return std::size_t(std::stoull(line.substr(7))) * 1024;
    return 0;
}

enum ExitCode { kFinished = 0, kOutOfMemory = 3, kOtherException = 4 };

}  // namespace

BoundedOutcome runBounded(std::size_t extraBytes, unsigned seconds, const std::function<void()>& action) {
    int channel[2];
    if (pipe(channel) != 0) return {.finished = false, .error = "", .problem = "cannot make a pipe"};
    std::fflush(nullptr);
    const pid_t child = fork();
    if (child < 0) return {.finished = false, .error = "", .problem = "cannot fork"};
    if (child == 0) {
        close(channel[0]);
#ifndef SUBDFIT_TEST_ASAN
        const rlim_t limit = rlim_t(addressSpaceBytes() + extraBytes);
        const rlimit bound{limit, limit};
        setrlimit(RLIMIT_AS, &bound);
#else
        (void)extraBytes;
#endif
        alarm(seconds);
        int code = kFinished;
        std::string message;
        try {
            action();
        } catch (const Error& e) {
            message = e.what();
        } catch (const std::bad_alloc&) {
            code = kOutOfMemory;
        } catch (const std::exception& e) {
            message = e.what();
            code = kOtherException;
        }
        for (size_t done = 0; done < message.size();) {
            const ssize_t n = write(channel[1], message.data() + done, message.size() - done);
            if (n <= 0) break;
            done += size_t(n);
        }
        _exit(code);
    }
    close(channel[1]);
    std::string message;
    char buffer[4096];
    for (ssize_t n; (n = read(channel[0], buffer, sizeof buffer)) > 0;) message.append(buffer, size_t(n));
    close(channel[0]);
    int status = 0;
    waitpid(child, &status, 0);
    BoundedOutcome outcome;
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        outcome.problem = signal == SIGALRM ? "took more than " + std::to_string(seconds) + " s"
                                            : "crashed (signal " + std::to_string(signal) + ")";
    } else if (WEXITSTATUS(status) == kOutOfMemory) {
        outcome.problem = "out of memory (more than " + std::to_string(extraBytes >> 20) + " MB)";
    } else if (WEXITSTATUS(status) == kOtherException) {
        outcome.problem = "threw something other than subdfit::Error: " + message;
    } else if (WEXITSTATUS(status) != kFinished) {
        outcome.problem = "exited with " + std::to_string(WEXITSTATUS(status));
    } else {
        outcome.finished = true;
        outcome.error = message;
    }
    return outcome;
}

void expectRefused(const BoundedOutcome& outcome, const std::string& file, const std::string& problem) {
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    EXPECT_NE(outcome.error.find(file), std::string::npos) << outcome.error;
    EXPECT_NE(outcome.error.find(problem), std::string::npos) << "expected '" << problem << "' in: " << outcome.error;
    EXPECT_EQ(outcome.error.find('\n'), std::string::npos) << outcome.error;
}

}  // namespace subdfit::test
