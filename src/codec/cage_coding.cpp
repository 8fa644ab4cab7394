#include "codec/cage_coding.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <zstd.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "codec/subd_format.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_validation.h"
#include "util/disjoint_sets.h"
#include "util/error.h"

namespace subdfit::codec {
namespace {

// kDraco's polygon marks are a byte per triangle; kDracoPairs' are coded by pairMarks(),
// kDracoOnce's by onceMarks().
enum Coding : std::uint8_t { kPlain = 0, kDraco = 1, kDracoPairs = 2, kDracoOnce = 3 };
// Draco's speed 1: its valence connectivity coder and multi-parallelogram position prediction,
// 1-6 % smaller than speed 5 on decimated cages (docs/results.md, where a cage's bytes go).
constexpr int kDracoSpeed = 1;

using Cell = std::array<std::int32_t, 3>;  // a quantised position

std::uint64_t cellKey(const Cell& c) {
    return std::uint64_t(std::uint32_t(c[0])) | std::uint64_t(std::uint32_t(c[1])) << 21 |
           std::uint64_t(std::uint32_t(c[2])) << 42;
}

// Bytes of `raw` zstd-packed as asset.subd packs a section.
std::size_t zstdSize(std::span<const unsigned char> raw) {
    std::vector<unsigned char> out(ZSTD_compressBound(raw.size()));
    const std::size_t size = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), kSubdZstdLevel);
    if (ZSTD_isError(size)) throw Error(std::string("zstd: ") + ZSTD_getErrorName(size));
    return size;
}

std::int64_t squaredLength(const Cell& a, const Cell& b) {
    std::int64_t length = 0;
    for (size_t i = 0; i < 3; ++i) length += std::int64_t(a[i] - b[i]) * (a[i] - b[i]);
    return length;
}

std::uint64_t edgeKey(int from, int to) { return std::uint64_t(std::uint32_t(from)) << 32 | std::uint32_t(to); }

// Three consecutive corners of a face: which face (and where in it) they are, even where two
// faces share a directed edge (a flipped neighbour, a non-manifold edge).
std::uint64_t cornerKey(int a, int b, int c) {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int v : {a, b, c}) h = (h ^ std::uint64_t(std::uint32_t(v))) * 0xff51afd7ed558ccdull;
    return h;
}

// Positions on a grid of 2^bits − 1 steps over the cage's bounding cube.
struct Grid {
    glm::vec3 origin{0.0f};
    float extent = 1.0f;
    int bits = 16;

    float levels() const { return float((1u << bits) - 1u); }
    Cell cell(const glm::vec3& p) const {
        Cell c;
        for (int a = 0; a < 3; ++a)
            c[size_t(a)] = std::int32_t(std::lround(std::clamp((p[a] - origin[a]) / extent, 0.0f, 1.0f) * levels()));
        return c;
    }
    glm::vec3 position(const Cell& c) const {
        glm::vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = origin[a] + float(c[size_t(a)]) / levels() * extent;
        return p;
    }
};

Grid gridFor(const std::vector<glm::vec3>& positions, int bits) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const auto& p : positions) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const float extent = std::max({high.x - low.x, high.y - low.y, high.z - low.z});
    return {.origin = positions.empty() ? glm::vec3(0.0f) : low, .extent = extent > 0.0f ? extent : 1.0f, .bits = bits};
}

// Draco's decoder makes one vertex of two on one grid cell (codec/cage_coding.h): where a coarse
// grid puts two there, the later moves to the free neighbouring cell nearest its position, one
// step away, about the quantisation's own error. Each cell's vertex then, or nothing when a vertex
// finds no free cell.
std::optional<std::unordered_map<std::uint64_t, int>> separateCells(std::vector<Cell>& cells,
                                                                    const std::vector<glm::vec3>& positions,
                                                                    const Grid& grid) {
    std::unordered_map<std::uint64_t, int> vertexOfCell;
    const auto top = std::int32_t(grid.levels());
    for (size_t v = 0; v < cells.size(); ++v) {
        if (vertexOfCell.emplace(cellKey(cells[v]), int(v)).second) continue;
        const glm::vec3 at = (positions[v] - grid.origin) / grid.extent * grid.levels();
        std::optional<Cell> nearest;
        float nearestDistance = 0.0f;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const Cell c{cells[v][0] + dx, cells[v][1] + dy, cells[v][2] + dz};
                    if (std::any_of(c.begin(), c.end(), [&](std::int32_t i) { return i < 0 || i > top; }) ||
                        vertexOfCell.count(cellKey(c)))
                        continue;
                    const float d = glm::length(glm::vec3(float(c[0]), float(c[1]), float(c[2])) - at);
                    if (!nearest || d < nearestDistance) nearest = c, nearestDistance = d;
                }
        if (!nearest) return std::nullopt;
        cells[v] = *nearest;
        vertexOfCell.emplace(cellKey(cells[v]), int(v));
    }
    return vertexOfCell;
}

void writeGrid(const Grid& grid, ByteWriter& out) {
    for (float c : {grid.origin.x, grid.origin.y, grid.origin.z, grid.extent}) out.put<float>(c);
    out.put<std::uint8_t>(std::uint8_t(grid.bits));
}

