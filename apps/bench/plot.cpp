#include "plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::bench {
namespace {

namespace IBA = OIIO::ImageBufAlgo;
using Colour = std::array<float, 3>;

constexpr Colour kBlack{0.0f, 0.0f, 0.0f};
constexpr Colour kWhite{1.0f, 1.0f, 1.0f};
constexpr Colour kGrid{0.89f, 0.89f, 0.89f};
constexpr Colour kMinorTick{0.45f, 0.45f, 0.45f};

// matplotlib's "tab10": distinct on white and for the common colour-vision deficiencies.
constexpr std::array<Colour, 10> kPalette{{
    {0.122f, 0.467f, 0.706f}, {1.000f, 0.498f, 0.055f}, {0.173f, 0.627f, 0.173f},
    {0.839f, 0.153f, 0.157f}, {0.580f, 0.404f, 0.741f}, {0.549f, 0.337f, 0.294f},
    {0.890f, 0.467f, 0.761f}, {0.498f, 0.498f, 0.498f}, {0.737f, 0.741f, 0.133f},
    {0.090f, 0.745f, 0.812f},
}};

constexpr int kTitlePx = 20, kLabelPx = 16, kTickPx = 13, kLegendPx = 14;

// ---- text ---------------------------------------------------------------------------------

// Debian 12's OpenImageIO (2.4) finds no default font on its own ("Could not set default font
// face"), so name one: DejaVu Sans from fonts-dejavu-core by path, then by name (OIIO searches
// /usr/share/fonts and $OPENIMAGEIO_FONTS), then OIIO's own default. With none of them usable the
// plot is still drawn, without any text: a plot missing its labels beats a failed benchmark.
const std::optional<std::string>& plotFont() {
    static const std::optional<std::string> font = []() -> std::optional<std::string> {
        for (const char* candidate : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "DejaVuSans",
                                      "DejaVu Sans", ""}) {
            const std::string name = candidate;
            if (!name.empty() && name.front() == '/' && !std::filesystem::exists(name)) continue;
            const bool usable = IBA::text_size("Ag", kTickPx, name).defined();
            (void)OIIO::geterror();  // a failed probe leaves a global error message; drop it
            if (usable) return name;
        }
        return std::nullopt;
    }();
    return font;
}

struct TextSize {
    int width = 0, height = 0;
};

TextSize textSize(const std::string& text, int px) {
    if (!plotFont() || text.empty()) return {};
    const OIIO::ROI roi = IBA::text_size(text, px, *plotFont());
    if (!roi.defined()) return {};
    return {roi.width(), roi.height()};
}

void drawText(OIIO::ImageBuf& image, int x, int y, const std::string& text, int px,
              IBA::TextAlignX alignX, IBA::TextAlignY alignY, const Colour& colour = kBlack) {
    if (!plotFont() || text.empty()) return;
    IBA::render_text(image, x, y, text, px, *plotFont(), colour, alignX, alignY);
}

// Text rotated a quarter turn counter-clockwise (reads bottom to top), centred on (cx, cy).
void drawVerticalText(OIIO::ImageBuf& image, int cx, int cy, const std::string& text, int px) {
    if (!plotFont() || text.empty()) return;
    const OIIO::ROI roi = IBA::text_size(text, px, *plotFont());
    if (!roi.defined()) return;
    const int pad = 2;
    OIIO::ImageBuf strip(OIIO::ImageSpec(roi.width() + 2 * pad, roi.height() + 2 * pad, 3, OIIO::TypeDesc::UINT8));
    IBA::fill(strip, kWhite);
    IBA::render_text(strip, pad - roi.xbegin, pad - roi.ybegin, text, px, *plotFont(), kBlack);
    OIIO::ImageBuf turned = IBA::rotate270(strip);
    const OIIO::ROI t = turned.roi();
    IBA::paste(image, cx - t.width() / 2, cy - t.height() / 2, 0, 0, turned);
}

