// Every bundled OpenSubdiv regression shape (assets/osd-shapes) through the whole render path:
// load, PatchSet, stencils, tessellated draw from six views. Each shape is its own test, so a
// regression names the shape. What must hold: colour finite, something drawn, face ids in
// range, and on closed shapes no pinholes (cracks between patches of different depth show up
// as single background pixels inside the object).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gl_test_context.h"
#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "render/camera.h"
#include "render/patch_renderer.h"
#include "render/render_target.h"
#include "render/stencil_evaluator.h"
#include "scene/scene_frame.h"
#include "subdiv/patch_set.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::render {
namespace {

namespace fs = std::filesystem;

constexpr int kResolution = 128;
constexpr int kViews = 6;
constexpr int kTessLevel = 8;

// Shapes buildPatchSet refuses (with a subdfit::Error naming the file), and why. A shape that
// starts or stops being refused fails its test, so this list stays the truth.
const std::map<std::string, std::string> kRefused = {};

std::vector<std::string> shapeFiles() {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(test::assetPath("osd-shapes")))
        if (entry.path().extension() == ".obj") names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Closed: every edge is shared by exactly two faces (no boundary, no non-manifold edge, no
// degenerate self-edge). Hole tags do not count: through a hole one sees the inside (both
// sides are drawn), so a closed cage with holes must not show pinholes either.
bool isClosed(const mesh::PolygonMesh& m) {
    std::map<std::pair<int, int>, int> edgeUse;
    int offset = 0;
    for (int size : m.faceSizes) {
        for (int k = 0; k < size; ++k) {
            const int a = m.faceIndices[size_t(offset + k)];
            const int b = m.faceIndices[size_t(offset + (k + 1) % size)];
            if (a == b) return false;
            ++edgeUse[{std::min(a, b), std::max(a, b)}];
        }
        offset += size;
    }
    return std::all_of(edgeUse.begin(), edgeUse.end(), [](const auto& e) { return e.second == 2; });
}

// Background pixels whose four neighbours are all covered.
std::vector<int> pinholes(const std::vector<int>& ids) {
    std::vector<int> found;
    for (int y = 1; y < kResolution - 1; ++y)
        for (int x = 1; x < kResolution - 1; ++x) {
            const auto id = [&](int px, int py) { return ids[size_t(py) * kResolution + px]; };
            if (id(x, y) < 0 && id(x - 1, y) >= 0 && id(x + 1, y) >= 0 && id(x, y - 1) >= 0 && id(x, y + 1) >= 0)
                found.push_back(y * kResolution + x);
        }
    return found;
}

fs::path saveForInspection(const std::string& shape, int view, const std::vector<glm::vec4>& color,
                           const std::vector<int>& ids) {
    const auto dir = test::scratchDir("RenderShapes." + shape + ".view" + std::to_string(view));
    std::vector<glm::vec4> rgb(color);
    for (auto& c : rgb)
        if (!std::isfinite(c.x + c.y + c.z)) c = glm::vec4(1, 0, 1, 1);  // NaN/Inf in magenta
    io::writeImage(dir / "color.png", rgb, kResolution, kResolution);
    std::vector<glm::vec4> coverage(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) coverage[i] = ids[i] < 0 ? glm::vec4(0.0f) : glm::vec4(1.0f);
    for (int p : pinholes(ids)) coverage[size_t(p)] = glm::vec4(1, 0, 0, 1);  // pinholes in red
    io::writeImage(dir / "coverage.png", coverage, kResolution, kResolution);
    return dir;
}

class RenderShapes : public ::testing::TestWithParam<std::string> {};

TEST_P(RenderShapes, LoadsBuildsAndRendersCleanly) {
    const std::string name = GetParam();
    const fs::path path = test::assetPath("osd-shapes/" + name);
    mesh::PolygonMesh cage;
    ASSERT_NO_THROW(cage = mesh::loadMesh(path));
    cage.positions = scene::frameAround(cage.positions).toNormalized(cage.positions);
    const bool closed = isClosed(cage);
    RecordProperty("closed", closed ? "yes" : "no");

    subdiv::PatchSet patches;
    const auto refused = kRefused.find(name);
    try {
        patches = subdiv::buildPatchSet(cage);
    } catch (const Error& e) {
        const std::string message = e.what();
        RecordProperty("outcome", "refused: " + message);
        std::cout << "[ outcome ] " << name << ": refused: " << message << "\n";
        EXPECT_NE(refused, kRefused.end()) << "unexpectedly refused: " << message;
        EXPECT_NE(message.find(name), std::string::npos) << "error does not name the file: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return;
    }
    ASSERT_EQ(refused, kRefused.end()) << "listed as refused (" << refused->second << ") but builds";

    const StencilEvaluator stencils(patches);
    std::vector<float> flat;
    for (const auto& p : cage.positions) flat.insert(flat.end(), {p.x, p.y, p.z});
    const auto control = gl::Buffer::fromVector(flat);
    const auto points = stencils.makePointBuffer();
    stencils.evaluate(test::programs(), control, points);
    const PatchRenderer renderer(patches, kTessLevel);
    RenderTarget target(kResolution, kResolution);

    const auto cameras = orbitCameras(kViews, 1u);
    int totalPinholes = 0;
    for (int v = 0; v < kViews; ++v) {
        SCOPED_TRACE("view " + std::to_string(v));
        renderer.draw(test::programs(), points, cameras[size_t(v)], target);
        const auto color = target.readColor();
        const auto ids = target.readFaceId();
        const int nonFinite = int(std::count_if(color.begin(), color.end(), [](const glm::vec4& c) {
            return !std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w);
        }));
        const int covered = int(std::count_if(ids.begin(), ids.end(), [](int id) { return id >= 0; }));
        const int outOfRange =
            int(std::count_if(ids.begin(), ids.end(), [&](int id) { return id < -1 || id >= patches.ptexFaceCount; }));
        const int holes = closed ? int(pinholes(ids).size()) : 0;
        totalPinholes += holes;
        EXPECT_EQ(nonFinite, 0) << "pixels with NaN/Inf colour";
        EXPECT_GT(covered, 0) << "nothing drawn";
        EXPECT_EQ(outOfRange, 0) << "face ids outside [-1, " << patches.ptexFaceCount << ")";
        EXPECT_EQ(holes, 0) << "pinholes in a closed shape";
        if (nonFinite || !covered || outOfRange || holes)
            std::cout << "  images: " << saveForInspection(name.substr(0, name.size() - 4), v, color, ids).string()
                      << "\n";
    }
    RecordProperty("outcome", "rendered");
    std::cout << "[ outcome ] " << name << ": rendered, " << patches.patchCount() << " patches, ptex "
              << patches.ptexFaceCount << (closed ? ", closed" : ", open") << ", pinholes " << totalPinholes << "\n";
    test::expectNoGlError();
}

// The detector itself, on a made-up id image: one enclosed background pixel is found, a gap open
// to one side is not.
TEST(RenderShapesCorpus, PinholeDetectorFindsEnclosedPixelsOnly) {
    std::vector<int> ids(size_t(kResolution) * kResolution, -1);
    for (int y = 10; y < 20; ++y)
        for (int x = 10; x < 20; ++x) ids[size_t(y) * kResolution + x] = 3;
    ids[size_t(15) * kResolution + 15] = -1;  // enclosed
    ids[size_t(10) * kResolution + 12] = -1;  // notch on the border: open to the background
    const auto found = pinholes(ids);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0], 15 * kResolution + 15);
}

TEST(RenderShapesCorpus, AllFiftyEightShapesAreBundled) { EXPECT_EQ(shapeFiles().size(), 58u); }

INSTANTIATE_TEST_SUITE_P(Osd, RenderShapes, ::testing::ValuesIn(shapeFiles()), [](const auto& info) {
    std::string id = info.param.substr(0, info.param.size() - 4);  // gtest names: no '.'
    return id;
});

}  // namespace
}  // namespace subdfit::render
