// PatchSet and LimitEvaluator against OpenSubdiv's own limit stencils (an independent path:
// its own patch table, stencils with control vertices, its own patch lookup), against known
// Catmull-Clark values, and against brute force.
#include <gtest/gtest.h>
#include <opensubdiv/sdc/crease.h>

#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <tuple>

#include "mesh/obj_reader.h"
#include "subdiv/limit_evaluator.h"
#include "subdiv/patch_set.h"
#include "subdiv/topology.h"
#include "test_paths.h"
#include "util/error.h"

// PatchTable::EvaluateBasis needs a PatchTable; evaluating from the flattened PatchSet arrays
// (as the GPU does) needs the basis by patch type + PatchParam. OpenSubdiv exports that
// function from libosdCPU but does not install its header (far/patchBasis.h), so declare it.
namespace OpenSubdiv::OPENSUBDIV_VERSION::Far::internal {
template <typename REAL>
int EvaluatePatchBasis(int patchType, PatchParam const& param, REAL s, REAL t, REAL wP[], REAL wDs[], REAL wDt[],
                       REAL wDss[], REAL wDst[], REAL wDtt[]);
}  // namespace OpenSubdiv::OPENSUBDIV_VERSION::Far::internal

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;
using mesh::PolygonMesh;

// ---- cages built in code -------------------------------------------------------------------

void addFace(PolygonMesh& m, std::initializer_list<int> vertices) {
    m.faceSizes.push_back(int(vertices.size()));
    m.faceIndices.insert(m.faceIndices.end(), vertices);
}

// (n+1)^2 vertices on [-n/2, n/2]^2, z = height(x, y); vertex (i, j) is j * (n+1) + i.
PolygonMesh quadGrid(int n, const std::function<float(float, float)>& height) {
    PolygonMesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = i - n * 0.5f, y = j - n * 0.5f;
            m.positions.emplace_back(x, y, height(x, y));
        }
    const auto id = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) addFace(m, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    return m;
}

