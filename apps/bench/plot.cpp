#include "plot.h"

#include <plplot/plstream.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::bench {
namespace {

// matplotlib's "tab10": distinct on white and for the common colour-vision deficiencies.
constexpr std::array<std::array<int, 3>, 10> kPalette{{
    {31, 119, 180},
    {255, 127, 14},
    {44, 160, 44},
    {214, 39, 40},
    {148, 103, 189},
    {140, 86, 75},
    {227, 119, 194},
    {127, 127, 127},
    {188, 189, 34},
    {23, 190, 207},
}};
constexpr int kBlack = 1, kGrid = 2, kFirstSeries = 3;  // colour map 0 slots

// A series' points on the plotted axes (log10 where the axis is logarithmic), split into runs
// at every point that cannot be drawn, so that lines break there.
std::vector<std::vector<std::array<double, 2>>> runs(const Series& s, bool logX, bool logY) {
    std::vector<std::vector<std::array<double, 2>>> out(1);
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
        double x = s.x[i], y = s.y[i];
        const bool ok = std::isfinite(x) && std::isfinite(y) && (!logX || x > 0) && (!logY || y > 0);
        if (!ok) {
            if (!out.back().empty()) out.emplace_back();
            continue;
        }
        out.back().push_back({logX ? std::log10(x) : x, logY ? std::log10(y) : y});
    }
    return out;
}

struct Range {
    double lo = std::numeric_limits<double>::max(), hi = -std::numeric_limits<double>::max();
    void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
    // A little margin, and some width even for a single value.
    Range padded() const {
        if (lo > hi) return {0.0, 1.0};
        const double span = hi > lo ? hi - lo : std::max(std::abs(lo), 1.0) * 0.1;
        return {lo - 0.05 * span, hi + 0.05 * span};
    }
};

// Tick labels: plain numbers, and on a log axis (whose data are log10 values) 10^value, so that
// an axis spanning less than a decade still has labels (PLplot's own log labels sit at decades).
void tickLabel(PLINT axis, PLFLT value, char* label, PLINT length, PLPointer data) {
    const auto& spec = *static_cast<const PlotSpec*>(data);
    const bool log = axis == PL_X_AXIS ? spec.logX : spec.logY;
    std::snprintf(label, size_t(length), "%.3g", log ? std::pow(10.0, value) : value);
}

