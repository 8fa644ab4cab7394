#pragma once
// What a user asks of a fit, described once. Every option is a row of one table (its key in
// report.json's `settings` and in the checkpoint fingerprint, its command-line flag and help,
// its range, which runs it tells apart); the command line registers flags from the table
// (apps/common/fit_cli.h), validate() checks the ranges, settingsJson() and
// checkpointFingerprint() read it. Plus the pure functions of the options that a resumed run
// must reproduce exactly (the view schedule).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "context/gl_context.h"
#include "maps/map_effects.h"
#include "mesh/polygon_mesh.h"
#include "render/shading_model.h"
#include "surface/surface_maps.h"
#include "util/error.h"
#include "util/named_enum.h"

namespace subdfit::fit {

// An option the device chooses unless it was given: see resolveDeviceDefaults().
inline constexpr int kByDevice = -1;

// How the step size follows the fit (fit/step_schedule.h): Plateau halves it when the monitored
// loss stalls and stops once converged, `steps` being the most; Anneal takes exactly `steps`
// steps, the step annealed x0.1 over them.
enum class Schedule { Plateau, Anneal };

// What the USD export writes beside asset.subd (export/usd/usd_export.h).
enum class UsdExport { Usdz, UsdzAndUsda, None };

}  // namespace subdfit::fit

template <>
struct subdfit::EnumNames<subdfit::fit::Schedule> {
    static constexpr std::array names{std::pair{fit::Schedule::Plateau, std::string_view("plateau")},
                                      std::pair{fit::Schedule::Anneal, std::string_view("anneal")}};
};
template <>
struct subdfit::EnumNames<subdfit::fit::UsdExport> {
    static constexpr std::array names{std::pair{fit::UsdExport::Usdz, std::string_view("usdz")},
                                      std::pair{fit::UsdExport::UsdzAndUsda, std::string_view("usdz,usda")},
                                      std::pair{fit::UsdExport::None, std::string_view("none")}};
};