// The surface of [-1,1]^3 cut into n x n quads per side, optionally pushed onto the unit sphere.
PolygonMesh cubeCage(int n, bool sphere = false) {
    PolygonMesh m;
    std::map<std::tuple<int, int, int>, int> index;
    const auto vertex = [&](glm::ivec3 lattice) {
        const auto key = std::make_tuple(lattice.x, lattice.y, lattice.z);
        if (auto it = index.find(key); it != index.end()) return it->second;
        glm::vec3 p = glm::vec3(lattice) * (2.0f / n) - 1.0f;
        if (sphere) p = glm::normalize(p);
        m.positions.push_back(p);
        return index[key] = m.vertexCount() - 1;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            // (b, c) with e_b x e_c pointing out of the cube, so faces wind counter-clockwise.
            int b = (axis + 1) % 3, c = (axis + 2) % 3;
            if (side == 0) std::swap(b, c);
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const auto at = [&](int di, int dj) {
                        glm::ivec3 l(0);
                        l[axis] = side * n;
                        l[b] = i + di;
                        l[c] = j + dj;
                        return vertex(l);
                    };
                    addFace(m, {at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
                }
        }
    return m;
}

// A closed pentagonal pyramid: one pentagon and five triangles (non-quads everywhere).
PolygonMesh pentagonPyramid() {
    PolygonMesh m;
    for (int i = 0; i < 5; ++i) {
        const float a = float(i) * 2.0f * 3.14159265f / 5.0f;
        m.positions.emplace_back(std::cos(a), std::sin(a), 0.0f);
    }
    m.positions.emplace_back(0.1f, -0.2f, 1.3f);
    addFace(m, {4, 3, 2, 1, 0});
    for (int i = 0; i < 5; ++i) addFace(m, {i, (i + 1) % 5, 5});
    return m;
}

// An open disk whose centre has `valence` edges: `valence` quads around it, one ring beyond.
PolygonMesh poleDisk(int valence) {
    PolygonMesh m;
    m.positions.emplace_back(0.0f, 0.0f, 0.3f);
    const int ring = 2 * valence;
    for (int r = 1; r <= 2; ++r)
        for (int k = 0; k < ring; ++k) {
            const float a = float(k) * 2.0f * 3.14159265f / float(ring);
            m.positions.emplace_back(r * std::cos(a), r * std::sin(a), 0.2f * std::sin(3.0f * a));
        }
    const auto inner = [&](int k) { return 1 + k % ring; };
    const auto outer = [&](int k) { return 1 + ring + k % ring; };
    for (int q = 0; q < valence; ++q) addFace(m, {0, inner(2 * q), inner(2 * q + 1), inner(2 * q + 2)});
    for (int k = 0; k < ring; ++k) addFace(m, {inner(k), outer(k), outer(k + 1), inner(k + 1)});
    return m;
}

PolygonMesh bumpyGridWithCreases() {
    PolygonMesh m = quadGrid(4, [](float x, float y) { return 0.3f * std::sin(x) * std::cos(y); });
    m.tags.creases = {{6, 7, 10.0f}, {7, 8, 10.0f}, {11, 12, 2.0f}, {12, 13, 2.5f}};
    m.tags.corners = {{0, 10.0f}};
    return m;
}

PolygonMesh gridWithHole() {
    PolygonMesh m = quadGrid(4, [](float x, float y) { return 0.1f * x * y; });
    m.tags.holes = {5};
    return m;
}

struct NamedMesh {
    const char* name;
    PolygonMesh mesh;
};

std::vector<NamedMesh> testMeshes() {
    PolygonMesh chaikin = bumpyGridWithCreases();
    chaikin.tags.creaseMethod = mesh::CreaseMethod::Chaikin;
    chaikin.tags.boundary = mesh::BoundaryInterpolation::EdgeAndCorner;
    PolygonMesh smoothTris = pentagonPyramid();
    smoothTris.tags.triangles = mesh::TriangleSubdivision::Smooth;
    return {{"cube", cubeCage(1)},
            {"sphere cube 3", cubeCage(3, true)},
            {"grid with creases", bumpyGridWithCreases()},
            {"chaikin, edge-and-corner", chaikin},
            {"pentagon pyramid", pentagonPyramid()},
            {"smooth triangles", smoothTris},
            {"valence 8 pole", poleDisk(8)},
            {"valence 66 pole", poleDisk(66)},
            {"grid with hole", gridWithHole()}};
}

// ---- references ----------------------------------------------------------------------------

struct Location {
    int ptexFace;
    float u, v;
};

// OpenSubdiv's LimitStencilTable for the same cage and isolation level, built its own way.
std::unique_ptr<const Far::LimitStencilTable> limitStencils(const PolygonMesh& mesh, int isolationLevel,
                                                            const std::vector<Location>& locations) {
    RefinerPtr refiner = buildTopologyRefiner(mesh);
    Far::TopologyRefiner::AdaptiveOptions adaptive(isolationLevel);
    adaptive.useInfSharpPatch = true;
    refiner->RefineAdaptive(adaptive);
    Far::LimitStencilTableFactory::LocationArrayVec arrays;
    for (const Location& l : locations) {
        Far::LimitStencilTableFactory::LocationArray a;
        a.ptexIdx = l.ptexFace;
        a.numLocations = 1;
        a.s = &l.u;
        a.t = &l.v;
        arrays.push_back(a);
    }
    std::unique_ptr<const Far::LimitStencilTable> table(Far::LimitStencilTableFactory::Create(*refiner, arrays));
    EXPECT_TRUE(table);
    EXPECT_EQ(table->GetNumStencils(), int(locations.size()));  // no location in a hole
    return table;
}

std::vector<LimitSample> limitStencilReference(const PolygonMesh& mesh, int isolationLevel,
                                               const std::vector<Location>& locations) {
    const auto table = limitStencils(mesh, isolationLevel, locations);
    std::vector<LimitSample> samples(locations.size());
    for (int s = 0; s < table->GetNumStencils(); ++s) {
        glm::dvec3 p(0.0), du(0.0), dv(0.0);
        for (int e = table->GetOffsets()[s]; e < table->GetOffsets()[s] + table->GetSizes()[s]; ++e) {
            const glm::dvec3 x(mesh.positions[table->GetControlIndices()[e]]);
            p += double(table->GetWeights()[e]) * x;
            du += double(table->GetDuWeights()[e]) * x;
            dv += double(table->GetDvWeights()[e]) * x;
        }
        samples[s] = {glm::vec3(p), glm::vec3(du), glm::vec3(dv)};
    }
    return samples;
}

// The GPU's path: points from the stencil CSR, the patch found in the flattened patch arrays,
// the basis from patch type + PatchParam bits.
LimitSample evaluatePatchSet(const PatchSet& set, const std::vector<glm::vec3>& points, const Location& l) {
    for (int patch = 0; patch < set.patchCount(); ++patch) {
        const Far::PatchParam param = set.patchParam(patch);
        if (param.GetFaceId() != l.ptexFace) continue;
        const float frac = param.GetParamFraction();
        const float u0 = param.GetU() * frac, v0 = param.GetV() * frac;
        if (l.u < u0 || l.u > u0 + frac || l.v < v0 || l.v > v0 + frac) continue;
        const glm::ivec4 info = set.patchInfo[patch];
        float wP[20], wDu[20], wDv[20];
        Far::internal::EvaluatePatchBasis<float>(info.y, param, l.u, l.v, wP, wDu, wDv, nullptr, nullptr, nullptr);
        LimitSample s;
        for (int k = 0; k < patchCvCount(info.y); ++k) {
            const glm::vec3 cv = points[set.patchCvIndices[info.x + k]];
            s.position += wP[k] * cv;
            s.dPdu += wDu[k] * cv;
            s.dPdv += wDv[k] * cv;
        }
        return s;
    }
    ADD_FAILURE() << "no patch covers ptex face " << l.ptexFace << " at " << l.u << "," << l.v;
    return {};
}

// Sample coordinates that avoid dyadic fractions, so no sample sits on a sub-patch border
// (where Gregory end caps are only approximately tangent-continuous and two patches could
// legitimately give different derivatives).
constexpr float kSampleCoords[] = {0.013f, 0.27f, 0.61f, 0.93f, 0.994f};

std::vector<Location> sampleLocations(const PatchSet& set) {
    std::vector<Location> locations;
    for (int f = 0; f < set.ptexFaceCount; ++f) {
        if (set.faceVertexOffsets[f] == set.faceVertexOffsets[f + 1]) continue;  // hole
        for (float u : kSampleCoords)
            for (float v : kSampleCoords) locations.push_back({f, u, v});
    }
    return locations;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance, const std::string& what) {
    const float scale = std::max(1.0f, glm::length(expected));
    EXPECT_LE(glm::length(actual - expected), tolerance * scale)
        << what << ": got (" << actual.x << ", " << actual.y << ", " << actual.z << "), want (" << expected.x << ", "
        << expected.y << ", " << expected.z << ")";
}

// ---- tests ---------------------------------------------------------------------------------

TEST(SubdivPatchSet, FlatGridLimitStaysInItsPlane) {
    PolygonMesh grid = quadGrid(5, [](float, float) { return 0.0f; });
    for (glm::vec3& p : grid.positions) p += glm::vec3(0.1f * std::sin(7.0f * p.y), 0.13f * std::cos(5.0f * p.x), 0.0f);
    const PatchSet set = buildPatchSet(grid);
    const std::vector<glm::vec3> points = evaluatePoints(set, grid.positions);
    for (const glm::vec3& p : points) EXPECT_NEAR(p.z, 0.0f, 1e-6f);
    const LimitEvaluator evaluator(grid);
    for (const Location& l : sampleLocations(set)) {
        const LimitSample s = evaluatePatchSet(set, points, l);
        const LimitSample r = evaluator.evaluate(l.ptexFace, l.u, l.v, grid.positions);
        EXPECT_NEAR(s.position.z, 0.0f, 1e-6f);
        EXPECT_NEAR(r.position.z, 0.0f, 1e-6f);
        EXPECT_NEAR(r.dPdu.z, 0.0f, 1e-5f);
        EXPECT_NEAR(r.dPdv.z, 0.0f, 1e-5f);
        EXPECT_GT(glm::cross(r.dPdu, r.dPdv).z, 0.0f);  // faces wind counter-clockwise
    }
}

TEST(SubdivPatchSet, CubeFaceCentreHasTheKnownLimit) {
    // One Catmull-Clark step by hand on [-1,1]^3: the face point (0,0,1) becomes a regular
    // vertex with edge points at height 3/4 and moved corners at 5/9; the B-spline limit mask
    // (16 v + 4 sum(edge) + sum(diagonal)) / 36 gives z = (16 + 12 + 20/9) / 36 = 68/81.
    const PolygonMesh cube = cubeCage(1);
    const PatchSet set = buildPatchSet(cube);
    ASSERT_EQ(set.ptexFaceCount, 6);
    const LimitEvaluator evaluator(cube);
    for (int f = 0; f < 6; ++f) {
        const LimitSample s = evaluator.evaluate(f, 0.5f, 0.5f, cube.positions);
        EXPECT_NEAR(glm::length(s.position), 68.0f / 81.0f, 1e-6f) << "face " << f;
        const LimitSample p = evaluatePatchSet(set, evaluatePoints(set, cube.positions), {f, 0.5f, 0.5f});
        expectNear(p.position, s.position, 1e-6f, "patch set");
    }
}

TEST(SubdivPatchSet, PatchSetAndEvaluatorMatchOpenSubdivLimitStencils) {
    for (const int level : {1, 3}) {
        for (const NamedMesh& named : testMeshes()) {
            SCOPED_TRACE(std::string(named.name) + ", isolation " + std::to_string(level));
            const PolygonMesh& mesh = named.mesh;
            const PatchSet set = buildPatchSet(mesh, {level});
            const std::vector<glm::vec3> points = evaluatePoints(set, mesh.positions);
            const LimitEvaluator evaluator(mesh, {level});
            const std::vector<Location> locations = sampleLocations(set);
            const std::vector<LimitSample> reference = limitStencilReference(mesh, level, locations);
            ASSERT_EQ(reference.size(), locations.size());
            for (std::size_t i = 0; i < locations.size(); ++i) {
                const Location& l = locations[i];
                const std::string where = "ptex " + std::to_string(l.ptexFace) + " (" + std::to_string(l.u) + ", " +
                                          std::to_string(l.v) + ")";
                const LimitSample s = evaluatePatchSet(set, points, l);
                const LimitSample e = evaluator.evaluate(l.ptexFace, l.u, l.v, mesh.positions);
                for (const auto& [sample, who] : {std::pair{s, "patch set"}, std::pair{e, "evaluator"}}) {
                    expectNear(sample.position, reference[i].position, 1e-5f, std::string(who) + " P " + where);
                    expectNear(sample.dPdu, reference[i].dPdu, 1e-5f, std::string(who) + " dPdu " + where);
                    expectNear(sample.dPdv, reference[i].dPdv, 1e-5f, std::string(who) + " dPdv " + where);
                }
            }
        }
    }
}

TEST(SubdivPatchSet, FaceVertexListsAreExactlyTheStencilSupports) {
    for (const NamedMesh& named : testMeshes()) {
        SCOPED_TRACE(named.name);
        const PatchSet set = buildPatchSet(named.mesh);
        // Dense point -> base weights, then the support union per ptex face, by brute force.
        const int base = set.baseVertexCount;
        std::vector<std::vector<float>> dense(set.pointCount, std::vector<float>(base, 0.0f));
        for (int v = 0; v < base; ++v) dense[v][v] = 1.0f;
        for (int row = 0; row < set.stencilCount(); ++row)
            for (int e = set.stencilOffsets[row]; e < set.stencilOffsets[row + 1]; ++e)
                dense[base + row][set.stencilIndices[e]] += set.stencilWeights[e];
        std::vector<std::set<int>> expected(set.ptexFaceCount);
        for (int patch = 0; patch < set.patchCount(); ++patch) {
            const glm::ivec4 info = set.patchInfo[patch];
            for (int k = 0; k < patchCvCount(info.y); ++k)
                for (int v = 0; v < base; ++v)
                    if (dense[set.patchCvIndices[info.x + k]][v] != 0.0f)
                        expected[set.patchParam(patch).GetFaceId()].insert(v);
        }
        ASSERT_EQ(int(set.faceVertexOffsets.size()), set.ptexFaceCount + 1);
        for (int f = 0; f < set.ptexFaceCount; ++f) {
            const std::vector<int> actual(set.faceVertexIndices.begin() + set.faceVertexOffsets[f],
                                          set.faceVertexIndices.begin() + set.faceVertexOffsets[f + 1]);
            EXPECT_EQ(actual, std::vector<int>(expected[f].begin(), expected[f].end())) << "ptex " << f;
        }
    }
}

TEST(SubdivPatchSet, FaceVertexListsCoverOpenSubdivLimitStencils) {
    // Every base vertex OpenSubdiv's own limit stencil uses at a point of a face must be in
    // that face's list, or the gradient pass would miss a parameter.
    for (const NamedMesh& named : testMeshes()) {
        SCOPED_TRACE(named.name);
        const PatchSet set = buildPatchSet(named.mesh);
        const std::vector<Location> locations = sampleLocations(set);
        const auto table = limitStencils(named.mesh, 3, locations);
        ASSERT_EQ(table->GetNumStencils(), int(locations.size()));
        for (int s = 0; s < table->GetNumStencils(); ++s) {
            const int f = locations[s].ptexFace;
            const auto first = set.faceVertexIndices.begin() + set.faceVertexOffsets[f];
            const auto last = set.faceVertexIndices.begin() + set.faceVertexOffsets[f + 1];
            for (int e = table->GetOffsets()[s]; e < table->GetOffsets()[s] + table->GetSizes()[s]; ++e) {
                if (table->GetWeights()[e] == 0.0f) continue;
                EXPECT_TRUE(std::binary_search(first, last, table->GetControlIndices()[e]))
                    << "ptex " << f << " misses vertex " << table->GetControlIndices()[e];
            }
        }
    }
}

TEST(SubdivPatchSet, LargeCageKeepsPtexIdsAndPatchData) {
    // Several hundred faces: past the 64-patch chunk where llvmpipe restarts gl_PrimitiveID.
    const PolygonMesh cage = cubeCage(11, true);
    ASSERT_EQ(cage.faceCount(), 726);
    const PatchSet set = buildPatchSet(cage);
    ASSERT_EQ(set.ptexFaceCount, 726);
    for (int f = 0; f < set.ptexFaceCount; ++f) EXPECT_EQ(set.ptexToBaseFace[f], f);
    std::vector<int> patchesPerFace(set.ptexFaceCount, 0);
    for (int patch = 0; patch < set.patchCount(); ++patch) {
        const int face = set.patchParam(patch).GetFaceId();
        ASSERT_GE(face, 0);
        ASSERT_LT(face, set.ptexFaceCount);
        ++patchesPerFace[face];
    }
    for (int f = 0; f < set.ptexFaceCount; ++f) EXPECT_GT(patchesPerFace[f], 0) << "ptex " << f;

    std::vector<Location> centres;
    for (int f = 0; f < set.ptexFaceCount; ++f) centres.push_back({f, 0.31f, 0.62f});
    const std::vector<LimitSample> reference = limitStencilReference(cage, 3, centres);
    const std::vector<glm::vec3> points = evaluatePoints(set, cage.positions);
    for (std::size_t i = 0; i < centres.size(); ++i)
        expectNear(evaluatePatchSet(set, points, centres[i]).position, reference[i].position, 1e-5f,
                   "ptex " + std::to_string(i));
}

TEST(SubdivPatchSet, NonQuadFacesGetOnePtexFacePerCorner) {
    const PolygonMesh pyramid = pentagonPyramid();
    const PatchSet set = buildPatchSet(pyramid);
    ASSERT_EQ(set.ptexFaceCount, 5 + 5 * 3);
    EXPECT_EQ(set.ptexToBaseFace, (std::vector<int>{0, 0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5, 5, 5}));
}

TEST(SubdivPatchSet, InfinitelySharpCreaseStaysOnItsLine) {
    // A tent over the x axis, creased along y = 0 (the ridge, whose cage vertices are collinear).
    const auto tent = [](bool creased) {
        PolygonMesh m = quadGrid(4, [](float, float y) { return std::abs(y); });
        if (creased)
            for (int i = 0; i < 4; ++i) m.tags.creases.push_back({10 + i, 11 + i, 10.0f});
        return m;
    };
    const auto isRidge = [](const glm::vec3& p) { return p.y == 0.0f; };
    for (const bool creased : {true, false}) {
        const PolygonMesh m = tent(creased);
        const LimitEvaluator evaluator(m);
        const PatchSet set = buildPatchSet(m);
        const std::vector<glm::vec3> points = evaluatePoints(set, m.positions);
        float maxOff = 0.0f;
        for (int f = 0; f < m.faceCount(); ++f) {
            const int* v = &m.faceIndices[4 * f];
            for (int k = 0; k < 4; ++k) {
                if (!isRidge(m.positions[v[k]]) || !isRidge(m.positions[v[(k + 1) % 4]])) continue;
                for (float t : {0.0f, 0.25f, 0.5f, 0.77f, 1.0f}) {
                    // Edge k of a quad's ptex face: (t,0), (1,t), (1-t,1), (0,1-t).
                    const float u[] = {t, 1.0f, 1.0f - t, 0.0f}, w[] = {0.0f, t, 1.0f, 1.0f - t};
                    const glm::vec3 p = evaluator.evaluate(f, u[k], w[k], m.positions).position;
                    const glm::vec3 q = evaluatePatchSet(set, points, {f, u[k], w[k]}).position;
                    maxOff = std::max({maxOff, std::abs(p.y) + std::abs(p.z), std::abs(q.y) + std::abs(q.z)});
                }
            }
        }
        if (creased) EXPECT_LT(maxOff, 1e-5f);
        else EXPECT_GT(maxOff, 0.1f);  // the test can tell a crease from none
    }
}

TEST(SubdivPatchSet, OnlyRegularAndGregoryPatchesNoDeeperThanIsolation) {
    for (const NamedMesh& named : testMeshes())
        for (int level = 1; level <= 5; ++level) {
            SCOPED_TRACE(std::string(named.name) + ", isolation " + std::to_string(level));
            const PatchSet set = buildPatchSet(named.mesh, {level});
            EXPECT_LE(set.maxPatchDepth, level);
            EXPECT_GE(set.maxPatchDepth, 0);
            int deepest = 0;
            for (int patch = 0; patch < set.patchCount(); ++patch) {
                const glm::ivec4 info = set.patchInfo[patch];
                EXPECT_TRUE(info.y == kRegularPatch || info.y == kGregoryBasisPatch) << info.y;
                deepest = std::max(deepest, int(set.patchParam(patch).GetDepth()));
                const int nextOffset =
                    patch + 1 < set.patchCount() ? set.patchInfo[patch + 1].x : int(set.patchCvIndices.size());
                EXPECT_EQ(nextOffset, info.x + patchCvCount(info.y));
                for (int k = 0; k < patchCvCount(info.y); ++k) {
                    const int point = set.patchCvIndices[info.x + k];
                    EXPECT_GE(point, 0);
                    EXPECT_LT(point, set.pointCount);
                }
            }
            EXPECT_EQ(set.maxPatchDepth, deepest);
            EXPECT_EQ(int(set.stencilOffsets.size()), set.stencilCount() + 1);
            EXPECT_EQ(set.stencilOffsets.back(), int(set.stencilIndices.size()));
            for (int index : set.stencilIndices) {
                EXPECT_GE(index, 0);
                EXPECT_LT(index, set.baseVertexCount);
            }
        }
}

TEST(SubdivPatchSet, HolesKeepPtexIdsButHaveNoSurface) {
    const PolygonMesh grid = gridWithHole();
    const PatchSet set = buildPatchSet(grid);
    ASSERT_EQ(set.ptexFaceCount, 16);
    EXPECT_EQ(set.ptexToBaseFace[5], 5);
    EXPECT_EQ(set.faceVertexOffsets[5], set.faceVertexOffsets[6]);
    for (int patch = 0; patch < set.patchCount(); ++patch) EXPECT_NE(set.patchParam(patch).GetFaceId(), 5);
    const LimitEvaluator evaluator(grid);
    EXPECT_FALSE(evaluator.hasSurface(5, 0.5f, 0.5f));
    EXPECT_TRUE(evaluator.hasSurface(4, 0.5f, 0.5f));
    // Its neighbours still feel it: the hole's vertices shape the surface around it.
    for (int f : {4, 6}) EXPECT_GT(set.faceVertexOffsets[f + 1] - set.faceVertexOffsets[f], 9);
}

TEST(SubdivPatchSet, PointsFollowMovedCage) {
    // Topology is fixed at build time; positions are an argument everywhere.
    PolygonMesh sphere = cubeCage(3, true);
    const PatchSet set = buildPatchSet(sphere);
    const LimitEvaluator evaluator(sphere);
    std::vector<glm::vec3> moved = sphere.positions;
    for (glm::vec3& p : moved) p = 2.0f * p + glm::vec3(1.0f, -2.0f, 0.5f);
    const std::vector<glm::vec3> points = evaluatePoints(set, moved);
    for (int f : {0, 17, 53}) {
        const LimitSample a = evaluator.evaluate(f, 0.3f, 0.7f, sphere.positions);
        const LimitSample b = evaluator.evaluate(f, 0.3f, 0.7f, moved);
        expectNear(b.position, 2.0f * a.position + glm::vec3(1.0f, -2.0f, 0.5f), 1e-5f, "affine P");
        expectNear(b.dPdu, 2.0f * a.dPdu, 1e-5f, "affine dPdu");
        expectNear(evaluatePatchSet(set, points, {f, 0.3f, 0.7f}).position, b.position, 1e-5f, "patch set");
    }
}

TEST(SubdivPatchSet, PositionWeightsAreTheEvaluatedLimitOnce) {
    // The limit position as weights on the base vertices (what the limit fit's rows hold), each
    // vertex once, at regular points and at extraordinary corners of a creased cage.
    const PolygonMesh cage = mesh::readObj(test::assetPath("osd-shapes/catmark_cube_creases1.obj"));
    const LimitEvaluator evaluator(cage);
    for (int f = 0; f < evaluator.ptexFaceCount(); f += 5)
        for (const glm::vec2 uv : {glm::vec2(0.0f), glm::vec2(0.3f, 0.7f), glm::vec2(1.0f, 0.5f)}) {
            if (!evaluator.hasSurface(f, uv.x, uv.y)) continue;
            const auto weights = evaluator.positionWeights(f, uv.x, uv.y);
            std::set<int> vertices;
            glm::dvec3 weighted(0.0);
            for (const auto& [vertex, weight] : weights) {
                EXPECT_TRUE(vertices.insert(vertex).second) << "face " << f << ": vertex " << vertex << " twice";
                weighted += weight * glm::dvec3(cage.positions[size_t(vertex)]);
            }
            expectNear(glm::vec3(weighted), evaluator.evaluate(f, uv.x, uv.y, cage.positions).position, 1e-5f,
                       "weights");
        }
}

TEST(SubdivPatchSet, OsdShapesBuildAndMatchLimitStencils) {
    // OpenSubdiv's regression cages: non-manifold edges, repeated vertices, a valence-66 pole,
    // holes, every crease and boundary rule. Each must build and match OpenSubdiv's limit
    // stencils, or fail with a subdfit::Error (none does today).
    SUBDFIT_REQUIRE_SHARED(folder, "osd-shapes/catmark_cube.obj");
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder.parent_path()))
        if (entry.path().extension() == ".obj") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    EXPECT_EQ(files.size(), 58u);
    int built = 0;
    for (const std::filesystem::path& file : files) {
        SCOPED_TRACE(file.filename().string());
        try {
            const PolygonMesh cage = mesh::readObj(file);
            const PatchSet set = buildPatchSet(cage);
            const std::vector<glm::vec3> points = evaluatePoints(set, cage.positions);
            for (const glm::vec3& p : points) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
            std::vector<Location> locations;
            for (int f = 0; f < set.ptexFaceCount; ++f)
                if (set.faceVertexOffsets[f] < set.faceVertexOffsets[f + 1])
                    for (float u : {0.013f, 0.61f}) locations.push_back({f, u, 0.994f - u});
            const std::vector<LimitSample> reference = limitStencilReference(cage, 3, locations);
            ASSERT_EQ(reference.size(), locations.size());
            for (std::size_t i = 0; i < locations.size(); ++i) {
                const LimitSample s = evaluatePatchSet(set, points, locations[i]);
                expectNear(s.position, reference[i].position, 1e-5f, "P");
                expectNear(s.dPdu, reference[i].dPdu, 1e-4f, "dPdu");
            }
            ++built;
        } catch (const Error& e) {
            ADD_FAILURE() << "rejected: " << e.what();
        }
    }
    EXPECT_EQ(built, 58);
}

