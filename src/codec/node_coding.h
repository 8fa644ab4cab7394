#pragma once
// One channel of a map's node values (surface/texel_layout.h), quantised and coded coarse to
// fine, as displaced micro-meshes and displaced subdivision surfaces code their heights: the
// tiles' corners first (each predicted from its coded neighbours one cell away, else from the
// tile's coded corners), then at every finer level the new nodes predicted by linear
// interpolation of the two coded nodes that bracket them (along u, then along v). Each kind of
// prediction leans from the channel's center towards the neighbours by a fraction the encoder
// picks (in eighths, stored first): a noisy map is better predicted by its mean. Only the
// quantised residuals are stored. Prediction runs on the *decoded* values, so the decoder
// predicts exactly what the encoder did and every value is within step/2 of its original. A
// node shared by several tiles is coded once, by the first tile to reach it.
#include <span>

#include "codec/byte_stream.h"
#include "surface/texel_layout.h"

namespace subdfit::codec {

struct ChannelQuantisation {
    float center = 0.0f;  // what a tile's first corner is predicted as
    float step = 1.0f;    // the quantisation step: the largest error is step / 2
};

// How the residuals are laid out. Level by level (what encodeNodes writes, .subd version 10 on):
// each pass of the coarse-to-fine order across every tile, its residuals one block of Draco's
// entropy coder (a block's statistics are its level's: the coarse residuals spread wider than
// the fine ones), so a file's levels come in order. Tile by tile (version 9 and before, read
// only): each tile's nodes in turn, zigzag varints.
enum class NodeStream { LevelBlocks, TileVarints };

// The step that spends `bits` on the channel's range (bits in 1..24).
ChannelQuantisation quantisationFor(std::span<const float> values, int stride, int channel, int bits);

// Appends the two leans (u8 each: corners, interpolated) and the residuals of channel `channel`
// of `values` (`stride` floats per node), level by level.
void encodeNodes(const surface::TexelLayout& layout, std::span<const float> values, int stride, int channel,
                 const ChannelQuantisation& q, ByteWriter& out);

// Fills channel `channel` of `values` (layout.nodeCount × stride floats). Throws subdfit::Error
// for truncated or malformed data or a residual that does not fit a float.
void decodeNodes(const surface::TexelLayout& layout, std::span<float> values, int stride, int channel,
                 const ChannelQuantisation& q, ByteReader& in, NodeStream stream = NodeStream::LevelBlocks);

}  // namespace subdfit::codec