namespace subdfit::fit {

struct FitOptions {
    std::filesystem::path cage, reference, out;
    // By the device unless given (fit/device_defaults.h): 24 views at 256², at most 4000 steps on
    // a software rasterizer; more of each on a hardware GPU, where a step costs little.
    int views = kByDevice;  // training views (held-out views come in addition)
    int holdoutViews = 6;
    int resolution = kByDevice;
    int steps = kByDevice;
    int viewsPerStep = 1;
    int samplesPerStep = 1;  // perturbations averaged per Adam step
    int tessLevel = 8;
    std::uint32_t seed = 1;
    // The vertex perturbation and Adam step, as fractions of the cage's mean edge length (at most
    // about a pixel and half a pixel): the same defaults then serve a 100-face and a 10 000-face
    // cage. The step shrinks as the schedule says.
    float epsilon = 0.08f;
    float learningRate = 0.15f;
    float smoothing = 4.0f;  // λ of the Laplacian preconditioner (0: off)
    // c of every group's noise gate (optim::GroupSettings::noiseGate): a parameter whose running
    // gradient is within c times its expected noise of 0 barely moves; 0: plain Adam.
    float noiseGate = 0.0f;
    float relaxation = 0.0f;  // tangential relaxation of the cage per vertex update (0: off)
    float tangential = 0.2f;  // fraction of the vertex gradient's tangential part kept
    context::GlProvider glProvider = context::GlProvider::Auto;
    // How the scene is shaded; nothing ("auto"): what the reference's materials call for.
    std::optional<render::ShadingModel> shading;
    maps::MapEffects maps;  // none by default
    int mapResolution = 8;  // cells per ptex-face edge of each map tile
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;  // what shades the displaced surface
    int appearanceResolution = 16;  // ... of the appearance maps (base colour, metallic-roughness)
    // simplify: texels per side of the appearance maps in the reference's own texture atlas
    // (surface/appearance_atlas.h); 0: per-face tiles of appearanceResolution.
    int appearanceAtlas = 0;
    float mapsStart = 0.4f;      // fraction of the steps fitted by the cage alone before maps join
    int mapBits = 12;            // bits per map value in asset.subd (over each channel's range)
    int positionBits = 14;       // bits per cage coordinate in asset.subd (over its bounding cube)
    int appearanceQuality = 90;  // JPEG quality of the appearance images in asset.subd
    bool preview = false;        // also write fitted.glb: the displaced limit surface, tessLevel per face edge
    bool draco = false;          // fitted.glb with KHR_draco_mesh_compression
    UsdExport usd = UsdExport::Usdz;
    bool compactMaps = false;   // ship maps as HALF EXR and 8-bit PNG (codec/map_atlas.h)
    bool resume = false;        // continue from out/checkpoint.bin when it exists
    bool force = false;         // write into a non-empty folder that holds no subdfit results
    int checkpointEvery = 100;  // steps between checkpoints (also written on interrupt and at the end)
    Schedule schedule = Schedule::Plateau;
};

// One row of the table.
struct OptionInfo {
    const char* key;   // report.json's name, e.g. "map_resolution"
    const char* flag;  // the command line's, e.g. "--map-res"; "" for options set by code only
    const char* help;
    double min = 1.0, max = 0.0;  // inclusive range of a number; min > max: none
    bool openRange = false;       // the range excludes its ends
    bool resumable = false;       // must match for a checkpoint to continue
    bool setting = false;         // shapes the result: report.json's settings, a batch asset's identity
    bool byDevice = false;        // kByDevice until resolveDeviceDefaults() (fit/device_defaults.h)
};

// A row of a table of options: its OptionInfo and the member it describes, `Member` a
// std::variant of pointers to members of one options struct.
template <class Member>
struct TableRow {
    OptionInfo info;
    Member member;
};

// Calls visit(info, field) for every row of `rows`, `field` a reference to the member of
// `options` the row describes.
template <class Row, class Options, class Visitor>
void forEachRow(const std::vector<Row>& rows, Options& options, Visitor&& visit) {
    for (const auto& row : rows) std::visit([&](auto member) { visit(row.info, options.*member); }, row.member);
}

namespace detail {
using OptionMember =
    std::variant<int FitOptions::*, std::uint32_t FitOptions::*, float FitOptions::*, bool FitOptions::*,
                 maps::MapEffects FitOptions::*, std::optional<render::ShadingModel> FitOptions::*,
                 surface::ShadingNormal FitOptions::*, Schedule FitOptions::*, UsdExport FitOptions::*,
                 context::GlProvider FitOptions::*>;
using OptionRow = TableRow<OptionMember>;
const std::vector<OptionRow>& optionTable();
}  // namespace detail

// Calls visit(info, field) for every option: `field` a number, a bool, or a value spelt as words
// (WordOption).
template <class Options, class Visitor>
void forEachOption(Options& options, Visitor&& visit) {
    forEachRow(detail::optionTable(), options, visit);
}

// An option spelt as words rather than a number: the maps, and every NamedEnum (an optional one
// spells "not given" as "auto").
template <class T>
concept WordOption = std::is_same_v<T, maps::MapEffects> || NamedEnum<T> ||(requires {
    typename T::value_type;
} && NamedEnum<typename T::value_type> && std::is_same_v<T, std::optional<typename T::value_type>>);

template <WordOption T>
std::string optionText(const T& value) {
    if constexpr (std::is_same_v<T, maps::MapEffects>) return maps::toString(value);
    else return std::string(nameOf(value));
}

// Reads `text` into `field`; throws OptionError(key, "must be ..., got '...'") when it names nothing.
template <WordOption T>
void readOptionText(const OptionInfo& info, T& field, const std::string& text) {
    if constexpr (std::is_same_v<T, maps::MapEffects>) {
        try {
            field = maps::parseMapEffects(text);
        } catch (const Error& e) {
            throw OptionError(info.key, e.what());
        }
    } else if constexpr (NamedEnum<T>) {
        const auto value = parseNamed<T>(text);
        if (!value) throw OptionError(info.key, "must be " + namesOf<T>() + ", got '" + text + "'");
        field = *value;
    } else {
        using E = typename T::value_type;
        if (text == kAutoName) field = std::nullopt;
        else if (const auto value = parseNamed<E>(text)) field = *value;
        else throw OptionError(info.key, "must be " + namesOf<E>(true) + ", got '" + text + "'");
    }
}

// The row of an option key, or nullptr.
const OptionInfo* findOption(std::string_view key);
// The flag of an option key ("" when it has none).
std::string optionFlag(const std::string& key);

// Sets the option `key` (report.json's name) from text, e.g. ("noise_gate", "2"). Throws
// OptionError for an unknown key or a value that does not parse; ranges are validate()'s.
void setOption(FitOptions& options, const std::string& key, const std::string& value);

// Throws OptionError for anything out of range, before any work. Options still kByDevice pass.
void validate(const FitOptions& options);

// Options that passed validate() with no option left kByDevice (fit/device_defaults.h chooses
// them): what FitScene and FitRun are built from, so neither checks again. Only resolved() makes one.
class ResolvedFitOptions {
public:
    const FitOptions& operator*() const { return options_; }
    const FitOptions* operator->() const { return &options_; }

private:
    explicit ResolvedFitOptions(FitOptions options) : options_(std::move(options)) {}
    friend ResolvedFitOptions resolved(FitOptions options);
    FitOptions options_;
};
// Throws OptionError for an option out of range or still left to the device.
ResolvedFitOptions resolved(FitOptions options);

// The options whose rows say `setting`, by key: what report.json's settings record and what
// tells one run's output from another's.
nlohmann::json settingsJson(const FitOptions& options);

// The training views of step `step`: shuffled rounds over all views, every view equally often.
// A pure function of (seed, step), so a resumed run visits exactly what the first would have.
std::vector<int> viewsForStep(const FitOptions& options, int step);

// What must match for a checkpoint to be resumed: the inputs' geometry and the options whose
// rows say `resumable` (not the step count, so a finished run can be extended).
std::string checkpointFingerprint(const FitOptions& options, const mesh::PolygonMesh& cage,
                                  const mesh::PolygonMesh& reference);

}  // namespace subdfit::fit