// Worst and mean distance between `cage`'s limit surfaces at two isolation levels, in mean edges.
struct LevelShift {
    double worst = 0.0, mean = 0.0;
};

LevelShift limitShift(const PolygonMesh& cage, int shallow, int deep) {
    double edge = 0.0;
    for (std::size_t t = 0; t < cage.faceIndices.size(); t += 3)
        edge += glm::length(cage.positions[cage.faceIndices[t]] - cage.positions[cage.faceIndices[t + 1]]);
    edge /= double(cage.faceCount());
    const LimitEvaluator a(cage, {.isolationLevel = shallow}), b(cage, {.isolationLevel = deep});
    EXPECT_EQ(a.ptexFaceCount(), b.ptexFaceCount());
    LevelShift shift;
    int samples = 0;
    for (int f = 0; f < b.ptexFaceCount(); f += 7)
        for (float u : kSampleCoords)
            for (float v : kSampleCoords) {
                const double d = glm::length(a.evaluate(f, u, v, cage.positions).position -
                                             b.evaluate(f, u, v, cage.positions).position);
                shift.worst = std::max(shift.worst, d / edge);
                shift.mean += d / edge;
                ++samples;
            }
    shift.mean /= samples;
    return shift;
}

// A bumpy sphere of 2 646 quads (`quads`) and its 5 292 triangles: extraordinary vertices
// everywhere, as on a decimated cage.
struct BumpyCages {
    PolygonMesh quads, triangles;
};