Grid readGrid(ByteReader& in) {
    Grid grid;
    for (int a = 0; a < 3; ++a) grid.origin[a] = in.get<float>();
    grid.extent = in.get<float>();
    grid.bits = in.get<std::uint8_t>();
    if (grid.bits < 1 || grid.bits > 16 || !(grid.extent > 0.0f) || !std::isfinite(grid.extent) ||
        !std::isfinite(grid.origin.x + grid.origin.y + grid.origin.z))
        throw Error(in.what() + ": bad position quantisation");
    return grid;
}

// --- OpenSubdiv tags, in the decoded numbering --------------------------------------------

void writeTags(const mesh::SubdivisionTags& t, const CageCorrespondence& to, ByteWriter& out) {
    for (int value : {int(t.boundary), t.faceVaryingBoundary, int(t.creaseMethod), int(t.triangles)})
        out.put<std::uint8_t>(std::uint8_t(value));
    // A tag repeated in the source (an OBJ may list an edge twice) is written once, its first
    // sharpness: the reader refuses repeats.
    std::unordered_set<std::uint64_t> tagged;
    std::vector<mesh::Crease> creases;
    for (const auto& c : t.creases) {
        const int a = to.vertex[size_t(c.v0)], b = to.vertex[size_t(c.v1)];
        if (tagged.insert(edgeKey(std::min(a, b), std::max(a, b))).second) creases.push_back({a, b, c.sharpness});
    }
    out.putVarint(creases.size());
    for (const auto& c : creases) {
        out.putVarint(std::uint64_t(c.v0));
        out.putVarint(std::uint64_t(c.v1));
        out.put<float>(c.sharpness);
    }
    tagged.clear();
    std::vector<mesh::Corner> corners;
    for (const auto& c : t.corners)
        if (tagged.insert(std::uint64_t(to.vertex[size_t(c.vertex)])).second)
            corners.push_back({to.vertex[size_t(c.vertex)], c.sharpness});
    out.putVarint(corners.size());
    for (const auto& c : corners) {
        out.putVarint(std::uint64_t(c.vertex));
        out.put<float>(c.sharpness);
    }
    tagged.clear();
    std::vector<int> holes;
    for (int face : t.holes)
        if (tagged.insert(std::uint64_t(to.face[size_t(face)])).second) holes.push_back(to.face[size_t(face)]);
    out.putVarint(holes.size());
    for (int face : holes) out.putVarint(std::uint64_t(face));
}

void readTags(ByteReader& in, mesh::PolygonMesh& cage) {
    const std::size_t vertices = cage.positions.size(), faces = cage.faceSizes.size();
    auto& t = cage.tags;
    const int boundary = in.get<std::uint8_t>(), faceVarying = in.get<std::uint8_t>(), method = in.get<std::uint8_t>(),
              triangles = in.get<std::uint8_t>();
    if (boundary > 2 || faceVarying > 5 || method > 1 || triangles > 1)
        throw Error(in.what() + ": unknown subdivision rule");
    t.boundary = mesh::BoundaryInterpolation(boundary);
    t.faceVaryingBoundary = faceVarying;
    t.creaseMethod = mesh::CreaseMethod(method);
    t.triangles = mesh::TriangleSubdivision(triangles);
    t.hasBoundary = t.hasFaceVaryingBoundary = t.hasCreaseMethod = t.hasTriangles = true;
    // Each edge, vertex and face is tagged at most once: repeats add nothing but work (50 M
    // copies of one crease fit in 27 KB of zstd).
    std::unordered_set<std::uint64_t> tagged;
    auto once = [&](std::uint64_t key, const char* what) {
        if (!tagged.insert(key).second) throw Error(in.what() + ": duplicate " + what);
    };
    t.creases.resize(in.getCount(6, "crease"));
    for (auto& c : t.creases) {
        c.v0 = in.getIndex(vertices, "crease vertex");
        c.v1 = in.getIndex(vertices, "crease vertex");
        c.sharpness = in.get<float>();
        once(edgeKey(std::min(c.v0, c.v1), std::max(c.v0, c.v1)), "crease");
    }
    tagged.clear();
    t.corners.resize(in.getCount(5, "corner"));
    for (auto& c : t.corners) {
        c.vertex = in.getIndex(vertices, "corner vertex");
        c.sharpness = in.get<float>();
        once(std::uint64_t(c.vertex), "corner");
    }
    tagged.clear();
    t.holes.resize(in.getCount(1, "hole"));
    for (int& face : t.holes) {
        face = in.getIndex(faces, "hole face");
        once(std::uint64_t(face), "hole");
    }
}

// --- plain: positions as they are, indices as deltas ---------------------------------------

void writePlain(const mesh::PolygonMesh& cage, const Grid& grid, ByteWriter& out) {
    std::vector<Cell> cells;
    for (const auto& p : cage.positions) cells.push_back(grid.cell(p));
    for (int axis = 0; axis < 3; ++axis)
        for (const Cell& c : cells) out.put<std::uint16_t>(std::uint16_t(c[size_t(axis)]));
    for (int size : cage.faceSizes) out.putVarint(std::uint64_t(size));
    int previous = 0;
    for (int index : cage.faceIndices) {
        out.putSigned(std::int64_t(index) - previous);
        previous = index;
    }
}

