#include "result_scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <span>

#include "codec/decode_density.h"
#include "io/input_file.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

namespace subdfit::view {
namespace {

std::string describe(std::uintmax_t bytes, double psnr, double ssim) {
    char text[96] = "";
    int n = 0;
    if (bytes > 0) n += std::snprintf(text + n, sizeof text - n, "%.1f KB", double(bytes) / 1000.0);
    if (!std::isnan(psnr)) n += std::snprintf(text + n, sizeof text - n, "%s%.2f dB", n ? "  " : "", psnr);
    if (!std::isnan(ssim)) std::snprintf(text + n, sizeof text - n, "%sSSIM %.3f", n ? "  " : "", ssim);
    return text;
}

bool isSubd(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".subd";
}

std::string kilobytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", double(bytes) / 1000.0);
    return text;
}

// A mesh file's one level, or an asset.subd's levels as `subd` reads them.
std::vector<LoadedLevel> loadLevels(const std::filesystem::path& path, const SubdReading& subd) {
    if (!isSubd(path)) return {{.path = path, .mesh = mesh::triangulated(mesh::loadReference(path))}};
    const std::string file = io::readInputFile(path);
    const std::span bytes{reinterpret_cast<const unsigned char*>(file.data()), file.size()};
    std::vector<std::size_t> firsts{std::min(subd.firstBytes, bytes.size())};
    if (subd.prefixes)
        if (const std::size_t cage = codec::cageEnd(bytes, path.string()); cage > 0) {
            for (std::size_t n = firsts.front() / 2; n > cage; n /= 2) firsts.push_back(n);
            if (cage < firsts.front()) firsts.push_back(cage);
        }
    std::vector<LoadedLevel> levels;
    for (const std::size_t n : firsts) {
        const bool prefix = n < bytes.size();
        LoadedLevel& level = levels.emplace_back(
            LoadedLevel{.path = path,
                        .asset = codec::decodeSubd(bytes.first(n), path.string(), nullptr, {},
                                                   prefix ? codec::SubdEnding::Prefix : codec::SubdEnding::Whole)});
        if (prefix) level.label = "its first " + kilobytes(n) + " of " + kilobytes(bytes.size()) + " KB";
    }
    return levels;
}

ColumnInputs fileColumn(const std::filesystem::path& path, const SubdReading& subd) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    return {.name = path.filename().string(),
            .stats = describe(ec ? 0 : bytes, NAN, NAN),
            .levels = loadLevels(path, subd)};
}

ColumnInputs referenceColumn(const std::filesystem::path& path) {
    ColumnInputs reference = fileColumn(path, {});
    reference.name = "reference";
    reference.stats = std::to_string(reference.levels.front().mesh.faceCount()) + " triangles";
    reference.reference = true;
    return reference;
}

void addFolder(ResultInputs& inputs, const std::filesystem::path& dir, bool referenceGiven, const SubdReading& subd) {
    fit::ResultFolder folder = fit::readResultFolder(dir);
    if (referenceGiven) {
        std::erase_if(folder.notes, [](const std::string& note) { return note.starts_with("the reference "); });
    } else if (!folder.reference.empty() && !inputs.folder) {
        inputs.columns.insert(inputs.columns.begin(), referenceColumn(folder.reference));
    }
    for (const auto& entry : folder.entries) {
        ColumnInputs column{.name = entry.name, .stats = describe(entry.bytes, entry.psnrHoldout, entry.ssimHoldout)};
        for (const auto& path : entry.levels)
            std::ranges::move(loadLevels(path, subd), std::back_inserter(column.levels));
        inputs.columns.push_back(std::move(column));
    }
    for (const auto& note : folder.notes) inputs.notes.push_back(dir.filename().string() + ": " + note);
    if (!inputs.folder) inputs.folder = std::move(folder);
}

// The frame everything is drawn in: the reference's, as the fit's was; else the first column's.
scene::SceneFrame frameOf(const ColumnInputs& column) {
    const LoadedLevel& level = column.levels.front();
    try {
        return scene::frameAround(level.asset ? level.asset->cage.positions : level.mesh.positions);
    } catch (const Error& e) {
        throw fileError(level.path.string(), e.what());
    }
}

