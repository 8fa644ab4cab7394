#pragma once
// The AUVS section of asset.subd: the atlas coordinates of every ptex face's corners
// (surface/appearance_atlas.h), stored once per distinct value at each limit point. Corners meet
// at the nodes of the cage's one-cell texel layout (surface::buildTexelLayout(cage, 1), which the
// decoder rebuilds); inside a chart of the atlas all corners at a node agree, so most nodes hold
// one coordinate pair and their corners need no index. Raw layout:
//
//   varint atlas size | u8 bits b | per node: varint count (>= 1) | per ptex corner (face order,
//   corners at (0,0), (1,0), (1,1), (0,1)) whose node holds more than one value: varint index
//   into its node's values | per value, in the order of cage faces: the quantised
//   q = round(uv · 2^b) less its prediction from the values of its cage face coded before it,
//   as signed varints (u, then v).
//
// A quad's corners are predicted by the parallelogram of its other three (else a neighbour, else
// the value coded last); a triangle's vertex corners by the parallelogram across the edge between
// its two others when a triangle coded before holds that edge with the same values, else (and an
// n-gon's) by the one before; then its edge midpoints by the mean of the edge's ends and its
// centre by the mean of its vertices, which inside a chart is within a fraction of a texel (the
// face's texture is about affine), so that the two thirds of a triangle cage's values that sit
// at midpoints and centres cost a few bits each.
#include "codec/byte_stream.h"
#include "mesh/polygon_mesh.h"
#include "surface/appearance_atlas.h"

namespace subdfit::codec {

// Bits under the point: a quarter of a texel. The fit places corners no better than that, so
// finer bits cost bytes for the same image.
int atlasUvBits(int atlasSize);

void writeAtlasUvs(const mesh::PolygonMesh& cage, const surface::AppearanceAtlas& atlas, ByteWriter& out);
// Throws subdfit::Error naming `in` for anything that does not fit `cage`.
surface::AppearanceAtlas readAtlasUvs(ByteReader& in, const mesh::PolygonMesh& cage);

}  // namespace subdfit::codec