void readPlain(ByteReader& in, const Grid& grid, std::size_t vertices, std::size_t faces, mesh::PolygonMesh& cage) {
    std::vector<Cell> cells(vertices);
    for (int axis = 0; axis < 3; ++axis)
        for (Cell& c : cells) c[size_t(axis)] = in.get<std::uint16_t>();
    for (const Cell& c : cells) cage.positions.push_back(grid.position(c));
    cage.faceSizes.resize(faces);
    std::uint64_t corners = 0;
    for (int& size : cage.faceSizes) {
        size = in.getIndex(std::uint64_t(mesh::kMaxCageFaceSize) + 1, "face size");
        corners += std::uint64_t(size);
    }
    if (corners > in.remaining()) throw Error(in.what() + ": truncated face indices");
    cage.faceIndices.resize(corners);
    std::int64_t previous = 0;
    for (int& index : cage.faceIndices) {
        previous += in.getSigned();
        if (previous < 0 || previous >= std::int64_t(vertices)) throw Error(in.what() + ": face index out of range");
        index = int(previous);
    }
}

// --- Draco: fan triangles, edgebreaker-coded ------------------------------------------------

// Triangles over distinct quantised positions, as the decoder sees them.
struct CellTriangles {
    std::vector<Cell> cells;   // one per vertex, in Draco's point order (equal cells merged)
    std::vector<int> corners;  // 3 per triangle
};

std::vector<unsigned char> encodeDracoTriangles(const std::vector<Cell>& cells, const std::vector<int>& corners) {
    draco::Mesh mesh;
    mesh.set_num_points(std::uint32_t(cells.size()));
    mesh.SetNumFaces(corners.size() / 3);
    for (size_t t = 0; t < corners.size() / 3; ++t)
        mesh.SetFace(draco::FaceIndex(std::uint32_t(t)), {draco::PointIndex(std::uint32_t(corners[3 * t])),
                                                          draco::PointIndex(std::uint32_t(corners[3 * t + 1])),
                                                          draco::PointIndex(std::uint32_t(corners[3 * t + 2]))});
    draco::GeometryAttribute attribute;
    attribute.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_INT32, false, sizeof(Cell), 0);
    const int id = mesh.AddAttribute(attribute, true, mesh.num_points());
    for (std::uint32_t p = 0; p < mesh.num_points(); ++p)
        mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(p), cells[p].data());
    draco::Encoder encoder;
    encoder.SetSpeedOptions(kDracoSpeed, kDracoSpeed);
    encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
    if (!status.ok()) throw Error("Draco could not encode the cage: " + status.error_msg_string());
    return {buffer.data(), buffer.data() + buffer.size()};
}

CellTriangles decodeDracoTriangles(std::span<const unsigned char> bytes, const Grid& grid, const std::string& what) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) throw Error(what + ": corrupt Draco cage: " + decoded.status().error_msg_string());
    const draco::Mesh& mesh = *decoded.value();
    if (std::int64_t(mesh.num_points()) > mesh::kMaxVertices || std::int64_t(mesh.num_faces()) > mesh::kMaxTriangles)
        throw Error(what + ": more vertices or faces than subdfit reads");
    const draco::PointAttribute* positions = mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
    if (!positions || positions->num_components() != 3) throw Error(what + ": the Draco cage has no positions");
    CellTriangles out;
    std::vector<int> vertexOfPoint(mesh.num_points());
    std::unordered_map<std::uint64_t, int> vertexOfCell;
    const auto top = std::int32_t(grid.levels());
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
        Cell c;
        if (!positions->ConvertValue<std::int32_t>(positions->mapped_index(p), 3, c.data()))
            throw Error(what + ": unreadable Draco positions");
        if (std::any_of(c.begin(), c.end(), [&](std::int32_t v) { return v < 0 || v > top; }))
            throw Error(what + ": a Draco position off the quantisation grid");
        // Edgebreaker splits a vertex it cannot walk around into several points: one again here.
        const auto [at, added] = vertexOfCell.emplace(cellKey(c), int(out.cells.size()));
        if (added) out.cells.push_back(c);
        vertexOfPoint[p.value()] = at->second;
    }
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) out.corners.push_back(vertexOfPoint[mesh.face(f)[k].value()]);
    return out;
}

// Polygons from triangles joined across the edges `interior` marks (bit k: the edge from corner
// k to k + 1). Polygons come in the order of their first triangle and start at the first
// corner of that triangle whose edge is on the polygon's boundary.
void polygonsFromTriangles(const std::vector<int>& corners, std::span<const unsigned char> interior,
                           mesh::PolygonMesh& cage, const std::string& what) {
    const size_t triangles = corners.size() / 3;
    auto isInterior = [&](size_t t, int k) { return (interior[t] >> k) & 1; };
    auto from = [&](size_t t, int k) { return corners[3 * t + size_t(k)]; };
    auto to = [&](size_t t, int k) { return corners[3 * t + size_t((k + 1) % 3)]; };

    DisjointSets polygons{int(triangles)};  // a polygon's root is its first triangle
    std::unordered_map<std::uint64_t, int> interiorEdges;
    for (size_t t = 0; t < triangles; ++t) {
        if (interior[t] >= 7) throw Error(what + ": bad polygon mark");
        for (int k = 0; k < 3; ++k)
            if (isInterior(t, k) && !interiorEdges.emplace(edgeKey(from(t, k), to(t, k)), int(t)).second)
                throw Error(what + ": an interior edge twice");
    }
    for (const auto& [key, t] : interiorEdges) {
        const auto twin = interiorEdges.find(edgeKey(int(key & 0xffffffffu), int(key >> 32)));
        if (twin == interiorEdges.end()) throw Error(what + ": an interior edge without its twin");
        polygons.join(t, twin->second);
    }
    // Each polygon's boundary as vertex -> next vertex, then walked from its start.
    std::vector<std::vector<size_t>> members(triangles);
    for (size_t t = 0; t < triangles; ++t) members[size_t(polygons.find(int(t)))].push_back(t);
    std::unordered_map<int, int> next;
    for (size_t first = 0; first < triangles; ++first) {
        if (members[first].empty()) continue;
        next.clear();
        int start = -1;
        size_t edges = 0;
        for (size_t t : members[first])
            for (int k = 0; k < 3; ++k) {
                if (isInterior(t, k)) continue;
                if (!next.emplace(from(t, k), to(t, k)).second) throw Error(what + ": a polygon visits a vertex twice");
                if (start < 0) start = from(t, k);
                ++edges;
            }
        if (edges > size_t(mesh::kMaxCageFaceSize)) throw Error(what + ": a polygon too large");
        int v = start;
        for (size_t k = 0; k < edges; ++k) {
            cage.faceIndices.push_back(v);
            const auto it = next.find(v);
            if (it == next.end()) throw Error(what + ": a polygon's boundary is not a loop");
            v = it->second;
        }
        if (v != start) throw Error(what + ": a polygon's boundary is not one loop");
        cage.faceSizes.push_back(int(edges));
    }
}

