#include "codec/decode_budget.h"

#include "util/checked_size.h"
#include "util/error.h"

namespace subdfit::codec {

bool DecodeBudget::fits(std::uint64_t count, std::uint64_t bytesEach) const {
    return !productExceeds(count, bytesEach, left_);
}

void DecodeBudget::spend(std::uint64_t count, std::uint64_t bytesEach, const std::string& what) {
    if (!fits(count, bytesEach)) {
        const std::string size = productExceeds(count, bytesEach, UINT64_MAX)
                                     ? "far more"
                                     : "about " + std::to_string((count * bytesEach) >> 20) + " MB";
        throw Error(name_ + ": " + what + " would take " + size + " to decode, more than the " +
                    std::to_string(total_ >> 20) + " MB a decode may use" +
                    (left_ < total_ ? " (" + std::to_string((total_ - left_) >> 20) + " MB already spoken for)" : ""));
    }
    left_ -= count * bytesEach;
}

}  // namespace subdfit::codec
