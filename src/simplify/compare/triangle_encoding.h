#pragma once
// What the triangle baselines share: the most triangles a file holds within a budget, how a
// shipped file is read back and judged, and the search over how its vertices are coded
// (position bits, normals or none), searched like the triangle count so that each baseline is
// the strongest honest version of itself.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::fit {
class FitScene;
}

namespace subdfit::simplify {

// Never fewer triangles than a closed shape needs.
inline constexpr int kFewestTriangles = 12;

// The most triangles in [fewest, most] whose shipped file (`ship` writes it, returns its bytes)
// fits `budget`, to within 1/200 of the count: bytes grow about in proportion to triangles, so
// each probe aims where the line through the bracket meets the budget (bisecting when that
// stalls). `hint`, when given, is where the first probe aims. At `fewest` when even that is over
// (the report then says so: a .glb's own header and JSON weigh hundreds of bytes). The file is
// left as shipped at the count returned.
int mostWithinBudget(int fewest, int most, std::uintmax_t budget, const std::function<std::uintmax_t(int)>& ship,
                     std::optional<int> hint = std::nullopt);

// Decimations of one mesh by triangle count, the last few kept: the encodings a search tries
// land on the same counts again and again, and each decimation is a pass over the whole mesh.
class Decimations {
public:
    using Decimate = std::function<mesh::PolygonMesh(const mesh::PolygonMesh& source, int triangles)>;
    Decimations(const mesh::PolygonMesh& source, Decimate decimate) : source_(source), decimate_(std::move(decimate)) {}
    const mesh::PolygonMesh& at(int triangles);

private:
    static constexpr size_t kKept = 12;
    const mesh::PolygonMesh& source_;
    Decimate decimate_;
    std::map<int, mesh::PolygonMesh> made_;
};

// The fewest position bits the encoding search tries: at 8 a position moves by up to about a
// pixel of a 256² view of the whole asset.
inline constexpr int kFewestPositionBits = 8;

// How a triangle file codes its vertices.
struct VertexEncoding {
    int positionBits = 14;
    bool normals = true;  // false: none ship, and a viewer draws the triangles flat (glTF 3.7.2.1)
    int normalBits = 10;
    bool operator==(const VertexEncoding&) const = default;
};
nlohmann::json toJson(const VertexEncoding& encoding);

// A shipped triangle file as a viewer gets it: read back (quantised positions, lossy images and
// all), triangulated, in the scene's normalised frame. Without normals in the file it is flat
// shaded, as glTF asks of viewers (three.js does so).
mesh::PolygonMesh readBack(const std::filesystem::path& path, const fit::FitScene& scene);

// Mean-loss PSNR of `candidate` on the scene's monitor views (neither training nor held out).
double monitorPsnr(gl::ProgramCache& programs, const fit::FitScene& scene, const mesh::PolygonMesh& candidate);

// Writes the candidate coded as `encoding` with `triangles` into the baseline's file; its bytes.
using ShipEncoded = std::function<std::uintmax_t(const VertexEncoding& encoding, int triangles)>;

struct EncodedChoice {
    VertexEncoding encoding;
    int triangles = 0;
    std::uintmax_t bytes = 0;
    double monitorPsnr = 0.0;
    nlohmann::json tried = nlohmann::json::array();  // every encoding tried: its triangles, bytes, monitor PSNR
};

// The encoding that scores best on the monitor views at the budget, each at the most triangles
// that fit: `start` and `start` with its normals the other way (shipped or not), then, from the
// better, fewer position bits (12, 11, 10, 9, 8) until one scores worse by more than the
// monitor's noise. `path` is the file `ship` writes; it is left holding the choice.
EncodedChoice bestEncoding(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget, int most,
                           const std::filesystem::path& path, const ShipEncoded& ship, VertexEncoding start,
                           std::optional<int> hint = std::nullopt);

}  // namespace subdfit::simplify
