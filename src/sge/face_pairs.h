#pragma once
// The pairs of ptex faces whose stencils share a base vertex. Where one render saw face a at a
// pixel and the other face b, G adds the pixel into the pair's sum, which goes to the union of
// their vertices (glsl/gradient.comp, scatter_sums.comp). CPU only; FaceVertexTable uploads it.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace subdfit::sge {

struct FacePairs {
    // Pair k is (first[k], second[k]), first < second, sorted by first, then by second.
    std::vector<int> first, second;
    // Each face a's pairs hashed by their second face, so that G finds a pixel's pair in a read
    // or two rather than by a binary search over a face's hundred pairs (docs/measurements.md):
    // face a owns the 2^bits slots from regions[a] = (first slot, bits), at most half of them
    // full; a slot holds (b, k), or (−1, −1) where empty; a search probes from pairSlotOf(b, bits)
    // onwards to b or an empty slot.
    std::vector<glm::ivec2> regions, slots;
};

// `faceOffsets`, `faceVertices`: CSR, ptex face -> its base vertices (each face's sorted).
FacePairs findFacePairs(const std::vector<int>& faceOffsets, const std::vector<int>& faceVertices, int vertexCount);

// Where the search for face b starts among 2^bits slots (bits >= 1): Fibonacci hashing, whose top
// bits spread the runs of consecutive face ids that a face's neighbours have. gradient.comp's twin.
constexpr std::uint32_t pairSlotOf(int b, int bits) { return (std::uint32_t(b) * 2654435769u) >> (32 - bits); }

// k of the pair (a, b), a < b, or −1 where the two share no vertex: the search G does.
int findPair(const FacePairs& pairs, int a, int b);

}  // namespace subdfit::sge
