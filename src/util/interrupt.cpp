#include "util/interrupt.h"

#include <csignal>
#include <unistd.h>

namespace subdfit {
namespace {

std::atomic<bool> requested{false};

void onStopSignal(int signal) {
    if (requested.exchange(true)) _exit(128 + signal);  // only async-signal-safe calls here
}

}  // namespace

std::atomic<bool>& stopRequest() { return requested; }

void installStopSignals() {
    struct sigaction action {};
    action.sa_handler = onStopSignal;
    sigemptyset(&action.sa_mask);
    // No SA_RESTART: a read blocked on a slow file returns EINTR and sees the request.
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

}  // namespace subdfit
