#include "subdiv/osd_messages.h"

#include <opensubdiv/far/error.h>

#include <cstdio>
#include <mutex>

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;

// The callbacks are global, but the log is per thread: meshes may be built concurrently.
thread_local OsdMessageScope* currentScope = nullptr;

void onError(Far::ErrorType, const char* message) {
    if (currentScope) currentScope->addError(message);
    else std::fprintf(stderr, "OpenSubdiv error: %s\n", message);
}

void onWarning(const char* message) {
    if (currentScope) currentScope->addWarning(message);
    else std::fprintf(stderr, "OpenSubdiv warning: %s\n", message);
}

}  // namespace

OsdMessageScope::OsdMessageScope() : outer_(currentScope) {
    static std::once_flag installed;
    std::call_once(installed, [] {
        Far::SetErrorCallback(onError);
        Far::SetWarningCallback(onWarning);
    });
    currentScope = this;
}

OsdMessageScope::~OsdMessageScope() { currentScope = outer_; }

std::string OsdMessageScope::summary() const {
    std::string text;
    for (const auto* list : {&errors_, &warnings_})
        for (const std::string& message : *list) {
            if (!text.empty()) text += "; ";
            text += message;
        }
    return text;
}

}  // namespace subdfit::subdiv
