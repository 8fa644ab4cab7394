#pragma once
// PNG line and scatter plots for the benchmarks, drawn by PLplot (Debian's libplplot-dev, cairo
// driver): framed axes with a light grid, decades on log axes, title, axis labels and a legend
// to the right. The benchmarks describe what to plot; PLplot draws it.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace subdfit::bench {

struct Series {
    std::string label;
    std::vector<double> x{}, y{};  // same length; extra entries of the longer one are ignored
    bool markersOnly = false;      // scatter: markers without connecting lines
};

struct PlotSpec {
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;
    std::vector<Series> series{};
    // Drawn last as a thick black polyline in the given order, e.g. a Pareto front.
    std::vector<std::pair<double, double>> highlight{};
    int width = 900, height = 600;
    // Legend entry for `highlight` (empty: no entry).
    std::string highlightLabel = "Pareto front";
};

// Writes `spec` as a PNG, atomically. Points with a NaN/Inf coordinate, or a non-positive one on a
// log axis, are skipped (lines break there). Without PLplot's pngcairo driver it warns and draws
// nothing (the figures and CSV stand alone); throws subdfit::Error "png: problem" when the image
// cannot be made or written.
void writePlot(const std::filesystem::path& png, const PlotSpec& spec);

}  // namespace subdfit::bench
