#include "io/reduced_image.h"

#include <algorithm>
#include <cstring>

#include "util/error.h"

namespace subdfit::io {

ReducedImage::ReducedImage(int width, int height, int factor)
    : sourceWidth_(width),
      sourceHeight_(height),
      factor_(factor),
      width_((width + factor - 1) / factor),
      height_((height + factor - 1) / factor) {
    SUBDFIT_CHECK(width >= 1 && height >= 1 && factor >= 1);
    rgba_.resize(std::size_t(width_) * std::size_t(height_) * 4);
    if (factor_ > 1) sums_.assign(std::size_t(width_) * 4, 0);
}

void ReducedImage::addRow(const std::uint8_t* rgba) {
    SUBDFIT_CHECK(rows_ < sourceHeight_);
    if (factor_ == 1) {
        std::memcpy(rgba_.data() + std::size_t(rows_) * std::size_t(width_) * 4, rgba, std::size_t(width_) * 4);
        ++rows_;
        return;
    }
    for (int x = 0; x < sourceWidth_; ++x) {
        std::uint64_t* sum = sums_.data() + std::size_t(x / factor_) * 4;
        for (int c = 0; c < 4; ++c) sum[c] += rgba[std::size_t(x) * 4 + std::size_t(c)];
    }
    ++rows_;
    if (rows_ % factor_ == 0 || rows_ == sourceHeight_) flushRow();
}

void ReducedImage::flushRow() {
    const int y = (rows_ - 1) / factor_;
    const int boxRows = rows_ - y * factor_;
    std::uint8_t* out = rgba_.data() + std::size_t(y) * std::size_t(width_) * 4;
    for (int x = 0; x < width_; ++x) {
        const int boxColumns = std::min(factor_, sourceWidth_ - x * factor_);
        const std::uint64_t count = std::uint64_t(boxRows) * std::uint64_t(boxColumns);
        for (int c = 0; c < 4; ++c) {
            std::uint64_t& sum = sums_[std::size_t(x) * 4 + std::size_t(c)];
            out[std::size_t(x) * 4 + std::size_t(c)] = std::uint8_t((sum + count / 2) / count);
            sum = 0;
        }
    }
}

std::vector<std::uint8_t> ReducedImage::take() {
    SUBDFIT_CHECK(rows_ == sourceHeight_);
    return std::move(rgba_);
}

}  // namespace subdfit::io