BumpyCages bumpyCages() {
    BumpyCages cages{cubeCage(21, true), {}};
    for (glm::vec3& p : cages.quads.positions)
        p *= 1.0f + 0.03f * std::sin(9.0f * p.x) * std::cos(7.0f * p.y + 3.0f * p.z);
    cages.triangles = cages.quads;
    cages.triangles.faceSizes.clear();
    cages.triangles.faceIndices.clear();
    for (std::size_t q = 0; q < cages.quads.faceIndices.size(); q += 4) {
        const int* v = &cages.quads.faceIndices[q];
        addFace(cages.triangles, {v[0], v[1], v[2]});
        addFace(cages.triangles, {v[0], v[2], v[3]});
    }
    return cages;
}

TEST(SubdivPatchSet, DenseCagesAreDrawnShallowerWithinAFractionOfAPixel) {
    const auto [quads, triangles] = bumpyCages();
    ASSERT_GT(triangles.faceCount(), kVeryDenseCageFaces);
    ASSERT_GT(quads.faceCount(), kDenseCageFaces);
    ASSERT_LE(quads.faceCount(), kVeryDenseCageFaces);
    EXPECT_EQ(drawingIsolationLevel(triangles), 1);
    EXPECT_EQ(drawingIsolationLevel(quads), 2);
    EXPECT_EQ(drawingIsolationLevel(cubeCage(8, true)), 3);  // a light cage keeps level 3
    PolygonMesh creased = triangles;
    creased.tags.creases.push_back({.v0 = triangles.faceIndices[0], .v1 = triangles.faceIndices[1], .sharpness = 1.5f});
    EXPECT_EQ(drawingIsolationLevel(creased), 2);  // a crease of sharpness 1.5 needs the second level
    creased.tags.creases.back().sharpness = 2.5f;
    EXPECT_EQ(drawingIsolationLevel(creased), 3);  // one that needs the third level keeps it
    // Infinitely sharp tags never decay: no level resolves them, and none is asked for.
    creased.tags.creases.back().sharpness = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE;
    creased.tags.corners.push_back(
        {.vertex = triangles.faceIndices[5], .sharpness = OpenSubdiv::Sdc::Crease::SHARPNESS_INFINITE});
    EXPECT_EQ(drawingIsolationLevel(creased), 1);

    // What the shallower levels change is a fraction of a pixel at 256², where an edge spans about
    // 5 pixels on an 8 000-face cage (so ~6 at kVeryDenseCageFaces, ~10 at kDenseCageFaces): at
    // worst half a pixel, on average a twentieth. The shift sits near the extraordinary vertices,
    // where the end caps are.
    const LevelShift level2 = limitShift(triangles, 2, 3), level1 = limitShift(triangles, 1, 3);
    EXPECT_LT(level2.worst, 0.5 / 10.0);
    EXPECT_LT(level2.mean, 0.05 / 10.0);
    EXPECT_LT(level1.worst, 0.5 / 6.0);
    EXPECT_LT(level1.mean, 0.05 / 6.0);
    std::printf("vs level 3, in mean edges: level 2 worst %.2f %%, mean %.3f %%; level 1 worst %.2f %%, mean %.3f %%\n",
                100 * level2.worst, 100 * level2.mean, 100 * level1.worst, 100 * level1.mean);
}