void draw(plstream& pls, const PlotSpec& spec) {
    Range x, y;
    std::vector<std::vector<std::vector<std::array<double, 2>>>> data;
    for (const auto& s : spec.series) {
        data.push_back(runs(s, spec.logX, spec.logY));
        for (const auto& run : data.back())
            for (const auto& p : run) x.add(p[0]), y.add(p[1]);
    }
    Series highlight{.label = spec.highlightLabel};
    for (const auto& [hx, hy] : spec.highlight) highlight.x.push_back(hx), highlight.y.push_back(hy);
    const auto highlightRuns = runs(highlight, spec.logX, spec.logY);
    for (const auto& run : highlightRuns)
        for (const auto& p : run) x.add(p[0]), y.add(p[1]);
    x = x.padded(), y = y.padded();

    // Room on the right for the legend.
    pls.vpor(0.10, 0.72, 0.12, 0.90);
    pls.wind(x.lo, x.hi, y.lo, y.hi);
    // A log axis spanning a decade or more ticks at decades; a shorter one wherever PLplot likes.
    const PLFLT xTick = spec.logX && x.hi - x.lo >= 1.0 ? 1.0 : 0.0,
                yTick = spec.logY && y.hi - y.lo >= 1.0 ? 1.0 : 0.0;
    pls.slabelfunc(tickLabel, const_cast<PlotSpec*>(&spec));
    pls.col0(kGrid);
    pls.box("g", xTick, 0, "g", yTick, 0);  // the grid, under the data
    pls.col0(kBlack);
    pls.box("bcnsto", xTick, 0, "bcnstvo", yTick, 0);
    pls.lab(spec.xLabel.c_str(), spec.yLabel.c_str(), spec.title.c_str());

    std::vector<PLINT> opts, colours, lineStyles, markerColours;
    std::vector<PLFLT> widths, markerScales;
    std::vector<PLINT> markerCounts;
    std::vector<std::string> labels, markers;
    for (size_t k = 0; k < spec.series.size(); ++k) {
        const Series& s = spec.series[k];
        const PLINT colour = kFirstSeries + PLINT(k % kPalette.size());
        pls.col0(colour);
        pls.width(2.0);
        for (const auto& run : data[k]) {
            std::vector<PLFLT> rx, ry;
            for (const auto& p : run) rx.push_back(p[0]), ry.push_back(p[1]);
            if (rx.empty()) continue;
            if (!s.markersOnly && rx.size() > 1) pls.line(PLINT(rx.size()), rx.data(), ry.data());
            pls.string(PLINT(rx.size()), rx.data(), ry.data(), "•");
        }
        opts.push_back(s.markersOnly ? PL_LEGEND_SYMBOL : (PL_LEGEND_LINE | PL_LEGEND_SYMBOL));
        colours.push_back(colour), lineStyles.push_back(1), widths.push_back(2.0);
        markerColours.push_back(colour), markerScales.push_back(1.0), markerCounts.push_back(1);
        labels.push_back(s.label), markers.push_back("•");
    }
    if (!highlightRuns.empty() && !highlightRuns.front().empty()) {
        pls.col0(kBlack);
        pls.width(4.0);
        for (const auto& run : highlightRuns) {
            std::vector<PLFLT> rx, ry;
            for (const auto& p : run) rx.push_back(p[0]), ry.push_back(p[1]);
            if (rx.size() > 1) pls.line(PLINT(rx.size()), rx.data(), ry.data());
        }
        if (!spec.highlightLabel.empty()) {
            opts.push_back(PL_LEGEND_LINE);
            colours.push_back(kBlack), lineStyles.push_back(1), widths.push_back(4.0);
            markerColours.push_back(kBlack), markerScales.push_back(1.0), markerCounts.push_back(1);
            labels.push_back(spec.highlightLabel), markers.push_back("");
        }
    }
    pls.width(1.0);
    if (labels.empty()) return;
    std::vector<const char*> labelText, markerText;
    for (const auto& l : labels) labelText.push_back(l.c_str());
    for (const auto& m : markers) markerText.push_back(m.c_str());
    const PLINT n = PLINT(labels.size());
    std::vector<PLINT> none(size_t(n), 0);
    std::vector<PLFLT> zero(size_t(n), 0.0);
    PLFLT width = 0, height = 0;
    pls.legend(&width, &height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, PL_POSITION_RIGHT | PL_POSITION_OUTSIDE,
               0.02, 0.0, 0.1, 0, kBlack, 1, 0, 0, n, opts.data(), 1.0, 0.8, 2.0, 1.0, colours.data(), labelText.data(),
               none.data(), none.data(), zero.data(), zero.data(), colours.data(), lineStyles.data(), widths.data(),
               markerColours.data(), markerScales.data(), markerCounts.data(), markerText.data());
}

// PLplot exits the process when asked for a device it cannot load, so ask first.
bool pngDriverLoadable() {
    constexpr int kMost = 128;
    const char* menus[kMost];
    const char* names[kMost];
    const char** menuList = menus;
    const char** nameList = names;
    int count = kMost;
    plgDevs(&menuList, &nameList, &count);
    return std::any_of(names, names + std::clamp(count, 0, kMost),
                       [](const char* n) { return n && std::string(n) == "pngcairo"; });
}

}  // namespace

void writePlot(const std::filesystem::path& png, const PlotSpec& spec) {
    if (!pngDriverLoadable()) {
        std::fprintf(stderr, "warning: %s not drawn: PLplot has no pngcairo driver (Debian: plplot-driver-cairo)\n",
                     png.string().c_str());
        return;
    }
    io::writeAtomically(png, [&](const std::filesystem::path& temporary) {
        plstream pls;
        pls.sdev("pngcairo");
        pls.sfnam(temporary.c_str());
        pls.spage(0, 0, spec.width, spec.height, 0, 0);
        pls.scol0(0, 255, 255, 255);  // background
        pls.scol0(kBlack, 0, 0, 0);
        pls.scol0(kGrid, 225, 225, 225);
        for (size_t k = 0; k < kPalette.size(); ++k)
            pls.scol0(PLINT(kFirstSeries + k), kPalette[k][0], kPalette[k][1], kPalette[k][2]);
        pls.init();
        pls.adv(0);
        draw(pls, spec);
    });  // plstream's destructor ends the page and closes the file
    if (!std::filesystem::exists(png) || std::filesystem::file_size(png) == 0)
        throw fileError(png.string(), "PLplot wrote no image (is plplot-driver-cairo installed?)");
}

}  // namespace subdfit::bench
