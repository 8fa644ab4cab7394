#include "sge/face_pairs.h"

#include <algorithm>
#include <bit>

namespace subdfit::sge {
namespace {

// Face a's pairs [begin, end) of `pairs` hashed into slots of their own, appended to `pairs.slots`.
void hashRun(FacePairs& pairs, int begin, int end) {
    const int count = end - begin;
    const int bits = count <= 1 ? 1 : std::bit_width(unsigned(2 * count - 1));  // 2^bits >= 2 count
    const std::uint32_t mask = (1u << bits) - 1u;
    const int firstSlot = int(pairs.slots.size());
    pairs.regions.push_back({firstSlot, bits});
    pairs.slots.resize(pairs.slots.size() + (size_t(1) << bits), glm::ivec2(-1));
    for (int k = begin; k < end; ++k) {
        const int b = pairs.second[size_t(k)];
        std::uint32_t slot = pairSlotOf(b, bits);
        while (pairs.slots[size_t(firstSlot) + slot].x >= 0) slot = (slot + 1u) & mask;
        pairs.slots[size_t(firstSlot) + slot] = {b, k};
    }
}

}  // namespace

FacePairs findFacePairs(const std::vector<int>& faceOffsets, const std::vector<int>& faceVertices, int vertexCount) {
    const int faceCount = int(faceOffsets.size()) - 1;
    // Each vertex's faces, to find the faces that share one with a given face.
    std::vector<int> vertexFaceOffsets(size_t(vertexCount) + 1, 0), vertexFaces(faceVertices.size());
    for (int v : faceVertices) ++vertexFaceOffsets[size_t(v) + 1];
    for (size_t v = 1; v < vertexFaceOffsets.size(); ++v) vertexFaceOffsets[v] += vertexFaceOffsets[v - 1];
    std::vector<int> fill(vertexFaceOffsets.begin(), vertexFaceOffsets.end() - 1);
    for (int f = 0; f < faceCount; ++f)
        for (int k = faceOffsets[size_t(f)]; k < faceOffsets[size_t(f) + 1]; ++k)
            vertexFaces[size_t(fill[size_t(faceVertices[size_t(k)])]++)] = f;

    FacePairs pairs;
    std::vector<int> pairedWith(size_t(faceCount), -1);
    for (int a = 0; a < faceCount; ++a) {
        const int begin = int(pairs.second.size());
        for (int k = faceOffsets[size_t(a)]; k < faceOffsets[size_t(a) + 1]; ++k) {
            const int v = faceVertices[size_t(k)];
            for (int j = vertexFaceOffsets[size_t(v)]; j < vertexFaceOffsets[size_t(v) + 1]; ++j) {
                const int b = vertexFaces[size_t(j)];
                if (b > a && pairedWith[size_t(b)] != a) {
                    pairedWith[size_t(b)] = a;
                    pairs.second.push_back(b);
                }
            }
        }
        std::sort(pairs.second.begin() + begin, pairs.second.end());
        pairs.first.resize(pairs.second.size(), a);
        hashRun(pairs, begin, int(pairs.second.size()));
    }
    return pairs;
}

int findPair(const FacePairs& pairs, int a, int b) {
    const glm::ivec2 region = pairs.regions[size_t(a)];
    const std::uint32_t mask = (1u << region.y) - 1u;
    for (std::uint32_t slot = pairSlotOf(b, region.y);; slot = (slot + 1u) & mask) {
        const glm::ivec2 entry = pairs.slots[size_t(region.x) + slot];
        if (entry.x == b) return entry.y;
        if (entry.x < 0) return -1;
    }
}

}  // namespace subdfit::sge