// With a reference, everything is shaded as the fit's scene was (settings.shading, or what the
// reference's materials call for); a file on its own, as its own appearance calls for.
render::ShadingModel shadingOf(const ResultInputs& inputs, const LoadedLevel& level) {
    const ColumnInputs& first = inputs.columns.front();
    if (first.reference) {
        const nlohmann::json* shading = inputs.folder ? &inputs.folder->settings : nullptr;
        const auto named = shading ? shading->find("shading") : nlohmann::json::const_iterator{};
        const std::string asked =
            shading && named != shading->end() && named->is_string() ? named->get<std::string>() : "auto";
        if (const auto model = parseNamed<render::ShadingModel>(asked)) return *model;
        return render::shadingFor(first.levels.front().mesh);  // "auto"
    }
    return level.asset ? fit::shadingOf(level.asset->maps) : render::shadingFor(level.mesh);
}

}  // namespace

ResultInputs loadResultInputs(const std::vector<std::filesystem::path>& results, const std::filesystem::path& reference,
                              const SubdReading& subd) {
    ResultInputs inputs;
    if (!reference.empty()) inputs.columns.push_back(referenceColumn(reference));
    for (const auto& path : results) {
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec)) addFolder(inputs, path, !reference.empty(), subd);
        else inputs.columns.push_back(fileColumn(path, subd));
        if (!inputs.title.empty()) inputs.title += ", ";
        inputs.title += path.string();
    }
    if (!reference.empty() && inputs.folder) inputs.folder->reference = reference;
    SUBDFIT_CHECK(!inputs.columns.empty());
    inputs.frame = frameOf(inputs.columns.front());
    return inputs;
}

ResultColumn::ResultColumn(gl::ProgramCache& programs, const ColumnInputs& inputs, const ResultInputs& scene,
                           int tessLevel)
    : programs_(programs), inputs_(inputs), scene_(scene), tessLevel_(tessLevel) {
    build();
}

void ResultColumn::setLevel(int level) {
    level_ = std::clamp(level, 0, int(inputs_.levels.size()) - 1);
    build();
}

int ResultColumn::tessLevel() const { return asset_ ? asset_->fitter().renderer().tessLevel() : 0; }

void ResultColumn::setTessLevel(int level) {
    tessLevel_ = level;
    if (asset_) asset_->setTessLevel(level);
}

maps::MapEffects ResultColumn::mapEffects() {
    return asset_ && asset_->fitter().maps() ? asset_->fitter().maps()->effects() : maps::MapEffects{};
}

void ResultColumn::build() {
    const LoadedLevel& level = inputs_.levels[size_t(level_)];
    asset_.reset();
    mesh_.reset();
    wireframe_.reset();
    if (level.asset) {
        const int tess =
            tessLevel_ > 0 ? tessLevel_ : codec::decodeDensity(*level.asset, {}, level.path.string()).segments;
        asset_ =
            std::make_unique<fit::ShippedAsset>(programs_, *level.asset, scene_.frame, shadingOf(scene_, level), tess);
        wireframe_ = std::make_unique<CageWireframe>(asset_->cage());
        return;
    }
    mesh::PolygonMesh triangles = level.mesh;
    triangles.positions = scene_.frame.toNormalized(triangles.positions);
    // A baseline without a material (decimation of a plain mesh) is drawn grey, as it was scored.
    const render::ShadingModel shading =
        inputs_.reference || triangles.materials ? shadingOf(scene_, level) : render::ShadingModel::Geometry;
    mesh_ = std::make_unique<render::MeshRenderer>(triangles, shading);
}

ViewSource ResultColumn::source(ResultColumn* reference) {
    ViewSource source;
    if (asset_) {
        source.draw = [this](const render::Camera& camera, const render::RenderTarget& target) {
            asset_->draw(camera, target);
        };
        source.maps = asset_->fitter().maps();
        source.wireframe = wireframe_.get();
        source.cageVertices = &asset_->fitter().vertexGroup().theta;
    } else {
        source.draw = [this](const render::Camera& camera, const render::RenderTarget& target) {
            mesh_->draw(programs_, camera, target);
        };
    }
    if (reference) source.drawReference = reference->source(nullptr).draw;
    return source;
}

}  // namespace subdfit::view
