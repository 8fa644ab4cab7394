#pragma once
// What a refusal says: the message of the subdfit::Error that `action` throws, or "" when it
// throws none (so a test can both require the refusal and check its wording).
#include <string>
#include <utility>

#include "util/error.h"

namespace subdfit::test {

template <class Action>
std::string errorMessage(Action&& action) {
    try {
        std::forward<Action>(action)();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace subdfit::test
