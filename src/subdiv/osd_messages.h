#pragma once
// OpenSubdiv reports topology problems through process-wide callbacks whose default prints to
// stdout and carries on (factories then return null). A scope collects this thread's messages
// instead, so the caller can turn a failure into a subdfit::Error with OpenSubdiv's own words.
#include <string>
#include <vector>

namespace subdfit::subdiv {

class OsdMessageScope {
public:
    OsdMessageScope();  // installs the callbacks (once per process) and starts an empty log
    ~OsdMessageScope();
    OsdMessageScope(const OsdMessageScope&) = delete;
    OsdMessageScope& operator=(const OsdMessageScope&) = delete;

    // Errors first, then warnings, "; "-joined; empty when OpenSubdiv said nothing.
    std::string summary() const;

    void addError(const char* message) { errors_.emplace_back(message); }
    void addWarning(const char* message) { warnings_.emplace_back(message); }

private:
    std::vector<std::string> errors_, warnings_;
    OsdMessageScope* outer_ = nullptr;  // scopes nest per thread
};

}  // namespace subdfit::subdiv
