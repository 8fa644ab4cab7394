#pragma once
// An image made `factor` times smaller on each side while its rows arrive, top first: each pixel
// the mean of its factor × factor box (boxes at the right and bottom edges partial). A decoder
// that streams rows into it holds one row of sums beside the result, never the full image, so
// a texture larger than subdfit uses costs what it is used at.
#include <cstdint>
#include <vector>

namespace subdfit::io {

class ReducedImage {
public:
    // width, height: of the rows that arrive; factor >= 1.
    ReducedImage(int width, int height, int factor);

    int width() const { return width_; }    // of the result
    int height() const { return height_; }  // of the result

    // The next row: width × 4 bytes of RGBA8.
    void addRow(const std::uint8_t* rgba);
    int rowsAdded() const { return rows_; }

    // The result (RGBA8, top row first), once every row has arrived.
    std::vector<std::uint8_t> take();

private:
    void flushRow();

    int sourceWidth_, sourceHeight_, factor_;
    int width_, height_;
    int rows_ = 0;
    std::vector<std::uint64_t> sums_;  // width_ × 4: the output row being summed
    std::vector<std::uint8_t> rgba_;   // width_ × height_ × 4
};

}  // namespace subdfit::io