TEST(LimitEvaluator, EvaluatesACageAtTheLevelItIsDrawnAt) {
    // What a bake displaces and an export tessellates is the surface a fit renders.
    const PolygonMesh dense = bumpyCages().triangles;
    const LimitEvaluator drawn(dense), level1(dense, {.isolationLevel = 1}), level3(dense, {.isolationLevel = 3});
    double apartFromLevel3 = 0.0;
    for (int f = 0; f < drawn.ptexFaceCount(); f += 5)
        for (float u : kSampleCoords)
            for (float v : kSampleCoords) {
                const glm::vec3 p = drawn.evaluate(f, u, v, dense.positions).position;
                ASSERT_EQ(p, level1.evaluate(f, u, v, dense.positions).position) << "face " << f;
                apartFromLevel3 = std::max(apartFromLevel3,
                                           double(glm::length(p - level3.evaluate(f, u, v, dense.positions).position)));
            }
    EXPECT_GT(apartFromLevel3, 0.0);  // the end caps of level 1 are not level 3's
    const PolygonMesh light = cubeCage(8, true);
    const LimitEvaluator lightDrawn(light), lightLevel3(light, {.isolationLevel = 3});
    EXPECT_EQ(lightDrawn.evaluate(0, 0.3f, 0.6f, light.positions).position,
              lightLevel3.evaluate(0, 0.3f, 0.6f, light.positions).position);
}