// The k for which triangle t's edge from corner k to k + 1 is an edge of triangle u (run the other
// way), where exactly one is; else -1.
int sharedEdge(const std::vector<int>& corners, size_t t, size_t u) {
    int shared = -1;
    for (int k = 0; k < 3; ++k) {
        const int a = corners[3 * t + size_t(k)], b = corners[3 * t + size_t((k + 1) % 3)];
        for (int j = 0; j < 3; ++j)
            if (corners[3 * u + size_t(j)] == b && corners[3 * u + size_t((j + 1) % 3)] == a) {
                if (shared >= 0) return -1;
                shared = k;
            }
    }
    return shared;
}

// The longest edge of triangle t (its first of equal ones): in a quad split in two, the
// diagonal, the one edge inside the polygon.
int longestEdge(const std::vector<Cell>& cells, const std::vector<int>& corners, size_t t) {
    int longest = 0;
    std::int64_t most = -1;
    for (int k = 0; k < 3; ++k) {
        const std::int64_t length = squaredLength(cells[size_t(corners[3 * t + size_t(k)])],
                                                  cells[size_t(corners[3 * t + size_t((k + 1) % 3)])]);
        if (length > most) most = length, longest = k;
    }
    return longest;
}

// Per quad, the corner (0 or 1) its diagonal should leave from so that neighbouring quads'
// diagonals run parallel, as in a grid split all one way: across a shared edge the two diagonals
// touch its two different ends. Spread from each unvisited quad breadth first; -1 for other faces.
// Draco's valence coder and parallelogram prediction code such a split cheapest (on OpenSubdiv's
// bishop with its quads' first corners scattered, 13 % more bytes than split all one way).
std::vector<int> parallelDiagonals(const mesh::PolygonMesh& cage) {
    std::vector<int> first(size_t(cage.faceCount()) + 1, 0);
    for (int f = 0; f < cage.faceCount(); ++f) first[size_t(f) + 1] = first[size_t(f)] + cage.faceSizes[size_t(f)];
    std::unordered_map<std::uint64_t, std::vector<int>> quadsOfEdge;
    const auto undirected = [](int a, int b) { return edgeKey(std::min(a, b), std::max(a, b)); };
    for (int f = 0; f < cage.faceCount(); ++f)
        if (cage.faceSizes[size_t(f)] == 4)
            for (int k = 0; k < 4; ++k)
                quadsOfEdge[undirected(cage.faceIndices[size_t(first[size_t(f)] + k)],
                                       cage.faceIndices[size_t(first[size_t(f)] + (k + 1) % 4)])]
                    .push_back(f);
    std::vector<int> apex(size_t(cage.faceCount()), -1), queue;
    for (int seed = 0; seed < cage.faceCount(); ++seed) {
        if (cage.faceSizes[size_t(seed)] != 4 || apex[size_t(seed)] >= 0) continue;
        apex[size_t(seed)] = 0;
        queue.assign(1, seed);
        for (size_t next = 0; next < queue.size(); ++next) {
            const int f = queue[next];
            const int* v = &cage.faceIndices[size_t(first[size_t(f)])];
            for (int k = 0; k < 4; ++k) {
                const auto& shared = quadsOfEdge[undirected(v[k], v[(k + 1) % 4])];
                if (shared.size() != 2) continue;
                const int g = shared[0] == f ? shared[1] : shared[0];
                if (apex[size_t(g)] >= 0) continue;
                // The end of edge k that f's diagonal does not touch; g's diagonal leaves from it.
                const int other = k % 2 == apex[size_t(f)] ? v[(k + 1) % 4] : v[k];
                const int* w = &cage.faceIndices[size_t(first[size_t(g)])];
                for (int j = 0; j < 4; ++j)
                    if (w[j] == other) apex[size_t(g)] = j % 2;
                if (apex[size_t(g)] < 0) continue;
                queue.push_back(g);
            }
        }
    }
    return apex;
}