// ---- axes ---------------------------------------------------------------------------------

struct Tick {
    double t;  // position on the (possibly log10) axis
    std::string label;  // empty: minor tick, no label or grid line
};

std::string trimExponent(std::string s) {
    // "1.5e+06" -> "1.5e6", "2e-05" -> "2e-5"
    const auto e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    bool negative = false;
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
        negative = exponent[0] == '-';
        exponent.erase(0, 1);
    }
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// A label for `value` on a linear grid of spacing `step` whose largest magnitude is `scale`, with
// just the digits the step needs. Scientific notation for the whole axis when its scale is large
// or small, so that labels on one axis share a style.
std::string formatOnGrid(double value, double step, double scale) {
    if (std::abs(value) < step * 1e-6) return "0";  // no "-0" or "1e-17"
    char buffer[64];
    if (scale >= 1e6 || scale < 1e-3) {
        const int digits = std::clamp(static_cast<int>(std::floor(std::log10(std::abs(value)) + 1e-9)) -
                                          static_cast<int>(std::floor(std::log10(step) + 1e-9)),
                                      0, 6);
        std::snprintf(buffer, sizeof buffer, "%.*e", digits, value);
        std::string text = buffer;
        const auto e = text.find('e');
        std::string mantissa = text.substr(0, e);
        if (mantissa.find('.') != std::string::npos) {  // "1.50" -> "1.5", "2.0" -> "2"
            mantissa.erase(mantissa.find_last_not_of('0') + 1);
            if (mantissa.back() == '.') mantissa.pop_back();
        }
        return trimExponent(mantissa + text.substr(e));
    }
    const int decimals = std::clamp(-static_cast<int>(std::floor(std::log10(step) + 1e-9)), 0, 9);
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

double niceStep(double span, int target) {
    const double raw = span / target;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double normalised = raw / magnitude;
    const double nice = normalised < 1.5 ? 1.0 : normalised < 3.5 ? 2.0 : normalised < 7.5 ? 5.0 : 10.0;
    return nice * magnitude;
}

std::vector<Tick> linearTicks(double lo, double hi, bool valuesAreLog10) {
    const double vlo = valuesAreLog10 ? std::pow(10.0, lo) : lo;
    const double vhi = valuesAreLog10 ? std::pow(10.0, hi) : hi;
    const double step = niceStep(vhi - vlo, 5);
    const double scale = std::max(std::abs(vlo), std::abs(vhi));
    std::vector<Tick> ticks;
    for (double k = std::ceil(vlo / step - 1e-9); k * step <= vhi * (1 + 1e-12) + step * 1e-9; k += 1.0) {
        const double v = k * step;
        if (valuesAreLog10 && v <= 0.0) continue;
        ticks.push_back({valuesAreLog10 ? std::log10(v) : v, formatOnGrid(v, step, scale)});
    }
    return ticks;
}

std::string decadeLabel(int exponent) {
    if (exponent >= -3 && exponent <= 4) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%g", std::pow(10.0, exponent));
        return buffer;
    }
    return "1e" + std::to_string(exponent);
}

// Ticks for a log10 axis spanning [lo, hi] in log10 units.
std::vector<Tick> logTicks(double lo, double hi) {
    const int first = static_cast<int>(std::ceil(lo - 1e-9)), last = static_cast<int>(std::floor(hi + 1e-9));
    const int decades = last - first + 1;
    std::vector<Tick> ticks;
    if (decades >= 3) {
        const int stride = std::max(1, (decades + 6) / 7);
        for (int d = first; d <= last; ++d)
            if ((d - first) % stride == 0) ticks.push_back({double(d), decadeLabel(d)});
        if (stride == 1 && decades <= 7)  // unlabelled 2..9 marks help read positions
            for (int d = first - 1; d <= last; ++d)
                for (int m = 2; m <= 9; ++m) {
                    const double t = d + std::log10(double(m));
                    if (t >= lo && t <= hi) ticks.push_back({t, ""});
                }
        return ticks;
    }
    // Fewer than three decades visible: 1, 2, 5 times powers of ten, else plain linear ticks.
    for (int d = first - 1; d <= last; ++d)
        for (int m : {1, 2, 5}) {
            const double t = d + std::log10(double(m));
            if (t >= lo - 1e-9 && t <= hi + 1e-9) {
                const double v = m * std::pow(10.0, d);
                ticks.push_back({t, m == 1 ? decadeLabel(d) : formatOnGrid(v, std::pow(10.0, d), v)});
            }
        }
    if (ticks.size() >= 3) return ticks;
    return linearTicks(lo, hi, true);
}

