#include "simplify/remesh/polygon_repair.h"

#include <numeric>
#include <unordered_map>

#include "util/disjoint_sets.h"

namespace subdfit::simplify::remesh {
namespace {

std::uint64_t directedKey(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

// The corners of a set of polygons, numbered face after face, and the corner starting each directed edge.
struct Corners {
    explicit Corners(const Polygons& faces) {
        for (int f = 0; f < int(faces.size()); ++f)
            for (int k = 0; k < int(faces[size_t(f)].size()); ++k) {
                face.push_back(f);
                index.push_back(k);
            }
        int c = 0;
        for (const auto& f : faces)
            for (size_t k = 0; k < f.size(); ++k, ++c) starting[directedKey(f[k], f[(k + 1) % f.size()])] = c;
    }
    std::vector<int> face, index;
    std::unordered_map<std::uint64_t, int> starting;
};

}  // namespace

std::vector<int> splitFans(Polygons& faces, int vertexCount) {
    const Corners corners(faces);
    const int n = int(corners.face.size());
    DisjointSets fans(n);
    // A corner at v and the corner at v of the face across the edge entering it are one fan.
    for (int c = 0; c < n; ++c) {
        const auto& f = faces[size_t(corners.face[size_t(c)])];
        const int k = corners.index[size_t(c)];
        const int v = f[size_t(k)], previous = f[(size_t(k) + f.size() - 1) % f.size()];
        const auto across = corners.starting.find(directedKey(v, previous));
        if (across != corners.starting.end()) fans.join(c, across->second);
    }
    std::vector<int> firstFan(size_t(vertexCount), -1), copied;
    std::unordered_map<int, int> vertexOfFan;
    for (int c = 0; c < n; ++c) {
        int& v = faces[size_t(corners.face[size_t(c)])][size_t(corners.index[size_t(c)])];
        const int root = fans.find(c);
        if (firstFan[size_t(v)] < 0) firstFan[size_t(v)] = root;
        if (firstFan[size_t(v)] == root) continue;
        const auto [it, added] = vertexOfFan.emplace(root, vertexCount + int(copied.size()));
        if (added) copied.push_back(v);
        v = it->second;
    }
    return copied;
}

void closeHoles(Polygons& faces, const std::vector<char>& inside) {
    std::unordered_map<std::uint64_t, char> directed;
    for (const auto& f : faces)
        for (size_t k = 0; k < f.size(); ++k) directed[directedKey(f[k], f[(k + 1) % f.size()])] = 1;
    std::unordered_map<int, int> next;  // a hole runs its boundary edges backwards: b → a for a face's a → b
    for (const auto& [key, _] : directed) {
        const int a = int(key >> 32), b = int(std::uint32_t(key));
        if (!directed.count(directedKey(b, a))) next[b] = a;
    }
    std::unordered_map<int, char> taken;
    Polygons holes;
    for (const auto& [start, _] : next) {
        if (taken[start]) continue;
        std::vector<int> loop;
        bool closes = true;
        for (int at = start; closes;) {
            loop.push_back(at);
            taken[at] = 1;
            const auto it = next.find(at);
            closes = it != next.end() && loop.size() <= next.size();
            if (!closes || it->second == start) break;
            at = it->second;
        }
        bool interior = closes && loop.size() >= 3;
        for (int v : loop) interior = interior && size_t(v) < inside.size() && inside[size_t(v)];
        if (interior) holes.push_back(std::move(loop));
    }
    for (auto& hole : holes) faces.push_back(std::move(hole));
}

bool isManifold(const mesh::PolygonMesh& mesh) {
    // Each directed edge once; the corner that starts it, to walk the fans.
    std::unordered_map<std::uint64_t, int> cornerOf;
    auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
    std::vector<int> faceOf, firstOf;
    for (int f = 0, first = 0; f < mesh.faceCount(); first += mesh.faceSizes[size_t(f)], ++f)
        for (int k = 0; k < mesh.faceSizes[size_t(f)]; ++k) {
            faceOf.push_back(f);
            firstOf.push_back(first);
        }
    auto nextCorner = [&](int c) {
        const int first = firstOf[size_t(c)], size = mesh.faceSizes[size_t(faceOf[size_t(c)])];
        return first + (c - first + 1) % size;
    };
    auto previousCorner = [&](int c) {
        const int first = firstOf[size_t(c)], size = mesh.faceSizes[size_t(faceOf[size_t(c)])];
        return first + (c - first + size - 1) % size;
    };
    for (int c = 0; c < int(mesh.faceIndices.size()); ++c) {
        const int a = mesh.faceIndices[size_t(c)], b = mesh.faceIndices[size_t(nextCorner(c))];
        if (a == b || !cornerOf.emplace(key(a, b), c).second) return false;
    }
    // Around each vertex: from any corner, turn through the faces (both ways where there is a
    // boundary) and count; one fan reaches every corner of the vertex.
    std::vector<int> cornersAt(size_t(mesh.vertexCount()), 0), someCorner(size_t(mesh.vertexCount()), -1);
    for (int c = 0; c < int(mesh.faceIndices.size()); ++c) {
        ++cornersAt[size_t(mesh.faceIndices[size_t(c)])];
        someCorner[size_t(mesh.faceIndices[size_t(c)])] = c;
    }
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        if (someCorner[size_t(v)] < 0) continue;
        int reached = 1;
        // Clockwise: the corner of v in the face across the edge entering v's corner.
        const int start = someCorner[size_t(v)];
        int c = start;
        bool closed = false;
        while (true) {
            const int previous = mesh.faceIndices[size_t(previousCorner(c))];
            const auto it = cornerOf.find(key(v, previous));  // the face running v → previous
            if (it == cornerOf.end()) break;
            c = it->second;
            if (c == start) {
                closed = true;
                break;
            }
            if (++reached > cornersAt[size_t(v)]) return false;
        }
        if (!closed) {
            c = start;
            while (true) {
                const int next = mesh.faceIndices[size_t(nextCorner(c))];
                const auto it = cornerOf.find(key(next, v));  // the face running next → v
                if (it == cornerOf.end()) break;
                c = nextCorner(it->second);
                if (++reached > cornersAt[size_t(v)]) return false;
            }
        }
        if (reached != cornersAt[size_t(v)]) return false;
    }
    return true;
}

}  // namespace subdfit::simplify::remesh
