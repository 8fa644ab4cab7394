// comparison.png: every column says what it is (name, bytes, PSNR) above its view, and the error
// row says what its colours mean.
#include <gtest/gtest.h>

#include <string>

#include "io/image_io.h"
#include "simplify/compare/comparison_image.h"
#include "test_paths.h"
#include "util/warnings.h"

namespace subdfit::test {
namespace {

// Pixels of the top-down RGBA `image` in [x0, x1) × [y0, y1) brighter than mid grey.
int brightPixels(const io::DecodedImage& image, int x0, int x1, int y0, int y1) {
    int bright = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const std::uint8_t* p = &image.rgba[4 * (size_t(y) * size_t(image.width) + size_t(x))];
            bright += p[0] + p[1] + p[2] > 3 * 128;
        }
    return bright;
}

TEST(ComparisonImage, EveryColumnAndTheErrorRowAreLabelled) {
    constexpr int kRes = 128;
    const std::vector<glm::vec4> reference(kRes * kRes, glm::vec4(0.3f, 0.3f, 0.3f, 1.0f));
    simplify::Quality ours, decimation;
    ours.view = reference;  // no error
    ours.bytes = 18415;
    ours.psnrHoldout = 30.14;
    decimation.view.assign(kRes * kRes, glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
    decimation.bytes = 18404;
    decimation.psnrHoldout = 23.49;

    std::string fontMissing;
    const WarningSink previous = setWarningSink([&](const std::string& message) { fontMissing = message; });
    const auto path = scratchDir("comparison_image") / "comparison.png";
    simplify::writeComparison(path, kRes, reference, {{"subdfit", &ours}, {"decimation + Draco", &decimation}});
    setWarningSink(previous);
    if (!fontMissing.empty()) GTEST_SKIP() << fontMissing;

    const io::DecodedImage image = io::readImage(path);
    ASSERT_EQ(image.width, 3 * kRes);
    const int band = image.height - 2 * kRes;  // the captions above the views
    ASSERT_GT(band, 10) << "no room for captions";
    // Each column's caption has text in it; the views and their errors sit under it, unlabelled.
    for (int column = 0; column < 3; ++column) {
        EXPECT_GT(brightPixels(image, column * kRes, (column + 1) * kRes, 0, band), 30) << "column " << column;
        EXPECT_EQ(brightPixels(image, column * kRes, (column + 1) * kRes, band, band + kRes), 0) << "column " << column;
    }
    // Under the reference, the error row's scale: words and a ramp up to white.
    EXPECT_GT(brightPixels(image, 0, kRes, band + kRes, image.height), 100);
    // Under subdfit (no error) black; under the darker decimation its error shows.
    EXPECT_EQ(brightPixels(image, kRes, 2 * kRes, band + kRes, image.height), 0);
    const std::uint8_t* error =
        &image.rgba[4 * (size_t(band + kRes + kRes / 2) * size_t(image.width) + 2 * kRes + kRes / 2)];
    EXPECT_GT(error[0], 100);  // an RMS error of 0.2: red towards yellow
}

// A picture too small for its captions (as the tests' quick runs make) is written all the same,
// the captions that do not fit left out.
TEST(ComparisonImage, ATinyPictureLeavesOutWhatDoesNotFit) {
    constexpr int kRes = 16;
    const std::vector<glm::vec4> reference(kRes * kRes, glm::vec4(0.3f, 0.3f, 0.3f, 1.0f));
    simplify::Quality ours;
    ours.view = reference;
    const auto path = scratchDir("comparison_image_tiny") / "comparison.png";
    simplify::writeComparison(path, kRes, reference, {{"subdfit", &ours}});
    const io::DecodedImage image = io::readImage(path);
    EXPECT_EQ(image.width, 2 * kRes);
    EXPECT_GE(image.height, 2 * kRes);
}

}  // namespace
}  // namespace subdfit::test