struct Axis {
    bool log = false;
    double lo = 0.0, hi = 1.0;  // transformed (log10 for a log axis)

    bool accepts(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
    double transform(double v) const { return log ? std::log10(v) : v; }
    std::vector<Tick> ticks() const { return log ? logTicks(lo, hi) : linearTicks(lo, hi, false); }
};

// Range of the accepted values, padded 5% each side; sensible defaults for none or one value.
Axis makeAxis(bool log, const std::vector<double>& values) {
    Axis axis{log};
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values)
        if (axis.accepts(v)) {
            lo = std::min(lo, axis.transform(v));
            hi = std::max(hi, axis.transform(v));
        }
    if (lo > hi) {
        lo = 0.0;
        hi = 1.0;
    } else if (hi - lo <= 1e-12 * std::max(1.0, std::abs(hi))) {
        const double half = log ? 0.5 : (hi != 0.0 ? std::abs(hi) * 0.1 : 1.0);
        lo -= half;
        hi += half;
    }
    const double pad = 0.05 * (hi - lo);
    axis.lo = lo - pad;
    axis.hi = hi + pad;
    return axis;
}

// ---- drawing ------------------------------------------------------------------------------

struct Frame {
    int left, top, right, bottom;  // plot area, pixels, inclusive
    Axis x, y;

    int px(double xt) const { return int(std::lround(left + (xt - x.lo) / (x.hi - x.lo) * (right - left))); }
    int py(double yt) const { return int(std::lround(bottom - (yt - y.lo) / (y.hi - y.lo) * (bottom - top))); }
};

void thickLine(OIIO::ImageBuf& image, int x0, int y0, int x1, int y1, const Colour& colour, int thickness) {
    static constexpr std::array<std::array<int, 2>, 9> offsets{
        {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {-1, 0}, {0, -1}, {-1, -1}, {1, -1}, {-1, 1}}};
    const int count = thickness <= 1 ? 1 : thickness == 2 ? 4 : 9;
    for (int i = 0; i < count; ++i)
        IBA::render_line(image, x0 + offsets[i][0], y0 + offsets[i][1], x1 + offsets[i][0], y1 + offsets[i][1], colour);
}

void marker(OIIO::ImageBuf& image, int x, int y, int half, const Colour& colour) {
    IBA::render_box(image, x - half, y - half, x + half, y + half, colour, true);
}

// Pixel positions of accepted points, std::nullopt where a point was rejected (breaks the line).
std::vector<std::optional<std::array<int, 2>>> project(const Frame& f, const std::vector<double>& xs,
                                                       const std::vector<double>& ys) {
    std::vector<std::optional<std::array<int, 2>>> points;
    const size_t n = std::min(xs.size(), ys.size());
    points.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        if (f.x.accepts(xs[i]) && f.y.accepts(ys[i]))
            points.push_back(std::array<int, 2>{f.px(f.x.transform(xs[i])), f.py(f.y.transform(ys[i]))});
        else
            points.push_back(std::nullopt);
    }
    return points;
}

