// The map groups MapParameters makes from the table of kinds (kinds/map_kinds.h): one per kind
// the scene fits, on its kind's lattice, its kind's channels and initial values, settings and
// name, and nothing for the kinds it does not.
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "maps/map_parameters.h"
#include "mesh/procedural.h"

namespace subdfit::maps {
namespace {

TEST(MapGroups, EachKindTheSceneFitsIsAGroupAsItsRowDescribes) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    MapEffects all;
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds) all.set(kind.kind);
    for (const MapEffects effects : {all, MapEffects{MapKind::NormalMap, MapKind::BaseColor}}) {
        MapSettings settings{.resolution = 3, .appearanceResolution = 5};
        settings.of(MapKind::BaseColor).epsilon = 0.125f;  // a setting reaches its kind's group
        MapParameters parameters(cage, effects, settings);
        size_t groups = 0;
        for (const kinds::MapKindInfo& kind : kinds::kMapKinds) {
            const optim::ParameterGroup* group = parameters.group(kind.kind);
            ASSERT_EQ(group != nullptr, effects.has(kind.kind)) << kind.name;
            if (!group) continue;
            ++groups;
            EXPECT_EQ(group->name(), kind.name);
            EXPECT_EQ(parameters.kindOf(*group), kind.kind);
            EXPECT_EQ(group->settings().epsilon, settings.of(kind.kind).epsilon) << kind.name;
            const surface::TexelLayout& lattice =
                kind.lattice == kinds::MapLattice::Appearance ? parameters.appearanceLayout() : parameters.layout();
            EXPECT_EQ(&parameters.layoutOf(*group), &lattice) << kind.name;
            EXPECT_EQ(lattice.resolution, kind.lattice == kinds::MapLattice::Appearance ? 5 : 3) << kind.name;
            ASSERT_EQ(group->count(), lattice.nodeCount * kind.channels) << kind.name;
            const std::vector<float> values = group->read();
            for (size_t k = 0; k < values.size(); ++k)
                ASSERT_EQ(values[k], kind.initial[k % size_t(kind.channels)]) << kind.name << " value " << k;
        }
        EXPECT_EQ(parameters.groups().size(), groups);
        EXPECT_EQ(parameters.forRaster(ParameterVersion::Current).kinds, effects);
    }
    test::expectNoGlError();
}

}  // namespace
}  // namespace subdfit::maps