// The polygon marks of a quad-dominant cage cost a byte per triangle as they are, where a
// triangle of a quad has one mark, nearly always on its longest edge: each triangle's 2-bit
// symbol, four to a byte (low bits first), says 0: no edge inside a polygon; 1: its longest
// edge alone; 2: the one edge it shares with the triangle before it, alone (Draco lays many
// quads' triangles one after the other); 3: other marks, given whole in a byte after the symbols,
// in triangle order.
enum PairSymbol : unsigned { kAlone = 0, kLongest = 1, kWithPrevious = 2, kOtherMarks = 3 };

std::vector<unsigned char> pairMarks(const CellTriangles& mesh, std::span<const unsigned char> interior) {
    const size_t triangles = interior.size();
    std::vector<unsigned char> symbols((triangles + 3) / 4, 0), others;
    for (size_t t = 0; t < triangles; ++t) {
        const int previous = t > 0 ? sharedEdge(mesh.corners, t, t - 1) : -1;
        unsigned symbol = kOtherMarks;
        if (interior[t] == 0) symbol = kAlone;
        else if (interior[t] == 1u << longestEdge(mesh.cells, mesh.corners, t)) symbol = kLongest;
        else if (previous >= 0 && interior[t] == 1u << previous) symbol = kWithPrevious;
        if (symbol == kOtherMarks) others.push_back(interior[t]);
        symbols[t / 4] |= std::uint8_t(symbol << (2 * (t % 4)));
    }
    symbols.insert(symbols.end(), others.begin(), others.end());
    return symbols;
}

std::vector<unsigned char> marksFromPairs(const CellTriangles& mesh, ByteReader& in) {
    const size_t triangles = mesh.corners.size() / 3;
    const auto symbols = in.take((triangles + 3) / 4);
    std::vector<unsigned char> interior(triangles, 0);
    for (size_t t = 0; t < triangles; ++t) {
        const unsigned symbol = (symbols[t / 4] >> (2 * (t % 4))) & 3u;
        if (symbol == kOtherMarks) interior[t] = in.get<std::uint8_t>();
        else if (symbol == kLongest) interior[t] = std::uint8_t(1u << longestEdge(mesh.cells, mesh.corners, t));
        else if (symbol == kWithPrevious) {
            const int k = t > 0 ? sharedEdge(mesh.corners, t, t - 1) : -1;
            if (k < 0) throw Error(in.what() + ": a polygon mark pairs triangles that share no one edge");
            interior[t] = std::uint8_t(1u << k);
        }
    }
    return interior;
}

// Each triangle's neighbour across each of its edges (the triangle whose edge runs the other
// way), or -1 where there is none or more than one.
std::vector<std::array<int, 3>> neighbours(const std::vector<int>& corners) {
    const size_t triangles = corners.size() / 3;
    std::unordered_map<std::uint64_t, int> edgeOwner;  // directed edge -> 3 t + k, or -1 when repeated
    for (size_t t = 0; t < triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            const auto key = edgeKey(corners[3 * t + size_t(k)], corners[3 * t + size_t((k + 1) % 3)]);
            const auto [at, added] = edgeOwner.emplace(key, int(3 * t) + k);
            if (!added) at->second = -1;
        }
    std::vector<std::array<int, 3>> across(triangles, {-1, -1, -1});
    for (size_t t = 0; t < triangles; ++t)
        for (int k = 0; k < 3; ++k) {
            const int from = corners[3 * t + size_t(k)], to = corners[3 * t + size_t((k + 1) % 3)];
            const auto reversed = edgeOwner.find(edgeKey(to, from));
            if (reversed != edgeOwner.end() && edgeOwner.at(edgeKey(from, to)) >= 0)
                across[t][size_t(k)] = reversed->second;  // -1 where the other way is repeated
        }
    return across;
}

// Triangle t's edges in `added` marked on the triangles across them, as their twins.
void markTwins(const std::vector<std::array<int, 3>>& across, size_t t, unsigned added,
               std::vector<unsigned char>& marked) {
    for (int k = 0; k < 3; ++k)
        if ((added >> k) & 1u) {
            const int twin = across[t][size_t(k)];
            marked[size_t(twin / 3)] |= std::uint8_t(1u << (twin % 3));
        }
}

// Coding 3's marks name each interior edge once, in the first of its two triangles (in Draco's
// order): a quad's second triangle has its diagonal from the first and, nearly always, nothing
// more to say. Per triangle a 2-bit symbol over its edges to later triangles not yet marked,
// longest first: 0 none; 1 the longest alone; 2 the second longest alone; 3 those given in a byte
// after the symbols. The symbols of triangles that already have a marked edge are a stream of
// their own (nearly all 0), after the others', whose count comes first.
enum OnceSymbol : unsigned { kNoMore = 0, kFirst = 1, kSecond = 2, kGiven = 3 };

// Triangle t's edges to later triangles not yet marked, longest first.
std::vector<int> laterEdges(const CellTriangles& mesh, const std::vector<std::array<int, 3>>& across, size_t t,
                            unsigned marked) {
    std::vector<int> edges;
    for (int k = 0; k < 3; ++k)
        if (across[t][size_t(k)] / 3 > int(t) && !((marked >> k) & 1u)) edges.push_back(k);
    const auto length = [&](int k) {
        return squaredLength(mesh.cells[size_t(mesh.corners[3 * t + size_t(k)])],
                             mesh.cells[size_t(mesh.corners[3 * t + size_t((k + 1) % 3)])]);
    };
    std::stable_sort(edges.begin(), edges.end(), [&](int a, int b) { return length(a) > length(b); });
    return edges;
}