void polyline(OIIO::ImageBuf& image, const std::vector<std::optional<std::array<int, 2>>>& points,
              const Colour& colour, int thickness) {
    for (size_t i = 1; i < points.size(); ++i)
        if (points[i - 1] && points[i])
            thickLine(image, (*points[i - 1])[0], (*points[i - 1])[1], (*points[i])[0], (*points[i])[1], colour,
                      thickness);
}

struct LegendEntry {
    std::string label;
    Colour colour;
    bool line, markers;
    int thickness;
};

}  // namespace

void writePlot(const std::filesystem::path& png, const PlotSpec& spec) {
    if (spec.width < 200 || spec.height < 150 || spec.width > 16384 || spec.height > 16384)
        throw fileError(png.string(), "plot size " + std::to_string(spec.width) + "x" +
                                          std::to_string(spec.height) + " is outside 200x150..16384x16384");

    std::vector<double> xs, ys;
    for (const Series& s : spec.series) {
        const size_t n = std::min(s.x.size(), s.y.size());
        xs.insert(xs.end(), s.x.begin(), s.x.begin() + std::ptrdiff_t(n));
        ys.insert(ys.end(), s.y.begin(), s.y.begin() + std::ptrdiff_t(n));
    }
    for (const auto& [x, y] : spec.highlight) {
        xs.push_back(x);
        ys.push_back(y);
    }
    Frame f{};
    f.x = makeAxis(spec.logX, xs);
    f.y = makeAxis(spec.logY, ys);
    const std::vector<Tick> xTicks = f.x.ticks(), yTicks = f.y.ticks();

    std::vector<LegendEntry> legend;
    for (size_t i = 0; i < spec.series.size(); ++i) {
        const Series& s = spec.series[i];
        legend.push_back({s.label.empty() ? "series " + std::to_string(i + 1) : s.label,
                          kPalette[i % kPalette.size()], !s.markersOnly, true, 2});
    }
    if (!spec.highlight.empty() && !spec.highlightLabel.empty())
        legend.push_back({spec.highlightLabel, kBlack, true, false, 3});

    // Layout: margins sized from the text actually drawn (all zero without a font).
    const bool haveText = plotFont().has_value();
    const int tickH = textSize("0123456789", kTickPx).height;
    int yTickW = 0;
    for (const Tick& t : yTicks) yTickW = std::max(yTickW, textSize(t.label, kTickPx).width);
    const int lineH = std::max(textSize("Ag", kLegendPx).height, 10) + 8;
    int legendW = 0;
    if (!legend.empty()) {
        int labelW = 0;
        for (const LegendEntry& e : legend) labelW = std::max(labelW, textSize(e.label, kLegendPx).width);
        legendW = std::min(10 + 26 + 8 + labelW + 10, spec.width / 3);
    }
    const int titleH = spec.title.empty() ? 0 : textSize(spec.title, kTitlePx).height;
    const int labelH = textSize("Ag", kLabelPx).height;

    f.top = 14 + (titleH ? titleH + 12 : 0);
    f.left = 14 + (spec.yLabel.empty() || !haveText ? 0 : labelH + 12) + yTickW + 12;
    f.right = spec.width - 1 - 20 - (legendW ? legendW + 16 : 0);
    f.bottom = spec.height - 1 - 14 - (spec.xLabel.empty() || !haveText ? 0 : labelH + 10) - tickH - 14;
    if (!haveText) f.left = std::max(f.left, 30);
    if (f.right - f.left < 60 || f.bottom - f.top < 60)
        throw fileError(png.string(), "plot size too small for its labels and legend");

    OIIO::ImageBuf image(OIIO::ImageSpec(spec.width, spec.height, 3, OIIO::TypeDesc::UINT8));
    IBA::fill(image, kWhite);

    // Grid under everything, at labelled ticks.
    for (const Tick& t : xTicks)
        if (!t.label.empty()) IBA::render_line(image, f.px(t.t), f.top, f.px(t.t), f.bottom, kGrid);
    for (const Tick& t : yTicks)
        if (!t.label.empty()) IBA::render_line(image, f.left, f.py(t.t), f.right, f.py(t.t), kGrid);

    // Data: all lines first, then all markers, so markers stay visible.
    std::vector<std::vector<std::optional<std::array<int, 2>>>> projected;
    for (const Series& s : spec.series) projected.push_back(project(f, s.x, s.y));
    for (size_t i = 0; i < spec.series.size(); ++i)
        if (!spec.series[i].markersOnly) polyline(image, projected[i], kPalette[i % kPalette.size()], 2);
    for (size_t i = 0; i < spec.series.size(); ++i)
        for (const auto& p : projected[i])
            if (p) marker(image, (*p)[0], (*p)[1], spec.series[i].markersOnly ? 3 : 2, kPalette[i % kPalette.size()]);
    if (!spec.highlight.empty()) {
        std::vector<double> hx, hy;
        for (const auto& [x, y] : spec.highlight) {
            hx.push_back(x);
            hy.push_back(y);
        }
        polyline(image, project(f, hx, hy), kBlack, 3);
    }

    // Frame, ticks and their labels.
    IBA::render_box(image, f.left, f.top, f.right, f.bottom, kBlack);
    for (const Tick& t : xTicks) {
        const int x = f.px(t.t), length = t.label.empty() ? 3 : 6;
        IBA::render_line(image, x, f.bottom, x, f.bottom + length, t.label.empty() ? kMinorTick : kBlack);
        drawText(image, x, f.bottom + 9, t.label, kTickPx, IBA::TextAlignX::Center, IBA::TextAlignY::Top);
    }
    for (const Tick& t : yTicks) {
        const int y = f.py(t.t), length = t.label.empty() ? 3 : 6;
        IBA::render_line(image, f.left - length, y, f.left, y, t.label.empty() ? kMinorTick : kBlack);
        drawText(image, f.left - 9, y, t.label, kTickPx, IBA::TextAlignX::Right, IBA::TextAlignY::Center);
    }

    // Title, axis labels.
    drawText(image, (f.left + f.right) / 2, 12, spec.title, kTitlePx, IBA::TextAlignX::Center, IBA::TextAlignY::Top);
    drawText(image, (f.left + f.right) / 2, f.bottom + 9 + tickH + 10, spec.xLabel, kLabelPx, IBA::TextAlignX::Center,
             IBA::TextAlignY::Top);
    drawVerticalText(image, 14 + labelH / 2, (f.top + f.bottom) / 2, spec.yLabel, kLabelPx);

    // Legend, right of the plot area, top-aligned with it. Without text it still shows the
    // colours in series order.
    if (legendW) {
        const int lx = f.right + 16, ly = f.top;
        const int lh = 6 + lineH * int(legend.size()) + 2;
        IBA::render_box(image, lx, ly, lx + legendW, ly + lh, kWhite, true);
        IBA::render_box(image, lx, ly, lx + legendW, ly + lh, kBlack);
        for (size_t i = 0; i < legend.size(); ++i) {
            const LegendEntry& e = legend[i];
            const int cy = ly + 6 + lineH * int(i) + lineH / 2;
            const int x0 = lx + 10, x1 = x0 + 26;
            if (e.line) thickLine(image, x0, cy, x1, cy, e.colour, e.thickness);
            if (e.markers) marker(image, (x0 + x1) / 2, cy, e.line ? 2 : 3, e.colour);
            drawText(image, x1 + 8, cy, e.label, kLegendPx, IBA::TextAlignX::Left, IBA::TextAlignY::Center);
        }
    }

    io::writeAtomically(png, [&](const std::filesystem::path& temporary) {
        if (!image.write(temporary.string())) {
            std::string problem = image.geterror();
            if (problem.empty()) problem = OIIO::geterror();
            throw fileError(png.string(), "could not write plot: " + problem);
        }
    });
}

}  // namespace subdfit::bench
