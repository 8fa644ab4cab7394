// `subdfit-bench prefix`: an asset.subd as a stream delivers it. The file is cut at evenly spaced
// points from the end of its cage to its end, each prefix decoded (codec::SubdEnding::Prefix) and
// scored as simplify scores what it ships: held-out PSNR against the dense reference and mean
// surface distance; files made for their own budgets, given after it, are scored whole beside
// them (and the file is cut at their bytes too). CSV and a plot of PSNR against bytes.
// With --grow T,BITS the file cut is made first: the asset's cage with heights baked from the
// reference at T cells a face edge (its own resolution times a power of two) and BITS, whose
// levels down to the asset's own lattice hold the asset's own heights on its own grid
// (codec::EmbeddedPrefix): a larger file whose prefix is the asset's heights on its cage.
#include <algorithm>
#include <cstdio>

#include "bench_commands.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/device_defaults.h"
#include "fit/fit_scene.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "plot.h"
#include "simplify/prefix_growth.h"
#include "simplify/compare/quality.h"
#include "simplify/simplify_options.h"
#include "surface/tessellation.h"

namespace subdfit::bench {
namespace {

struct Row {
    std::string file, kind;  // kind: "prefix" or "whole"
    std::size_t bytes = 0;
    double psnr = 0.0, meanDistance = 0.0;
};

// The asset's cage with heights baked at the grown resolution and bits, its own lattice and
// --prefix-bits first (simplify/prefix_growth.h); written into the output folder.
std::filesystem::path grown(const SubdPrefixOptions& o, const mesh::PolygonMesh& reference) {
    const std::string bytes = io::readInputFile(o.asset);
    const std::span file{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()};
    const simplify::GrowingAsset asset = simplify::growingAsset(file, o.asset.string(), o.prefixBits);
    const std::vector<unsigned char> grownFile = simplify::grownFile(
        asset, simplify::grownHeights(asset, reference, o.growResolution), o.growResolution, o.growBits);
    const std::filesystem::path out = o.out / "grown.subd";
    io::writeTextAtomically(out, {reinterpret_cast<const char*>(grownFile.data()), grownFile.size()});
    std::printf("%s: the cage of %s, heights at T = %d and %d bits, T = %d at %d bits first\n", out.string().c_str(),
                o.asset.string().c_str(), o.growResolution, o.growBits, asset.asset.maps.layout.resolution,
                o.prefixBits);
    return out;
}

}  // namespace

int runSubdPrefix(const SubdPrefixOptions& o) {
    std::filesystem::create_directories(o.out);
    auto context = context::createHeadlessContext(o.glProvider);
    gl::ProgramCache programs(gl::platformDefines());
    const mesh::PolygonMesh reference = mesh::loadReference(o.reference);
    std::filesystem::path cut = o.asset;
    if (o.growResolution > 0) cut = grown(o, mesh::triangulated(reference));
    const std::string file = io::readInputFile(cut);
    const codec::SubdAsset whole = codec::readSubd(cut);
    fit::FitOptions options;
    options.reference = o.reference;
    options.glProvider = o.glProvider;
    options.out = o.out;
    fit::resolveForCurrentDevice(options);  // the views and resolution simplify scores with here
    const fit::FitScene scene(fit::resolved(options), programs, whole.cage, reference);
    const int samples = simplify::SimplifyOptions{}.surfaceSamples;

    std::vector<Row> rows;
    auto score = [&](const std::string& name, const std::string& kind, std::size_t bytes,
                     const codec::SubdAsset& asset) {
        const auto drawn = simplify::drawnAsFitted(programs, scene, asset);
        const double psnr = fit::scoreHoldout(*drawn, scene.holdout).psnr;
        mesh::PolygonMesh surface =
            surface::triangleMesh(surface::tessellate(asset.cage, asset.maps, drawn->renderer().tessLevel()));
        surface.positions = scene.frame.toNormalized(surface.positions);
        const double mean = simplify::worldDistance(surface, scene.reference, scene.frame, samples).meanDistance;
        rows.push_back({name, kind, bytes, psnr, mean});
        std::printf("%-40s %-7s %9zu %8.2f dB %11.4e\n", name.c_str(), kind.c_str(), bytes, psnr, mean);
        std::fflush(stdout);
    };
    // Evenly spaced from the cage's end, and at each whole file's bytes: prefixes and files compared at equal bytes.
    // Where the cage ends: the header and its section (the reader's account of the file).
    const std::size_t first =
        16 + codec::readShippedSubd({reinterpret_cast<const unsigned char*>(file.data()), file.size()}, cut.string())
                 .sectionBytes.front()
                 .second;
    std::vector<std::size_t> cuts;
    for (int k = 0; k <= o.cuts; ++k)
        cuts.push_back(first + (file.size() - first) * std::size_t(k) / std::size_t(o.cuts));
    std::vector<std::filesystem::path> comparedAt = o.made;
    if (o.growResolution > 0) comparedAt.push_back(o.asset);  // what it grew from
    for (const auto& made : comparedAt)
        if (const auto bytes = std::size_t(std::filesystem::file_size(made)); bytes > first && bytes < file.size())
            cuts.push_back(bytes);
    std::sort(cuts.begin(), cuts.end());
    for (const std::size_t bytes : cuts) {
        const auto* data = reinterpret_cast<const unsigned char*>(file.data());
        score(cut.string(), "prefix", bytes,
              codec::decodeSubd({data, bytes}, cut.string(), nullptr, {}, codec::SubdEnding::Prefix));
    }
    if (o.growResolution > 0)
        score(o.asset.string(), "whole", std::filesystem::file_size(o.asset), codec::readSubd(o.asset));
    for (const auto& made : o.made)
        score(made.string(), "whole", std::filesystem::file_size(made), codec::readSubd(made));

    std::vector<std::vector<std::string>> csv{{"file", "kind", "bytes", "psnr_holdout", "mean_distance"}};
    Series prefixes{.label = "its prefixes"}, made{.label = "whole files", .markersOnly = true};
    for (const Row& r : rows) {
        char psnr[32], mean[32];
        std::snprintf(psnr, sizeof psnr, "%.3f", r.psnr);
        std::snprintf(mean, sizeof mean, "%.4e", r.meanDistance);
        csv.push_back({r.file, r.kind, std::to_string(r.bytes), psnr, mean});
        Series& s = r.kind == "prefix" ? prefixes : made;
        s.x.push_back(double(r.bytes) / 1000.0);
        s.y.push_back(r.psnr);
    }
    writeCsv(o.out / "subd_prefix.csv", csv);
    writePlot(o.out / "prefix_psnr_vs_bytes.png", {.title = "asset.subd prefixes, decoded as they arrive",
                                                   .xLabel = "bytes received (KB)",
                                                   .yLabel = "held-out PSNR (dB)",
                                                   .series = {prefixes, made}});
    std::printf("%s\npeak_rss_mib=%.0f\n", (o.out / "subd_prefix.csv").string().c_str(), peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