TEST(LimitEvaluator, PatchPointsGiveTheSameBitsAsTheBase) {
    // Bakes and limit fits evaluate thousands of samples of one position set through the points
    // the patches read, each stencil applied once: the same samples, bit for bit, on a creased
    // cage with extraordinary corners and on a dense triangle cage (Gregory end caps), moved.
    const PolygonMesh creased = mesh::readObj(test::assetPath("osd-shapes/catmark_cube_creases1.obj"));
    for (const PolygonMesh& cage : {creased, bumpyCages().triangles}) {
        const LimitEvaluator evaluator(cage);
        std::vector<glm::vec3> moved = cage.positions;
        for (size_t k = 0; k < moved.size(); ++k) moved[k] += 0.01f * glm::vec3(float(k % 7), float(k % 3), 1.0f);
        for (const std::vector<glm::vec3>& positions : {cage.positions, moved}) {
            const std::vector<glm::dvec3> points = evaluator.patchPoints(positions);
            int compared = 0;
            const int stride = evaluator.ptexFaceCount() > 100 ? 3 : 1;
            for (int f = 0; f < evaluator.ptexFaceCount(); f += stride)
                for (float u : kSampleCoords)
                    for (float v : kSampleCoords) {
                        if (!evaluator.hasSurface(f, u, v)) continue;
                        const LimitSample a = evaluator.evaluate(f, u, v, positions);
                        const LimitSample b = evaluator.evaluate(f, u, v, points);
                        ASSERT_EQ(a.position, b.position) << "face " << f;
                        ASSERT_EQ(a.dPdu, b.dPdu) << "face " << f;
                        ASSERT_EQ(a.dPdv, b.dPdv) << "face " << f;
                        ++compared;
                    }
            EXPECT_GE(compared, 150);  // the cube's 6 faces at 25 samples each, or more
        }
    }
}

}  // namespace
}  // namespace subdfit::subdiv