// The marks `interior` as coding 3, or nothing where some interior edge has no single twin.
std::optional<std::vector<unsigned char>> onceMarks(const CellTriangles& mesh,
                                                    std::span<const unsigned char> interior) {
    const size_t triangles = interior.size();
    const auto across = neighbours(mesh.corners);
    std::vector<unsigned char> marked(triangles, 0), given;
    std::vector<unsigned> fresh, known;  // the symbols of the two streams
    for (size_t t = 0; t < triangles; ++t) {
        const unsigned added = interior[t] & ~marked[t];
        const std::vector<int> later = laterEdges(mesh, across, t, marked[t]);
        unsigned reachable = 0;
        for (int k : later) reachable |= 1u << k;
        if (added & ~reachable) return std::nullopt;
        unsigned symbol = kGiven;
        if (added == 0) symbol = kNoMore;
        else if (!later.empty() && added == 1u << later[0]) symbol = kFirst;
        else if (later.size() > 1 && added == 1u << later[1]) symbol = kSecond;
        if (symbol == kGiven) given.push_back(std::uint8_t(added));
        (marked[t] ? known : fresh).push_back(symbol);
        markTwins(across, t, added, marked);
    }
    ByteWriter out;
    out.putVarint(fresh.size());
    for (const auto* stream : {&fresh, &known}) {
        std::vector<unsigned char> packed((stream->size() + 3) / 4, 0);
        for (size_t i = 0; i < stream->size(); ++i) packed[i / 4] |= std::uint8_t((*stream)[i] << (2 * (i % 4)));
        out.putBytes(packed);
    }
    out.putBytes(given);
    return std::move(out.bytes());
}

std::vector<unsigned char> marksFromOnce(const CellTriangles& mesh, ByteReader& in) {
    const size_t triangles = mesh.corners.size() / 3;
    const auto across = neighbours(mesh.corners);
    const size_t freshCount = in.getCount(0, "polygon mark");
    if (freshCount > triangles) throw Error(in.what() + ": more polygon marks than triangles");
    const auto fresh = in.take((freshCount + 3) / 4);
    const auto known = in.take((triangles - freshCount + 3) / 4);
    std::vector<unsigned char> marked(triangles, 0), interior(triangles, 0);
    size_t nextFresh = 0, nextKnown = 0;
    for (size_t t = 0; t < triangles; ++t) {
        unsigned symbol;
        if (marked[t]) {
            if (nextKnown == triangles - freshCount) throw Error(in.what() + ": polygon marks out of step");
            symbol = (known[nextKnown / 4] >> (2 * (nextKnown % 4))) & 3u;
            ++nextKnown;
        } else {
            if (nextFresh == freshCount) throw Error(in.what() + ": polygon marks out of step");
            symbol = (fresh[nextFresh / 4] >> (2 * (nextFresh % 4))) & 3u;
            ++nextFresh;
        }
        const std::vector<int> later = laterEdges(mesh, across, t, marked[t]);
        unsigned added = 0;
        if (symbol == kGiven) {
            added = in.get<std::uint8_t>();
            unsigned reachable = 0;
            for (int k : later) reachable |= 1u << k;
            if (added & ~reachable) throw Error(in.what() + ": a polygon mark on an edge it cannot name");
        } else if (symbol != kNoMore) {
            const size_t rank = symbol == kFirst ? 0 : 1;
            if (rank >= later.size()) throw Error(in.what() + ": a polygon mark on an edge it cannot name");
            added = 1u << later[rank];
        }
        interior[t] = std::uint8_t(marked[t] | added);
        markTwins(across, t, added, marked);
    }
    if (nextFresh != freshCount) throw Error(in.what() + ": polygon marks out of step");
    return interior;
}

// A Draco-coded cage: the coding of its marks, the bytes after the header, the correspondence.
struct DracoBody {
    Coding coding = kDracoOnce;
    std::vector<unsigned char> bytes;
    CageCorrespondence to;
};

