// The ID/UV buffer is what routes every pixel's loss difference to parameters (DESIGN.md, G), so
// it must name the right ptex face and (u,v): the CPU limit surface at (face, u, v), projected
// with the same camera, has to land on the pixel that reported it.
#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "gl_test_context.h"
#include "io/image_io.h"
#include "maps/map_parameters.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "render/camera.h"
#include "render/patch_renderer.h"
#include "render/render_target.h"
#include "render/stencil_evaluator.h"
#include "scene/scene_frame.h"
#include "subdiv/limit_evaluator.h"
#include "subdiv/patch_set.h"
#include "test_paths.h"

namespace subdfit::render {
namespace {

constexpr int kResolution = 256;
constexpr int kTessLevel = 16;
constexpr int kSamplesPerView = 2000;
constexpr float kMaxErrorPixels = 0.75f;
constexpr double kRequiredFraction = 0.99;

// A cage normalised into the unit sphere (which the cameras frame), on the GPU, with its CPU twin.
struct Cage {
    explicit Cage(mesh::PolygonMesh input)
        : mesh(normalised(std::move(input))),
          patches(subdiv::buildPatchSet(mesh)),
          limit(mesh),
          stencils(patches),
          control(gl::Buffer::fromVector(flatten(mesh.positions))),
          points(stencils.makePointBuffer()),
          renderer(patches, kTessLevel) {
        stencils.evaluate(test::programs(), control, points);
    }

    static mesh::PolygonMesh normalised(mesh::PolygonMesh m) {
        m.positions = scene::frameAround(m.positions).toNormalized(m.positions);
        return m;
    }
    static std::vector<float> flatten(const std::vector<glm::vec3>& positions) {
        std::vector<float> flat;
        for (const auto& p : positions) flat.insert(flat.end(), {p.x, p.y, p.z});
        return flat;
    }

    mesh::PolygonMesh mesh;
    subdiv::PatchSet patches;
    subdiv::LimitEvaluator limit;
    StencilEvaluator stencils;
    gl::Buffer control, points;
    PatchRenderer renderer;
};

struct Frame {
    std::vector<glm::vec4> color;
    std::vector<int> faceId;
    std::vector<glm::vec2> uv;
};

Frame render(const Cage& cage, const Camera& camera) {
    RenderTarget target(kResolution, kResolution);
    cage.renderer.draw(test::programs(), cage.points, camera, target);
    return {target.readColor(), target.readFaceId(), target.readPatchUv()};
}

// Interior pixels of a face region: the pixel and its 8 neighbours carry the same id, so the
// pixel centre is well inside one face's footprint (no edge, no silhouette against background).
bool interiorOfFace(const std::vector<int>& ids, int x, int y) {
    const int id = ids[size_t(y) * kResolution + x];
    if (id < 0 || x < 1 || y < 1 || x >= kResolution - 1 || y >= kResolution - 1) return false;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            if (ids[size_t(y + dy) * kResolution + (x + dx)] != id) return false;
    return true;
}

struct Reprojection {
    std::vector<float> errors;  // pixels
    int worst = -1;             // pixel index of the largest error
    float worstError = 0.0f;

