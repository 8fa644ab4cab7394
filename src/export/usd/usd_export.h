#pragma once
// The USD export beside asset.subd: asset.usdz, one self-contained package (the layer of
// export/usd/usd_stage.h and its images, export/usd/usdz_archive.h), and on request asset.usda, the
// same layer as text, its images read from inside the package.
#include <filesystem>
#include <vector>

#include "io/output_file.h"
#include "export/usd/usd_stage.h"

namespace subdfit::exporter {

inline constexpr const char* kUsdPackageFile = "asset.usdz";
inline constexpr const char* kUsdTextFile = "asset.usda";

// Writes dir/asset.usdz and, with `text`, dir/asset.usda, each atomically. Throws subdfit::Error
// naming the file that could not be written.
std::vector<io::WrittenFile> writeUsd(const std::filesystem::path& dir, const codec::SubdAsset& asset,
                                      bool text = false);

}  // namespace subdfit::exporter