// The Draco body, or nothing when Draco cannot carry this cage as it is (repeated or unused
// vertices, non-manifold pieces it would cut, ...).
std::optional<DracoBody> dracoBody(const mesh::PolygonMesh& cage, const Grid& grid) {
    std::vector<Cell> cells;
    for (const auto& p : cage.positions) cells.push_back(grid.cell(p));
    const auto separated = separateCells(cells, cage.positions, grid);
    if (!separated) return std::nullopt;
    const std::unordered_map<std::uint64_t, int>& vertexOfCell = *separated;
    // Fan triangles (v_a, v_a+k, v_a+k+1) from an apex a whose diagonals are no edge of the cage
    // and no other polygon's diagonal (the decoder tells a polygon's triangles by them).
    std::vector<int> corners, firstCorner;
    std::unordered_set<std::uint64_t> diagonals, edges;
    std::unordered_map<std::uint64_t, std::pair<int, int>> faceOfCorners;  // cornerKey -> (face, corner)
    for (int f = 0, first = 0; f < cage.faceCount(); first += cage.faceSizes[size_t(f)], ++f)
        for (int k = 0, n = cage.faceSizes[size_t(f)]; k < n; ++k)
            edges.insert(edgeKey(cage.faceIndices[size_t(first + k)], cage.faceIndices[size_t(first + (k + 1) % n)]));
    auto taken = [&](int a, int b) {
        return edges.count(edgeKey(a, b)) || edges.count(edgeKey(b, a)) || diagonals.count(edgeKey(a, b));
    };
    const std::vector<int> parallel = parallelDiagonals(cage);
    for (int f = 0, first = 0; f < cage.faceCount(); first += cage.faceSizes[size_t(f)], ++f) {
        const int n = cage.faceSizes[size_t(f)];
        const int* v = &cage.faceIndices[size_t(first)];
        firstCorner.push_back(first);
        for (int k = 0; k < n; ++k)
            if (!faceOfCorners.emplace(cornerKey(v[k], v[(k + 1) % n], v[(k + 2) % n]), std::pair{f, k}).second)
                return std::nullopt;
        int apex = 0;
        auto free = [&](int a) {
            for (int k = 2; k + 1 < n; ++k)
                if (taken(v[a], v[(a + k) % n])) return false;
            return true;
        };
        while (apex < n && !free(apex)) ++apex;
        if (apex == n) return std::nullopt;
        if (n == 4 && apex == 0 && parallel[size_t(f)] == 1 && free(1)) apex = 1;
        for (int k = 1; k + 1 < n; ++k)
            corners.insert(corners.end(), {v[apex], v[(apex + k) % n], v[(apex + k + 1) % n]});
        for (int k = 2; k + 1 < n; ++k)
            diagonals.insert({edgeKey(v[apex], v[(apex + k) % n]), edgeKey(v[(apex + k) % n], v[apex])});
    }

    std::vector<unsigned char> draco;
    CellTriangles decoded;
    try {
        draco = encodeDracoTriangles(cells, corners);
        decoded = decodeDracoTriangles(draco, grid, "Draco cage");
    } catch (const Error&) {
        return std::nullopt;
    }
    if (decoded.cells.size() != cells.size()) return std::nullopt;
    CageCorrespondence to{.vertex = std::vector<int>(cells.size(), -1),
                          .face = std::vector<int>(size_t(cage.faceCount()), -1),
                          .rotation = std::vector<int>(size_t(cage.faceCount()), 0)};
    std::vector<int> original(cells.size());
    for (size_t d = 0; d < decoded.cells.size(); ++d) {
        const auto it = vertexOfCell.find(cellKey(decoded.cells[d]));
        if (it == vertexOfCell.end()) return std::nullopt;
        original[d] = it->second;
        to.vertex[size_t(it->second)] = int(d);
    }
    std::vector<unsigned char> interior(decoded.corners.size() / 3, 0);
    for (size_t t = 0; t < interior.size(); ++t)
        for (int k = 0; k < 3; ++k)
            if (diagonals.count(edgeKey(original[size_t(decoded.corners[3 * t + size_t(k)])],
                                        original[size_t(decoded.corners[3 * t + size_t((k + 1) % 3)])])))
                interior[t] |= std::uint8_t(1u << k);
    mesh::PolygonMesh polygons;
    try {
        polygonsFromTriangles(decoded.corners, interior, polygons, "Draco cage");
    } catch (const Error&) {
        return std::nullopt;
    }
    if (polygons.faceCount() != cage.faceCount()) return std::nullopt;
    for (int f = 0, first = 0; f < polygons.faceCount(); first += polygons.faceSizes[size_t(f)], ++f) {
        const int n = polygons.faceSizes[size_t(f)];
        const int* v = &polygons.faceIndices[size_t(first)];
        const auto it = faceOfCorners.find(
            cornerKey(original[size_t(v[0])], original[size_t(v[1 % n])], original[size_t(v[2 % n])]));
        if (it == faceOfCorners.end()) return std::nullopt;
        const auto [face, corner] = it->second;
        if (cage.faceSizes[size_t(face)] != n || to.face[size_t(face)] >= 0) return std::nullopt;
        const int* c = &cage.faceIndices[size_t(firstCorner[size_t(face)])];
        for (int k = 0; k < n; ++k)
            if (original[size_t(v[k])] != c[(k + corner) % n]) return std::nullopt;
        to.face[size_t(face)] = f;
        to.rotation[size_t(face)] = corner;
    }
    // Coding 3's marks where they round-trip (every interior edge with one twin) and pack smaller
    // (a quad's), else coding 2's (a triangle cage's: no marks either way).
    const std::vector<unsigned char> pairs = pairMarks(decoded, interior);
    std::optional<std::vector<unsigned char>> once = onceMarks(decoded, interior);
    if (once) {
        ByteReader check(*once, "polygon marks");
        try {
            if (marksFromOnce(decoded, check) != std::vector<unsigned char>(interior.begin(), interior.end()) ||
                zstdSize(*once) >= zstdSize(pairs))
                once.reset();
        } catch (const Error&) {
            once.reset();
        }
    }
    ByteWriter body;
    body.putVarint(draco.size());
    body.putBytes(draco);
    body.putBytes(once ? *once : pairs);
    return DracoBody{.coding = once ? kDracoOnce : kDracoPairs, .bytes = std::move(body.bytes()), .to = std::move(to)};
}