    double fractionBelow(float limit) const {
        if (errors.empty()) return 0.0;
        return double(std::count_if(errors.begin(), errors.end(), [&](float e) { return e < limit; })) /
               double(errors.size());
    }
    float median() const {
        if (errors.empty()) return 0.0f;
        auto sorted = errors;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        return sorted[sorted.size() / 2];
    }
};

// Samples ~kSamplesPerView interior, non-grazing pixels (those accepted by `keep`) and measures
// the distance between each pixel centre and the projection of the limit point it names.
Reprojection reproject(const Cage& cage, const Camera& camera, const Frame& frame,
                       const std::function<bool(int face)>& keep) {
    std::vector<int> candidates;
    for (int y = 0; y < kResolution; ++y)
        for (int x = 0; x < kResolution; ++x)
            if (interiorOfFace(frame.faceId, x, y) && keep(frame.faceId[size_t(y) * kResolution + x]))
                candidates.push_back(y * kResolution + x);
    const size_t stride = std::max<size_t>(1, candidates.size() / kSamplesPerView);
    const glm::mat4 viewProjection = camera.viewProjection();

    Reprojection result;
    for (size_t k = 0; k < candidates.size(); k += stride) {
        const int pixel = candidates[k];
        const int x = pixel % kResolution, y = pixel / kResolution;
        const int face = frame.faceId[size_t(pixel)];
        const glm::vec2 uv = glm::clamp(frame.uv[size_t(pixel)], 0.0f, 1.0f);
        // A face id the CPU has no surface for is a wrong id: count it as a miss, not a skip.
        if (!cage.limit.hasSurface(face, uv.x, uv.y)) {
            result.errors.push_back(1e9f);
            continue;
        }
        const auto sample = cage.limit.evaluate(face, uv.x, uv.y, cage.mesh.positions);
        // Silhouettes within one face (the surface folding away from the eye): the pixel there
        // covers a steep stretch of surface, where (u,v) is legitimately ill-conditioned.
        const glm::vec3 normal = glm::cross(sample.dPdu, sample.dPdv);
        const glm::vec3 toEye = camera.eye - sample.position;
        if (glm::length(normal) > 0.0f && std::abs(glm::dot(glm::normalize(normal), glm::normalize(toEye))) < 0.1f)
            continue;
        const glm::vec4 clip = viewProjection * glm::vec4(sample.position, 1.0f);
        const glm::vec2 projected = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * float(kResolution);
        const float error = glm::length(projected - glm::vec2(float(x) + 0.5f, float(y) + 0.5f));
        result.errors.push_back(error);
        if (error > result.worstError) {
            result.worstError = error;
            result.worst = pixel;
        }
    }
    return result;
}

void saveForInspection(const std::string& name, const Frame& frame) {
    const auto dir = test::scratchDir("IdBuffer." + name);
    io::writeImage(dir / "color.png", frame.color, kResolution, kResolution);
    // Face ids as a hashed colour, so neighbouring faces differ visibly.
    std::vector<glm::vec4> ids(frame.faceId.size());
    for (size_t i = 0; i < ids.size(); ++i) {
        const unsigned h = unsigned(frame.faceId[i]) * 2654435761u;
        ids[i] = frame.faceId[i] < 0
                     ? glm::vec4(0.0f)
                     : glm::vec4(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u), 255.0f) / 255.0f;
    }
    io::writeImage(dir / "face_id.png", ids, kResolution, kResolution);
    std::cout << "  images in " << dir.string() << "\n";
}

void expectReprojects(const std::string& name, const Reprojection& r, const Frame& frame, size_t minSamples) {
    std::cout << "[ reproject ] " << name << ": " << r.errors.size() << " samples, median " << r.median() << " px, max "
              << r.worstError << " px (pixel " << r.worst % kResolution << "," << r.worst / kResolution << "), "
              << 100.0 * r.fractionBelow(kMaxErrorPixels) << " % < " << kMaxErrorPixels << " px\n";
    ::testing::Test::RecordProperty(name + "_median_px", std::to_string(r.median()));
    ::testing::Test::RecordProperty(name + "_max_px", std::to_string(r.worstError));
    EXPECT_GE(r.errors.size(), minSamples);
    EXPECT_GE(r.fractionBelow(kMaxErrorPixels), kRequiredFraction);
    if (::testing::Test::HasFailure()) saveForInspection(name, frame);
}

const glm::vec3 kViews[] = {{0.3f, 0.5f, 1.0f}, {-1.0f, -0.4f, 0.2f}, {0.1f, 1.0f, -0.5f}};

struct CageCase {
    const char* name;
    std::function<mesh::PolygonMesh()> make;
    double minSeenFraction = 0.0;  // of ptex faces, over the six views of the large-cage test
};
void PrintTo(const CageCase& c, std::ostream* os) { *os << c.name; }

class IdBufferReprojection : public ::testing::TestWithParam<CageCase> {};

TEST_P(IdBufferReprojection, LimitPointAtFaceUvProjectsOntoItsPixel) {
    const Cage cage(GetParam().make());
    for (size_t v = 0; v < std::size(kViews); ++v) {
        const Camera camera = orbitCamera(kViews[v]);
        const Frame frame = render(cage, camera);
        for (int id : frame.faceId) ASSERT_LT(id, cage.patches.ptexFaceCount);
        // The (u,v) of a face lies on its unit square (glsl/patch.frag clamps what a sliver at a
        // silhouette extrapolates past it); whether it is the right point, the reprojection says.
        for (const auto& uv : frame.uv) {
            ASSERT_GE(std::min(uv.x, uv.y), 0.0f);
            ASSERT_LE(std::max(uv.x, uv.y), 1.0f);
        }
        const auto r = reproject(cage, camera, frame, [](int) { return true; });
        expectReprojects(std::string(GetParam().name) + "_view" + std::to_string(v), r, frame, 1000);
    }
    test::expectNoGlError();
}

mesh::PolygonMesh loadAsset(const char* relative) { return mesh::loadMesh(test::assetPath(relative)); }

INSTANTIATE_TEST_SUITE_P(Cages, IdBufferReprojection,
                         ::testing::Values(CageCase{"torus", [] { return loadAsset("osd-shapes/catmark_torus.obj"); }},
                                           CageCase{"spot", [] { return loadAsset("spot/spot_control_mesh.obj"); }}),
                         [](const auto& info) { return std::string(info.param.name); });

// The tessellation is evaluated with one basis per pass (glsl/tessellate.comp): a cage without
// extraordinary vertices compiles no Gregory variant, one with them compiles both (what each kind
// draws, the reprojection above checks).
TEST(PatchKinds, OnlyACageWithGregoryPatchesCompilesTheirVariant) {
    for (const auto& [file, extraordinary] :
         {std::pair{"osd-shapes/catmark_torus.obj", false}, std::pair{"spot/spot_control_mesh.obj", true}}) {
        const Cage cage(loadAsset(file));
        const bool gregoryPatches = std::any_of(cage.patches.patchInfo.begin(), cage.patches.patchInfo.end(),
                                                [](const auto& info) { return info.y == subdiv::kGregoryBasisPatch; });
        ASSERT_EQ(gregoryPatches, extraordinary) << file;
        gl::ProgramCache cache(test::platformDefines());
        RenderTarget target(64, 64);
        cage.renderer.draw(cache, cage.points, orbitCamera(kViews[0]), target);
        bool regularVariant = false, gregoryVariant = false;
        for (const auto& v : cache.variants()) {
            if (v.name != "patch_tessellate") continue;
            (v.defines.count("SUBDFIT_GREGORY_PATCHES") ? gregoryVariant : regularVariant) = true;
        }
        EXPECT_TRUE(regularVariant) << file;
        EXPECT_EQ(gregoryVariant, extraordinary) << file;
    }
    test::expectNoGlError();
}

// A map stage on a frozen cage keeps the limit surface and displaces it by each set of heights
// (PatchRenderer::evaluateLimit, displace): the surface must be the one evaluate() gives with
// the same heights, bit for bit, its vertices and its triangles, whichever normal shades them.
TEST(PatchDisplacement, AKeptLimitSurfaceDisplacedIsTheSurfaceEvaluatedAtOnce) {
    const Cage cage(loadAsset("spot/spot_control_mesh.obj"));
    maps::MapParameters maps(cage.mesh, {maps::MapKind::Displacement}, {.resolution = 3});
    std::vector<float> heights(size_t(maps.displacement()->count()));
    for (size_t i = 0; i < heights.size(); ++i) heights[i] = 0.01f * std::sin(0.37f * float(i));
    maps.displacement()->write(heights);
    const gl::Buffer limit = cage.renderer.makeVertices();
    cage.renderer.evaluateLimit(test::programs(), cage.points, limit);
    for (const auto shading : {surface::ShadingNormal::Displaced, surface::ShadingNormal::Limit}) {
        maps.setShadingNormal(shading);
        const render::PatchMaps patchMaps = maps.forRaster(maps::ParameterVersion::Current);
        const auto atOnce = cage.renderer.makeSurface(), displaced = cage.renderer.makeSurface();
        cage.renderer.evaluate(test::programs(), cage.points, atOnce, &patchMaps);
        cage.renderer.displace(test::programs(), limit, displaced, patchMaps);
        EXPECT_EQ(displaced.vertices.read<float>(), atOnce.vertices.read<float>());
        EXPECT_EQ(displaced.triangles.read<std::uint32_t>(), atOnce.triangles.read<std::uint32_t>());
    }
    test::expectNoGlError();
}

// The SGE passes draw with the face id as the colour's alpha (render/render_target.h): read back,
// that layout must hold what the separate attachment does, pixel for pixel: colours, coverage,
// face ids (here up to 1535, past what a small float format would keep) and (u,v).
TEST(TargetLayouts, FaceInAlphaReadsBackAsTheSeparateAttachment) {
    const Cage cage(mesh::makeQuadSphere(16));
    for (const auto& direction : kViews) {
        const Camera camera = orbitCamera(direction);
        RenderTarget separate(kResolution, kResolution), packed(kResolution, kResolution, {.faceInAlpha = true});
        cage.renderer.draw(test::programs(), cage.points, camera, separate);
        cage.renderer.draw(test::programs(), cage.points, camera, packed);
        const auto ids = separate.readFaceId();
        ASSERT_GT(*std::max_element(ids.begin(), ids.end()), 1024);
        ASSERT_GT(std::count(ids.begin(), ids.end(), -1), 0);
        EXPECT_EQ(packed.readFaceId(), ids);
        EXPECT_EQ(packed.readColor(), separate.readColor());
        EXPECT_EQ(packed.readPatchUv(), separate.readPatchUv());
    }
    test::expectNoGlError();
}

// llvmpipe restarts gl_PrimitiveID every 1024 patches in the tessellation stages; a renderer
// that took the patch index from it would give every patch >= 1024 the id of patch % 1024.
// So: cages with well over 1024 patches, and the pixels of faces drawn by those late patches
// must still name their face and (u,v) correctly, from views that together see every face.
class IdBufferLargeCage : public ::testing::TestWithParam<CageCase> {};

TEST_P(IdBufferLargeCage, FacesOfPatchesBeyond1024AreRightAndAllFacesAppear) {
    const Cage cage(GetParam().make());
    ASSERT_GT(cage.patches.patchCount(), 1024) << "the case no longer tests the restart";
    std::set<int> lateFaces;  // faces with at least one patch at index >= 1024
    for (int p = 1024; p < cage.patches.patchCount(); ++p) lateFaces.insert(cage.patches.patchParam(p).GetFaceId());
    std::cout << "[ cage ] " << GetParam().name << ": " << cage.mesh.faceCount() << " faces, "
              << cage.patches.ptexFaceCount << " ptex faces, " << cage.patches.patchCount() << " patches, "
              << lateFaces.size() << " faces drawn by patches >= 1024\n";

    std::set<int> seen;
    size_t lateSamples = 0;
    const auto cameras = orbitCameras(6, 7u);
    for (size_t v = 0; v < cameras.size(); ++v) {
        const Frame frame = render(cage, cameras[v]);
        for (int id : frame.faceId) {
            ASSERT_LT(id, cage.patches.ptexFaceCount);
            if (id >= 0) seen.insert(id);
        }
        const std::string name = std::string(GetParam().name) + "_view" + std::to_string(v);
        expectReprojects(name, reproject(cage, cameras[v], frame, [](int) { return true; }), frame, 1000);
        const auto late = reproject(cage, cameras[v], frame, [&](int face) { return lateFaces.count(face) > 0; });
        expectReprojects(name + "_late", late, frame, 0);
        lateSamples += late.errors.size();
    }
    EXPECT_GE(lateSamples, 1000u) << "too few pixels of late patches to test";
    if (cage.patches.ptexFaceCount > 1024) {
        EXPECT_GE(*seen.rbegin(), 1024) << "no ptex face id >= 1024 ever drawn";
    }
    int lateSeen = 0;
    for (int face : lateFaces) lateSeen += seen.count(face) > 0;
    std::cout << "[ cage ] " << GetParam().name << ": " << seen.size() << " of " << cage.patches.ptexFaceCount
              << " ptex faces seen (max id " << (seen.empty() ? -1 : *seen.rbegin()) << "), " << lateSeen << " of "
              << lateFaces.size() << " late faces\n";
    // Concave cages hide some faces from every view (the bishop's inner shell); a sphere none.
    EXPECT_GE(double(lateSeen), GetParam().minSeenFraction * double(lateFaces.size()));
    EXPECT_GE(double(seen.size()), GetParam().minSeenFraction * double(cage.patches.ptexFaceCount));
    test::expectNoGlError();
}

INSTANTIATE_TEST_SUITE_P(Cages, IdBufferLargeCage,
                         // 1536 quads: ptex ids beyond 1024 as well as patches beyond 1024.
                         ::testing::Values(CageCase{"quad_sphere_16", [] { return mesh::makeQuadSphere(16); }, 1.0},
                                           CageCase{"bishop", [] { return loadAsset("osd-shapes/catmark_bishop.obj"); },
                                                    0.7}),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace subdfit::render
