// The table of map kinds: what every layer loops over must be consistent, and what reads and
// writes kinds by it (--maps, asset.subd sections, the CPU maps) must agree with it.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "codec/subd_format.h"
#include "kinds/map_kinds.h"
#include "maps/map_effects.h"
#include "mesh/procedural.h"
#include "surface/surface_maps.h"
#include "util/error.h"

namespace subdfit {
namespace {

using kinds::kMapKinds;
using kinds::MapKind;
using kinds::MapKindInfo;
using kinds::MapLattice;

TEST(MapKinds, EveryKindHasItsOwnNameSectionAndSeed) {
    std::set<std::string> names, sections;
    std::set<std::uint32_t> seeds;
    for (const MapKindInfo& k : kMapKinds) {
        EXPECT_TRUE(names.insert(std::string(k.name)).second) << k.name;
        EXPECT_TRUE(sections.insert(std::string(k.section.data(), 4)).second) << k.name;
        EXPECT_TRUE(seeds.insert(k.seed).second) << k.name;
        EXPECT_EQ(kinds::kindWithSection(k.section), &k);
        EXPECT_GE(k.channels, 1);
        EXPECT_LE(k.channels, 3);
        EXPECT_GT(k.epsilon, 0.0f);
        EXPECT_GT(k.learningRate, 0.0f);
        for (int c = 0; c < k.channels; ++c)
            if (k.unitRange) EXPECT_TRUE(k.initial[size_t(c)] >= 0.0f && k.initial[size_t(c)] <= 1.0f) << k.name;
        // The user chooses the geometric maps; the scene's materials the appearance.
        EXPECT_EQ(k.word.empty(), k.lattice == MapLattice::Appearance) << k.name;
    }
    EXPECT_EQ(kinds::kindWithSection({'C', 'A', 'G', 'E'}), nullptr);
}

TEST(MapKinds, ASetHoldsWhatIsSetAndKnowsItsLattices) {
    kinds::MapKinds set{MapKind::NormalMap};
    EXPECT_TRUE(set.has(MapKind::NormalMap));
    EXPECT_FALSE(set.has(MapKind::Displacement));
    EXPECT_TRUE(set.geometric());
    EXPECT_FALSE(set.appearance());
    set.set(MapKind::BaseColor);
    EXPECT_TRUE(set.appearance());
    set.set(MapKind::NormalMap, false);
    EXPECT_FALSE(set.geometric());
    EXPECT_EQ(set & kinds::MapKinds::on(MapLattice::Geometric), kinds::MapKinds{});
    EXPECT_EQ(set | kinds::MapKinds{MapKind::Displacement},
              (kinds::MapKinds{MapKind::BaseColor, MapKind::Displacement}));
    for (const MapKindInfo& k : kMapKinds) EXPECT_EQ(kinds::MapKinds::on(k.lattice).has(k.kind), true) << k.name;
}

TEST(MapKinds, TheMapsOptionReadsEveryGeometricKindsWordAndWritesItBack) {
    for (const MapKindInfo& k : kMapKinds) {
        if (k.word.empty()) continue;
        const maps::MapEffects effects = maps::parseMapEffects(std::string(k.word));
        EXPECT_EQ(effects, kinds::MapKinds{k.kind});
        EXPECT_EQ(maps::toString(effects), k.word);
    }
    EXPECT_EQ(maps::parseMapEffects("normal,displacement"),
              (kinds::MapKinds{MapKind::Displacement, MapKind::NormalMap}));
    EXPECT_EQ(maps::toString(maps::parseMapEffects("normal,displacement")), "displacement,normal");
    EXPECT_EQ(maps::toString({}), "none");
    EXPECT_THROW(maps::parseMapEffects("base_color"), Error);  // the materials decide that one
}

TEST(MapKinds, EachGeometricKindIsItsOwnSectionOfTheFileAndComesBack) {
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(2);
    for (const MapKindInfo& k : kMapKinds) {
        if (k.lattice != MapLattice::Geometric) continue;
        surface::SurfaceMaps maps;
        maps.layout = surface::buildTexelLayout(cage, 2);
        auto& values = maps.values(k.kind);
        for (int n = 0; n < maps.layout.nodeCount * k.channels; ++n) values.push_back(0.01f * float(n % 7));
        const codec::SubdAsset asset = codec::shippableAsset(cage, maps);
        const auto bytes = codec::encodeSubd(asset);
        const std::string tag(k.section.data(), 4);
        EXPECT_NE(std::string(bytes.begin(), bytes.end()).find(tag), std::string::npos) << k.name;
        const codec::SubdAsset decoded = codec::decodeSubd(bytes, "kinds.subd");
        EXPECT_EQ(decoded.maps.kinds(), kinds::MapKinds{k.kind});
        ASSERT_EQ(decoded.maps.values(k.kind).size(), asset.maps.values(k.kind).size()) << k.name;
        for (size_t n = 0; n < values.size(); ++n)
            EXPECT_NEAR(decoded.maps.values(k.kind)[n], asset.maps.values(k.kind)[n], 1e-3f) << k.name;
    }
}

}  // namespace
}  // namespace subdfit
