#pragma once
// The displacement's heights laid out for the surface pass: one tile per ptex face holding its
// nodes and the ring of nodes across its edges (glsl/height_tiles.comp), so that each vertex
// reads the nodes around it with plain texel fetches instead of the node table and its branches.
#include "gl/program_cache.h"
#include "gl/texture.h"

namespace subdfit::render {

struct PatchMaps;

class HeightTiles {
public:
    // `resolution`: cells per ptex-face edge of the heights.
    HeightTiles(int faceCount, int resolution);

    int resolution() const { return resolution_; }
    int tilesPerRow() const { return tilesPerRow_; }

    // Lays out the heights `maps` binds, and binds the tiles for the surface pass to read.
    void fill(gl::ProgramCache& programs, const PatchMaps& maps) const;

private:
    int faceCount_, resolution_, tilesPerRow_;
    gl::Texture texture_;
};

}  // namespace subdfit::render