void readDraco(ByteReader& in, int coding, const Grid& grid, std::size_t vertices, std::size_t faces,
               mesh::PolygonMesh& cage) {
    const auto draco = in.take(in.getCount(1, "Draco byte"));
    CellTriangles triangles = decodeDracoTriangles(draco, grid, in.what());
    if (triangles.cells.size() != vertices) throw Error(in.what() + ": the Draco cage has the wrong vertex count");
    for (const Cell& c : triangles.cells) cage.positions.push_back(grid.position(c));
    if (coding == kDracoOnce) polygonsFromTriangles(triangles.corners, marksFromOnce(triangles, in), cage, in.what());
    else if (coding == kDracoPairs)
        polygonsFromTriangles(triangles.corners, marksFromPairs(triangles, in), cage, in.what());
    else polygonsFromTriangles(triangles.corners, in.take(triangles.corners.size() / 3), cage, in.what());
    if (cage.faceSizes.size() != faces) throw Error(in.what() + ": the Draco cage has the wrong face count");
}

CageCorrespondence identity(const mesh::PolygonMesh& cage) {
    CageCorrespondence same{.vertex = std::vector<int>(size_t(cage.vertexCount())),
                            .face = std::vector<int>(size_t(cage.faceCount())),
                            .rotation = std::vector<int>(size_t(cage.faceCount()), 0)};
    std::iota(same.vertex.begin(), same.vertex.end(), 0);
    std::iota(same.face.begin(), same.face.end(), 0);
    return same;
}

}  // namespace

CageByteParts cageByteParts(const mesh::PolygonMesh& cage, int positionBits) {
    const auto packed = [](std::span<const unsigned char> raw) { return zstdSize(raw); };
    const CodedCage coded = encodeCage(cage, positionBits);
    CageByteParts parts{.draco = coded.bytes.at(0) != kPlain, .stored = packed(coded.bytes)};
    ByteWriter tags;
    writeTags(cage.tags, coded.correspondence, tags);
    parts.tags = packed(tags.bytes());
    const Grid grid = gridFor(cage.positions, positionBits);
    if (!parts.draco) {
        ByteWriter plain;
        writePlain(cage, grid, plain);
        const std::size_t positions = 6 * std::size_t(cage.vertexCount());
        parts.positions = packed(std::span(plain.bytes()).first(positions));
        parts.connectivity = packed(std::span(plain.bytes()).subspan(positions));
        return parts;
    }
    const auto body = dracoBody(cage, grid);
    SUBDFIT_CHECK(body.has_value());
    ByteReader in(body->bytes, "Draco body");
    const auto draco = in.take(in.getCount(1, "Draco byte"));
    parts.polygonMarks = packed(in.take(in.remaining()));
    // The same triangles over one position: what Draco spends on connectivity alone.
    const CellTriangles triangles = decodeDracoTriangles(draco, grid, "Draco cage");
    parts.connectivity =
        packed(encodeDracoTriangles(std::vector<Cell>(triangles.cells.size(), Cell{}), triangles.corners));
    const std::size_t whole = packed(draco);
    parts.positions = whole > parts.connectivity ? whole - parts.connectivity : 0;
    return parts;
}

CodedCage encodeCage(const mesh::PolygonMesh& cage, int positionBits) {
    SUBDFIT_CHECK(positionBits >= 8 && positionBits <= 16);
    const Grid grid = gridFor(cage.positions, positionBits);
    auto draco = dracoBody(cage, grid);
    ByteWriter plain;
    writePlain(cage, grid, plain);
    // A cage of a few faces is smaller plain (Draco's header alone is ~40 bytes); zstd is left
    // out of the comparison, it shrinks both.
    if (draco && draco->bytes.size() >= plain.bytes().size()) draco.reset();
    CodedCage coded;
    coded.correspondence = draco ? std::move(draco->to) : identity(cage);
    ByteWriter out;
    out.put<std::uint8_t>(draco ? draco->coding : kPlain);
    out.putVarint(std::uint64_t(cage.vertexCount()));
    out.putVarint(std::uint64_t(cage.faceCount()));
    writeGrid(grid, out);
    out.putBytes(draco ? draco->bytes : plain.bytes());
    writeTags(cage.tags, coded.correspondence, out);
    coded.bytes = std::move(out.bytes());
    ByteReader in(coded.bytes, "encoded cage");
    coded.decoded = decodeCage(in);
    coded.decoded.sourcePath = cage.sourcePath;
    coded.decoded.tags.passthrough = cage.tags.passthrough;
    return coded;
}

mesh::PolygonMesh decodeCage(ByteReader& in, int* positionBits) {
    const int coding = in.get<std::uint8_t>();
    if (coding != kPlain && coding != kDraco && coding != kDracoPairs && coding != kDracoOnce)
        throw Error(in.what() + ": unknown cage coding " + std::to_string(coding));
    const std::size_t vertices = in.getCount(coding == kPlain ? 6 : 0, "vertex"), faces = in.getCount(1, "face");
    if (vertices > std::size_t(mesh::kMaxVertices) || faces > std::size_t(mesh::kMaxTriangles))
        throw Error(in.what() + ": more vertices or faces than subdfit reads");
    const Grid grid = readGrid(in);
    if (positionBits) *positionBits = grid.bits;
    mesh::PolygonMesh cage;
    if (coding == kPlain) readPlain(in, grid, vertices, faces, cage);
    else readDraco(in, coding, grid, vertices, faces, cage);
    readTags(in, cage);
    cage.sourcePath = in.what();  // what the soundness checks name: "file: CAGE section"
    mesh::validateMesh(cage);
    cage.sourcePath.clear();
    return cage;
}

}  // namespace subdfit::codec
