#pragma once
// `decode --lods K`: a chain of levels of detail of a decoded asset, each about half the
// triangles of the one before (as Unreal's and Simplygon's automatic chains step), for engines
// that switch between them by the object's size on screen.
//
// Level 0 is the decoded surface itself. Each further level is the better, by its largest
// distance to level 0, of two meshes of the same triangle count: the limit surface tessellated
// with fewer segments a face edge (exact points of the surface, every face alike), and level 0
// simplified by meshoptimizer (points of level 0, spent where the surface bends; texture seams
// kept). Each level records its mean and largest sampled distance to level 0, both ways
// (surface_error.h), and the screen size below which it may be drawn: an error of e seen on a
// screen H pixels tall covers p pixels when the object's bounding sphere (radius R) spans
// 2·p·R / (e·H) of the screen height, whatever the field of view.
#include <vector>

#include "export/gltf_mesh.h"
#include "codec/subd_format.h"

namespace subdfit::exporter {

struct ScreenSizeRule {
    double pixelError = 1.0;  // p
    int screenHeight = 1080;  // H
};

struct LodLevel {
    GltfMesh mesh;
    int segments = 0;  // of a tessellation; 0: simplified from level 0
    double meanDistance = 0.0, maxDistance = 0.0;
    double screenSize = 1.0;  // of the bounding sphere's diameter over the screen height; level 0: 1
};

struct LodChain {
    std::vector<LodLevel> levels;
    double boundingRadius = 0.0;  // R, of level 0's bounding box
};

// The chain of `count` levels (1..kMostLods) from `full`, the decode of `asset` at `segments`.
// A level that cannot have fewer triangles than the one before ends the chain early.
LodChain lodChain(const codec::SubdAsset& asset, GltfMesh full, int segments, int count,
                  const ScreenSizeRule& rule = {});

inline constexpr int kMostLods = 8;

}  // namespace subdfit::exporter
