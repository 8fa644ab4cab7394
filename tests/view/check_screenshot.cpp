// Checks a subdfit-view screenshot: the panel was drawn left of `view-left`, and the 3D view to
// its right shows an object, not a blank or uniform background: enough pixels differ from the
// background, and their centroid sits near the view's centre (the scene is normalised and the
// camera starts framing it).
//   check_screenshot FILE VIEW_LEFT [--columns N] [--differs OTHER]
// --columns N: the view is N columns side by side (the result view), each showing an object
// centred in it (its label row at the top and its left edge, a separator, are not looked at).
// --differs OTHER: the view differs from OTHER's (a screenshot of the same size) over at least
// 2 % of this one's object pixels: it shows something else than OTHER does.
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

struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

std::string readImage(const std::string& file, Image& image) {
    auto in = OIIO::ImageInput::open(file);
    if (!in) return "cannot read: " + OIIO::geterror();
    const auto& spec = in->spec();
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    image.pixels.resize(size_t(image.width) * image.height * image.channels);
    if (image.channels < 3 || !in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        return "not an RGB image";
    return "";
}

float difference(const Image& a, int x, int y, const Image& b, int u, int v) {
    float d = 0.0f;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.at(x, y, c) - b.at(u, v, c)));
    return d;
}

// The background is a vertical gradient: each row's own background is the rightmost pixel of its
// stretch [left, right).
bool isObject(const Image& image, int x, int y, int right) {
    return difference(image, x, y, image, right - 1, y) > 0.06f;
}

// The object in [left, right) × [top, height): there, and centred.
int checkObject(const std::string& file, const Image& image, int left, int right, int top, const char* what) {
    long object = 0;
    double sumX = 0.0, sumY = 0.0;
    for (int y = top; y < image.height; ++y)
        for (int x = left; x < right; ++x)
            if (isObject(image, x, y, right)) {
                ++object;
                sumX += x;
                sumY += y;
            }
    const double fraction = double(object) / (double(right - left) * (image.height - top));
    std::printf("%s: %s covers %.1f %%\n", file.c_str(), what, 100.0 * fraction);
    if (fraction < 0.03) return fail(file, std::string(what) + " is (nearly) blank: no object drawn");
    if (fraction > 0.8) return fail(file, std::string(what) + " is nearly all foreground: no background seen");
    const double cx = sumX / double(object), cy = sumY / double(object);
    const double centreX = 0.5 * (left + right), centreY = 0.5 * image.height;
    if (std::abs(cx - centreX) > 0.15 * (right - left) || std::abs(cy - centreY) > 0.15 * image.height) {
        char where[160];
        std::snprintf(where, sizeof where, "%s: object centred at (%.0f, %.0f), its centre is (%.0f, %.0f)", what, cx,
                      cy, centreX, centreY);
        return fail(file, where);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3 && argc != 5 && argc != 7) {
        std::fprintf(stderr, "usage: check_screenshot FILE VIEW_LEFT [--columns N] [--differs OTHER]\n");
        return 2;
    }
    const std::string file = argv[1];
    const int left = std::atoi(argv[2]);
    int columns = 0;
    std::string other;
    for (int a = 3; a + 1 < argc; a += 2) {
        if (std::string(argv[a]) == "--columns") columns = std::atoi(argv[a + 1]);
        else if (std::string(argv[a]) == "--differs") other = argv[a + 1];
        else return fail(argv[a], "unknown option");
    }
    Image image;
    if (const auto problem = readImage(file, image); !problem.empty()) return fail(file, problem);
    const int w = image.width, h = image.height;
    if (left <= 0 || left >= w - 16) return fail(file, "view-left outside the image");
    std::printf("%s: %dx%d\n", file.c_str(), w, h);

    if (columns > 0) {
        constexpr int kLabelRows = 48, kEdge = 3;
        for (int c = 0; c < columns; ++c) {
            const int from = left + c * (w - left) / columns, to = left + (c + 1) * (w - left) / columns;
            const std::string what = "column " + std::to_string(c + 1) + " of " + std::to_string(columns);
            if (const int rc = checkObject(file, image, from + kEdge, to, kLabelRows, what.c_str())) return rc;
        }
    } else if (const int rc = checkObject(file, image, left, w, 0, "the view")) {
        return rc;
    }

    if (!other.empty()) {
        Image second;
        if (const auto problem = readImage(other, second); !problem.empty()) return fail(other, problem);
        if (second.width != w || second.height != h) return fail(other, "not the size of " + file);
        long object = 0, differing = 0;
        for (int y = 0; y < h; ++y)
            for (int x = left; x < w; ++x) {
                if (!isObject(image, x, y, w) && !isObject(second, x, y, w)) continue;
                ++object;
                if (difference(image, x, y, second, x, y) > 0.06f) ++differing;
            }
        std::printf("%s: differs from %s on %.1f %% of the object\n", file.c_str(), other.c_str(),
                    100.0 * double(differing) / double(std::max(1L, object)));
        if (double(differing) < 0.02 * double(object)) return fail(file, "shows what " + other + " shows");
    }

    // The panel: not one flat colour.
    long varied = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < left; ++x)
            if (std::abs(image.at(x, y, 0) - image.at(0, h / 2, 0)) +
                    std::abs(image.at(x, y, 1) - image.at(0, h / 2, 1)) >
                0.1f)
                ++varied;
    if (double(varied) / (double(left) * h) < 0.01) return fail(file, "the control panel is missing");
    return 0;
}
