// Checks a subdfit-view screenshot: the panel was drawn left of `view-left`, and the 3D view to
// its right shows an object, not a blank or uniform background: enough pixels differ from the
// background, and their centroid sits near the view's centre (the scene is normalised and the
// camera starts framing it).
//   check_screenshot FILE VIEW_LEFT
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

int fail(const std::string& file, const std::string& problem) {
    std::fprintf(stderr, "%s: %s\n", file.c_str(), problem.c_str());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: check_screenshot FILE VIEW_LEFT\n");
        return 2;
    }
    const std::string file = argv[1];
    const int left = std::atoi(argv[2]);
    auto in = OIIO::ImageInput::open(file);
    if (!in) return fail(file, "cannot read: " + OIIO::geterror());
    const auto& spec = in->spec();
    const int w = spec.width, h = spec.height, channels = spec.nchannels;
    std::vector<float> pixels(size_t(w) * h * channels);
    if (channels < 3 || !in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
        return fail(file, "not an RGB image");
    if (left <= 0 || left >= w - 16) return fail(file, "view-left outside the image");
    auto at = [&](int x, int y, int c) { return pixels[(size_t(y) * w + x) * channels + c]; };

    // The background is a vertical gradient: each row's own background is its rightmost pixel.
    long object = 0;
    double sumX = 0.0, sumY = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = left; x < w; ++x) {
            float difference = 0.0f;
            for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(at(x, y, c) - at(w - 1, y, c)));
            if (difference > 0.06f) {
                ++object;
                sumX += x;
                sumY += y;
            }
        }
    const double viewPixels = double(w - left) * h;
    const double fraction = double(object) / viewPixels;
    std::printf("%s: %dx%d, object covers %.1f %% of the view\n", file.c_str(), w, h, 100.0 * fraction);
    if (fraction < 0.03) return fail(file, "the view is (nearly) blank: no object drawn");
    if (fraction > 0.8) return fail(file, "the view is nearly all foreground: no background seen");
    const double cx = sumX / double(object), cy = sumY / double(object);
    const double centreX = 0.5 * (left + w), centreY = 0.5 * h;
    if (std::abs(cx - centreX) > 0.15 * (w - left) || std::abs(cy - centreY) > 0.15 * h) {
        char where[128];
        std::snprintf(where, sizeof where, "object centred at (%.0f, %.0f), view centre (%.0f, %.0f)", cx, cy, centreX, centreY);
        return fail(file, where);
    }

    // The panel: not one flat colour.
    long varied = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < left; ++x)
            if (std::abs(at(x, y, 0) - at(0, h / 2, 0)) + std::abs(at(x, y, 1) - at(0, h / 2, 1)) > 0.1f) ++varied;
    if (double(varied) / (double(left) * h) < 0.01) return fail(file, "the control panel is missing");
    return 0;
}
