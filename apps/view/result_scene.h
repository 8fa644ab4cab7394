#pragma once
// What the result view compares: the reference, subdfit's shipped asset and each baseline (or
// the files given), each a column drawn in one frame (the reference's) under one camera. The
// files are read and checked first, with no GL (so a damaged one is refused before a window
// opens); the columns' GL objects are built once the window's context is current.
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "codec/subd_format.h"
#include "fit/result_folder.h"
#include "fit/shipped_asset.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"
#include "view_renderer.h"

namespace subdfit::view {

// One file of a column, read: an asset.subd, or triangles (world units) with their appearance.
struct LoadedLevel {
    std::filesystem::path path;
    std::optional<codec::SubdAsset> asset{};
    mesh::PolygonMesh mesh{};
    std::string label{};  // an asset.subd's prefix: "its first 9.2 of 18.5 KB"; empty: the whole file
};

// How each asset.subd is read: whole, or its first bytes (--bytes, as `subdfit decode --bytes`
// and a stream deliver them), and with its prefixes as its column's levels (--prefixes): those
// bytes, then half of them, a quarter ... down to the cage alone (codec::cageEnd).
struct SubdReading {
    std::size_t firstBytes = std::numeric_limits<std::size_t>::max();
    bool prefixes = false;
};

struct ColumnInputs {
    std::string name;                   // "reference", "subdfit", a baseline's name, or a file's
    std::string stats;                  // bytes and held-out scores, for the panel and the column's label
    std::vector<LoadedLevel> levels{};  // finest first; one unless a chain of levels of detail is given
    bool reference = false;
};

struct ResultInputs {
    std::string title;
    std::vector<ColumnInputs> columns;        // the reference first, when there is one
    std::vector<std::string> notes;           // what is left out and why
    std::optional<fit::ResultFolder> folder;  // the first folder given
    scene::SceneFrame frame;                  // the reference's, else the first column's
};

// Reads every RESULT: a fit or simplify output folder (its reference, asset.subd and baselines:
// fit/result_folder.h says which files a folder may name), an asset.subd, or a mesh file (.glb,
// .gltf, .obj, .drc); `reference`, when given, is the reference instead of the folder's; every
// asset.subd as `subd` says. Throws subdfit::Error "path: problem" for a folder without a result
// and for a damaged or unreadable file (or one whose first bytes end before its cage does).
ResultInputs loadResultInputs(const std::vector<std::filesystem::path>& results,
                              const std::filesystem::path& reference = {}, const SubdReading& subd = {});

// A column on the GPU, at one level.
class ResultColumn {
public:
    // `tessLevel` 0: decode's default for the asset (its maps' sample density).
    ResultColumn(gl::ProgramCache& programs, const ColumnInputs& inputs, const ResultInputs& scene, int tessLevel);

    const ColumnInputs& inputs() const { return inputs_; }
    int level() const { return level_; }
    void setLevel(int level);
    // Segments per base-face edge of a subdfit-format column as drawn (0 for triangles).
    int tessLevel() const;
    void setTessLevel(int level);
    bool hasCage() const { return asset_ != nullptr; }
    maps::MapEffects mapEffects();

    // `reference` (may be null) is what the error view compares with.
    ViewSource source(ResultColumn* reference);

private:
    void build();

    gl::ProgramCache& programs_;
    const ColumnInputs& inputs_;
    const ResultInputs& scene_;
    int level_ = 0, tessLevel_;
    std::unique_ptr<fit::ShippedAsset> asset_;
    std::unique_ptr<render::MeshRenderer> mesh_;
    std::unique_ptr<CageWireframe> wireframe_;
};

}  // namespace subdfit::view
