#include "export/usd/usd_cage.h"

#include <glm/common.hpp>

#include <algorithm>
#include <limits>
#include <map>

#include "util/error.h"

namespace subdfit::exporter {
namespace {

// USD's UsdGeomMesh::SHARPNESS_INFINITE, and OpenSubdiv's Sdc::Crease::SHARPNESS_INFINITE.
constexpr float kInfinitelySharp = 10.0f;

// Each face corner's coordinates, deduplicated into values and per-corner indices.
struct IndexedPrimvar {
    std::vector<glm::vec2> values;
    std::vector<int> indices;
};

IndexedPrimvar faceVarying(const subdiv::RefinedCage& cage, const UsdTexCoords& coords) {
    IndexedPrimvar out;
    std::map<std::pair<float, float>, int> seen;
    for (int f = 0; f < cage.mesh.faceCount(); ++f)
        for (int c = 0; c < 4; ++c) {
            const glm::vec2 st = coords.at(cage.ptexFace[size_t(f)], cage.cornerUv[4 * size_t(f) + size_t(c)]);
            const auto [at, fresh] = seen.try_emplace({st.x, st.y}, int(out.values.size()));
            if (fresh) out.values.push_back(st);
            out.indices.push_back(at->second);
        }
    return out;
}

void writeTags(usda::Layer& layer, const mesh::SubdivisionTags& tags) {
    auto sharpness = [](float s) { return std::min(s, kInfinitelySharp); };
    if (!tags.creases.empty()) {
        std::vector<int> indices, lengths;
        std::vector<float> sharpnesses;
        for (const mesh::Crease& c : tags.creases) {
            indices.insert(indices.end(), {c.v0, c.v1});
            lengths.push_back(2);
            sharpnesses.push_back(sharpness(c.sharpness));
        }
        layer.line("int[] creaseIndices = " + usda::array(indices));
        layer.line("int[] creaseLengths = " + usda::array(lengths));
        layer.line("float[] creaseSharpnesses = " + usda::array(sharpnesses));
    }
    if (!tags.corners.empty()) {
        std::vector<int> indices;
        std::vector<float> sharpnesses;
        for (const mesh::Corner& c : tags.corners)
            indices.push_back(c.vertex), sharpnesses.push_back(sharpness(c.sharpness));
        layer.line("int[] cornerIndices = " + usda::array(indices));
        layer.line("float[] cornerSharpnesses = " + usda::array(sharpnesses));
    }
    if (!tags.holes.empty()) layer.line("int[] holeIndices = " + usda::array(tags.holes));
}

}  // namespace

std::string usdBoundaryToken(mesh::BoundaryInterpolation boundary) {
    switch (boundary) {
        case mesh::BoundaryInterpolation::None: return "none";
        case mesh::BoundaryInterpolation::EdgeAndCorner: return "edgeAndCorner";
        case mesh::BoundaryInterpolation::EdgeOnly: break;
    }
    return "edgeOnly";
}

std::string usdTriangleToken(mesh::TriangleSubdivision triangles) {
    return triangles == mesh::TriangleSubdivision::Smooth ? "smooth" : "catmullClark";
}

subdiv::RefinedCage usdCageOf(const mesh::PolygonMesh& cage, bool texCoords) {
    const bool quads = std::all_of(cage.faceSizes.begin(), cage.faceSizes.end(), [](int n) { return n == 4; });
    if (texCoords && !quads) return subdiv::refinedOnceWithPtex(cage);
    subdiv::RefinedCage out{.mesh = cage, .ptexFace = {}, .cornerUv = {}};
    if (!quads) return out;
    for (int f = 0; f < cage.faceCount(); ++f) {
        out.ptexFace.push_back(f);
        out.cornerUv.insert(out.cornerUv.end(), {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
    }
    return out;
}

void writeCagePrim(usda::Layer& layer, const subdiv::RefinedCage& cage, const std::vector<UsdTexCoords>& texCoords,
                   const UsdCageOptions& options) {
    const mesh::PolygonMesh& mesh = cage.mesh;
    SUBDFIT_CHECK(texCoords.empty() || (cage.ptexFace.size() == size_t(mesh.faceCount()) &&
                                        cage.cornerUv.size() == 4 * cage.ptexFace.size()));
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    lo -= glm::vec3(options.reach), hi += glm::vec3(options.reach);

    layer.block("def Mesh " + usda::quoted(options.name) +
                (options.material.empty() ? "" : " (prepend apiSchemas = [\"MaterialBindingAPI\"])"));
    layer.line("uniform token subdivisionScheme = \"catmullClark\"");
    layer.line("token interpolateBoundary = " + usda::quoted(usdBoundaryToken(mesh.tags.boundary)));
    // Face-varying values are blended linearly across each face, as subdfit samples its tiles
    // and atlas coordinates on a ptex face (see the header).
    layer.line("token faceVaryingLinearInterpolation = \"all\"");
    layer.line("token triangleSubdivisionRule = " + usda::quoted(usdTriangleToken(mesh.tags.triangles)));
    layer.line("uniform token orientation = \"rightHanded\"");
    layer.line("float3[] extent = " + usda::array(std::vector<glm::vec3>{lo, hi}));
    layer.line("int[] faceVertexCounts = " + usda::array(mesh.faceSizes));
    layer.line("int[] faceVertexIndices = " + usda::array(mesh.faceIndices));
    layer.line("point3f[] points = " + usda::array(mesh.positions));
    writeTags(layer, mesh.tags);
    for (const UsdTexCoords& coords : texCoords) {
        const IndexedPrimvar primvar = faceVarying(cage, coords);
        layer.line("texCoord2f[] primvars:" + coords.primvar + " = " + usda::array(primvar.values) +
                   " (interpolation = \"faceVarying\")");
        layer.line("int[] primvars:" + coords.primvar + ":indices = " + usda::array(primvar.indices));
    }
    // RenderMan displaces only within a bound it is told (hdPrman assumes 1 for a
    // UsdPreviewSurface): the heights' own reach, as RenderMan's attribute primvar.
    if (options.reach > 0.0f)
        layer.line("float primvars:ri:attributes:displacementbound:sphere = " + usda::number(options.reach) +
                   " (interpolation = \"constant\")");
    if (!options.material.empty()) layer.line("rel material:binding = <" + options.material + ">");
    layer.end();
}

}  // namespace subdfit::exporter
