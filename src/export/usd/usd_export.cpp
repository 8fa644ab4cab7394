#include "export/usd/usd_export.h"

#include <algorithm>

#include "export/usd/usdz_archive.h"
#include "util/error.h"
#include "util/warnings.h"

namespace subdfit::exporter {
namespace {

std::vector<unsigned char> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }

// UsdGeomMesh has no crease method: Chaikin's differs from the uniform rule only on semi-sharp tags.
void warnOfWhatUsdCannotSay(const std::filesystem::path& package, const mesh::SubdivisionTags& tags) {
    if (tags.creaseMethod != mesh::CreaseMethod::Chaikin) return;
    auto semiSharp = [](float s) { return s > 0.0f && s < 10.0f; };
    const bool any =
        std::any_of(tags.creases.begin(), tags.creases.end(), [&](const auto& c) { return semiSharp(c.sharpness); }) ||
        std::any_of(tags.corners.begin(), tags.corners.end(), [&](const auto& c) { return semiSharp(c.sharpness); });
    if (any)
        warn(package.string() +
             ": USD has no Chaikin crease method: the cage's semi-sharp creases render with the uniform "
             "rule there");
}

}  // namespace

std::vector<io::WrittenFile> writeUsd(const std::filesystem::path& dir, const codec::SubdAsset& asset, bool text) {
    std::vector<io::WrittenFile> written;
    const auto package = dir / kUsdPackageFile;
    warnOfWhatUsdCannotSay(package, asset.cage.tags);
    try {
        UsdStage stage = usdStage(asset);
        std::vector<UsdzEntry> entries{{kUsdTextFile, bytesOf(stage.layer)}};
        for (UsdTextureFile& texture : stage.textures) entries.push_back({texture.name, std::move(texture.bytes)});
        written.push_back(io::writeBytes(package, usdzArchive(entries)));
    } catch (const Error& e) {
        if (std::string(e.what()).starts_with(package.string())) throw;
        throw fileError(package.string(), e.what());
    }
    if (text) written.push_back(io::writeBytes(dir / kUsdTextFile, bytesOf(usdStage(asset, kUsdPackageFile).layer)));
    return written;
}

}  // namespace subdfit::exporter
