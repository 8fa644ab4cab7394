// The displacement's learning rate follows the map's cells: a height step is a small slope of a
// cell, whatever the cage's size and the map's resolution, so finer maps take finer steps.
#include <gtest/gtest.h>

#include "fit/fit_scene.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"

namespace subdfit::fit {
namespace {

float heightStep(const mesh::PolygonMesh& cage, int mapResolution) {
    FitOptions o;
    o.resolution = 128;
    o.views = 4;
    o.steps = 10;
    o.mapResolution = mapResolution;
    return fitSettings(o, cage).maps.of(maps::MapKind::Displacement).learningRate;
}

TEST(MapRates, AHeightStepIsASmallSlopeOfAMapCell) {
    for (const int divisions : {2, 6, 16}) {
        const mesh::PolygonMesh cage = mesh::makeQuadSphere(divisions);
        const float edge = mesh::meanEdgeLength(cage);
        for (const int resolution : {2, 8, 32}) {
            const float step = heightStep(cage, resolution);
            EXPECT_GT(step, 0.0f);
            // At most a 0.03 slope over a cell: a step tilts a normal by under 2 degrees.
            EXPECT_LE(step / (edge / float(resolution)), 0.0301f) << divisions << " " << resolution;
        }
        EXPECT_LT(heightStep(cage, 32), heightStep(cage, 8)) << divisions;
    }
}

}  // namespace
}  // namespace subdfit::fit
