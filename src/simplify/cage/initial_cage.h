#pragma once
// The cage `simplify` starts from: the reference decimated to the face budget, its slivers evened
// out (a Catmull-Clark surface wrinkles over them), made a sound Catmull-Clark cage. Decimated vertices lie on the reference, but a Catmull-Clark limit surface
// only approximates its cage, shrinking into it; so the vertices are then moved until the limit
// surface passes through where they were (limit interpolation), which starts the fit on the
// reference's surface rather than inside it; then until it lies on the reference across each
// face in the least-squares sense (simplify/cage/limit_fit.h), which removes the ripples that
// interpolation leaves between the vertices of a dense triangle cage.
#include <memory>
#include <optional>

#include "geometry/surface_queries.h"
#include "mesh/polygon_mesh.h"
#include "simplify/cage/feature_edges.h"
#include "simplify/cage/limit_fit.h"
#include "util/named_enum.h"

namespace subdfit::simplify {

// What a cage's faces are: quads along the reference's cross field (simplify/remesh), few of them
// triangles; the decimated reference's triangles; or those triangles joined in pairs into quads
// (simplify/cage/triangle_pairing.h: quad-dominant, its vertices where decimation put them).
// Auto is simplify's --budget choice: a triangle ladder whose best bare cage is also tried as
// quads at the same bytes; a cage made directly is then made of triangles.
enum class CageShape { Quads, Triangles, Auto, Paired };

// Whether a cage of `shape` has about a vertex a face (quads) rather than half of one.
constexpr bool quadDominant(CageShape shape) { return shape == CageShape::Quads || shape == CageShape::Paired; }

}  // namespace subdfit::simplify

template <>
struct subdfit::EnumNames<subdfit::simplify::CageShape> {
    static constexpr std::array names{std::pair{simplify::CageShape::Quads, std::string_view("quads")},
                                      std::pair{simplify::CageShape::Triangles, std::string_view("triangles")},
                                      std::pair{simplify::CageShape::Auto, std::string_view("auto")},
                                      std::pair{simplify::CageShape::Paired, std::string_view("paired")}};
};

namespace subdfit::simplify {

struct InitialCageOptions {
    // Faces of the cage: at most (triangles), about (quads; a quad cage has about as many
    // vertices as faces, a triangle cage half as many; paired: from twice as many triangles).
    int faces = 1000;
    CageShape shape = CageShape::Triangles;
    int evenOutRounds = 3;             // tangential smoothing of decimation's slivers (features stay)
    int interpolationIterations = 16;  // P += V − limit(P) sweeps (each ÷~2 the gap)
    LimitFitOptions limitFit{};        // .rounds = 0: the interpolated cage as it is
    bool hardEdges = true;             // the reference's hard edges as creases (simplify/cage/feature_edges.h)
};

// `reference` in any units, any polygons. A quad cage is a quad remesh of the reference (where
// remeshing fails, a part thinner than its quads say, the decimated cage is made instead, with
// a warning), its hard edges not yet creased. A paired cage is the triangle cage's decimation
// with its triangles joined in pairs (never across a crease). A triangle cage is welded, with OpenSubdiv's
// smooth-triangle rule (Loop-like weights on triangles, which keeps them from pinching),
// boundaries interpolated with their corners, and the reference's hard edges as sharp creases. Throws subdfit::Error naming the reference when
// the result is not a usable cage.
mesh::PolygonMesh initialCage(const mesh::PolygonMesh& reference, const InitialCageOptions& options);

// A reference prepared once for cages of any number of face counts (the budget search's): welded,
// its hard edges found, its surface ready for the limit fit's rays. cage() is initialCage().
// Given the most faces its ladder's cages will have, a dense reference is also decimated once to
// kDecimationCopyFactor times that, and cages up to twice that size (the search grows its best
// cage past the ladder) are decimated from the copy: each decimation from the reference is a
// pass over all of it.
class CageSource {
public:
    static constexpr int kDecimationCopyFactor = 8;
    explicit CageSource(const mesh::PolygonMesh& reference, bool hardEdges = true, int mostFaces = 0);
    mesh::PolygonMesh cage(const InitialCageOptions& options) const;

private:
    std::optional<mesh::PolygonMesh> quadCage(int faces) const;  // none where remeshing fails
    mesh::PolygonMesh decimatedCage(const InitialCageOptions& options) const;

    const mesh::PolygonMesh& reference_;
    mesh::PolygonMesh welded_;
    std::optional<mesh::PolygonMesh> decimationCopy_;  // of welded_, where it is dense
    int copyServes_ = 0;                               // cages of up to this many faces
    std::optional<HardEdges> hardEdges_;
    std::unique_ptr<geometry::SurfaceQueries> surface_;  // of welded_
};

// Where each base vertex of `cage` lies on its limit surface at `positions` (one per vertex).
std::vector<glm::vec3> limitPositionsOfVertices(const mesh::PolygonMesh& cage, const std::vector<glm::vec3>& positions);

}  // namespace subdfit::simplify
