#include "simplify/compare/comparison_image.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/image_io.h"

namespace subdfit::simplify {
namespace {

constexpr float kHeatScale = 0.25f;  // RMS error shown as white

// Black → red → yellow → white, in thirds, for t in [0, 1].
glm::vec4 heatColour(float t) {
    return {glm::clamp(3.0f * t, 0.0f, 1.0f), glm::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
            glm::clamp(3.0f * t - 2.0f, 0.0f, 1.0f), 1.0f};
}

glm::vec4 heat(const glm::vec4& a, const glm::vec4& b) {
    const glm::vec3 d = glm::vec3(a) - glm::vec3(b);
    return heatColour(glm::clamp(std::sqrt(glm::dot(d, d) / 3.0f) / kHeatScale, 0.0f, 1.0f));
}

// "18 415 bytes, 30.14 dB"
std::string caption(const Quality& q) {
    std::string digits = std::to_string(q.bytes), grouped;
    for (size_t k = 0; k < digits.size(); ++k) {
        if (k > 0 && (digits.size() - k) % 3 == 0) grouped += ' ';
        grouped += digits[k];
    }
    char psnr[32];
    std::snprintf(psnr, sizeof psnr, "%.2f dB", q.psnrHoldout);
    return grouped + " bytes, " + psnr;
}

// The picture's geometry: a caption band over the views' row, the error row under it.
struct Layout {
    int res, columns, textSize, lineHeight, band;
    int width() const { return columns * res; }
    int height() const { return band + 2 * res; }
};

Layout layoutFor(int res, int columns) {
    const int textSize = std::clamp(res / 16, 9, 16);
    const int lineHeight = textSize + textSize / 3;
    return {res, columns, textSize, lineHeight, 2 * lineHeight + textSize / 2};
}

// The ramp of the heat colours, `height` rows from `top` (counted from the image's top), across
// the cell under the reference, in `pixels` (rows bottom-up).
void drawRamp(const Layout& l, int top, int height, int pad, std::vector<glm::vec4>& pixels) {
    const int span = std::max(1, l.res - 2 * pad - 1);
    for (int y = top; y < std::min(top + height, l.height()); ++y)
        for (int x = pad; x <= pad + span; ++x)
            pixels[size_t(l.height() - 1 - y) * size_t(l.width()) + size_t(x)] =
                heatColour(float(x - pad) / float(span));
}

// The captions: each column's name and figures in the band, and in the cell under the reference
// what the error row's colours mean (a ramp drawn into `pixels`, its ends labelled).
std::vector<io::ImageText> captions(const Layout& l, const std::vector<ComparisonColumn>& columns,
                                    std::vector<glm::vec4>& pixels) {
    const int pad = l.textSize / 2, line = l.lineHeight;
    std::vector<io::ImageText> texts{{"reference", pad, pad / 2, l.textSize},
                                     {"held-out view", pad, pad / 2 + line, l.textSize}};
    for (size_t c = 0; c < columns.size(); ++c) {
        const int x = int(c + 1) * l.res + pad;
        texts.push_back({columns[c].name, x, pad / 2, l.textSize});
        texts.push_back({caption(*columns[c].quality), x, pad / 2 + line, l.textSize});
    }
    const int top = l.band + l.res + pad;  // the cell under the reference, from the image's top
    texts.push_back({"error in this row", pad, top, l.textSize});
    texts.push_back({"(RMS per pixel)", pad, top + line, l.textSize});
    const int rampTop = top + 2 * line + pad / 2, rampHeight = l.textSize;
    drawRamp(l, rampTop, rampHeight, pad, pixels);
    texts.push_back({"0", pad, rampTop + rampHeight + pad / 2, l.textSize});
    texts.push_back({"0.25+", l.res - pad - 3 * l.textSize, rampTop + rampHeight + pad / 2, l.textSize});
    return texts;
}

}  // namespace

void writeComparison(const std::filesystem::path& path, int res, const std::vector<glm::vec4>& reference,
                     const std::vector<ComparisonColumn>& columns) {
    const Layout l = layoutFor(res, 1 + int(columns.size()));
    // Bottom-up like the inputs: the error row first (rows 0..res−1), then the views, then the band.
    std::vector<glm::vec4> out(size_t(l.width()) * size_t(l.height()), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    auto put = [&](int column, bool views, int x, int y, const glm::vec4& c) {
        out[size_t(y + (views ? res : 0)) * size_t(l.width()) + size_t(column * res + x)] = c;
    };
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const size_t i = size_t(y) * size_t(res) + size_t(x);
            put(0, true, x, y, reference[i]);
            for (size_t c = 0; c < columns.size(); ++c) {
                const std::vector<glm::vec4>& view = columns[c].quality->view;
                put(int(c) + 1, true, x, y, view[i]);
                put(int(c) + 1, false, x, y, heat(view[i], reference[i]));
            }
        }
    const std::vector<io::ImageText> texts = captions(l, columns, out);
    io::writeImage(path, out, l.width(), l.height(), texts);
}

}  // namespace subdfit::simplify
