#pragma once
// A quad sphere with heights of uniform noise on 4-cell tiles, as asset.subd holds them: coarser
// densities and fewer bits lose detail on it everywhere.
#include <cstdint>
#include <random>

#include "codec/subd_format.h"
#include "mesh/procedural.h"

namespace subdfit::test {

inline codec::SubdAsset noisyHeightsSphere(int n, float amplitude, unsigned seed, std::uint32_t decodeTriangles = 0) {
    const auto cage = mesh::makeQuadSphere(n);
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 4);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(-amplitude, amplitude);
    maps.displacement.resize(size_t(maps.layout.nodeCount));
    for (float& d : maps.displacement) d = height(rng);
    return codec::shippableAsset(cage, maps, 14, decodeTriangles);
}

}  // namespace subdfit::test
