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
#include <vector>

#include "codec/byte_stream.h"
#include "surface/texel_layout.h"

namespace subdfit::codec {

struct ChannelQuantisation {
    float center = 0.0f;  // what a tile's first corner is predicted as
    float step = 1.0f;    // the quantisation step: the largest error is step / 2
    // Embedded coding: the first `coarsePasses` passes at step · 2^coarseShift, then a pass that
    // refines their nodes to `step`, then the finer passes (at `step`, predicted from the refined
    // values), so that a prefix ending before the refinement holds the coarse levels at the
    // coarse step, as a file made for fewer bits would. 0: every pass at `step`. (Written by
    // encodeNodes, read back by decodeNodes from the stream.)
    int coarsePasses = 0, coarseShift = 0;
    // The leans (eighths) to code with; -1: encodeNodes picks the cheapest. Given with the center
    // and a coarse step of another coding of the same lattice order, the coarse passes code that
    // coding's decoded values exactly (every residual a whole number of steps).
    int cornerLean = -1, interpolatedLean = -1;
};

// How the residuals are laid out. Level by level (what encodeNodes writes, .subd version 11):
// each pass of the coarse-to-fine order across every tile, its residuals one block of Draco's
// entropy coder (a block's statistics are its level's: the coarse residuals spread wider than
// the fine ones), so a file's levels come in order; the coarse passes' step and their refinement
// (ChannelQuantisation) stated after the leans. One step (version 10, read only): the same
// without the embedded coding. Tile by tile (version 9 and before, read only): each tile's nodes
// in turn, zigzag varints.
enum class NodeStream { LevelBlocks, LevelBlocksOneStep, TileVarints };

// The passes that code the lattice of resolution `coarse` within tiles of resolution
// `resolution` (a power-of-two multiple of it): the corners and every level down to its spacing.
int passesOfLattice(int resolution, int coarse);

// The step that spends `bits` on the channel's range (bits in 1..24).
ChannelQuantisation quantisationFor(std::span<const float> values, int stride, int channel, int bits);

// Appends the two leans (a u8: corners in its low 4 bits, interpolated in its high), the coarse
// passes and their shift (a u8: 0, or the passes in its high 4 bits and the shift less 1 in its
// low) and the residuals of channel `channel` of `values` (`stride` floats per node), level by
// level; with `passEnds`, the size of `out` after each pass is appended to it (where a prefix of
// the stream can end). `coarseValues` (one per node, or none): what the coarse passes of an
// embedded coding code instead (the values best on the coarse lattice alone, e.g. a bake at its
// resolution); the refinement then codes the difference to `values`.
void encodeNodes(const surface::TexelLayout& layout, std::span<const float> values, int stride, int channel,
                 const ChannelQuantisation& q, ByteWriter& out, std::vector<std::size_t>* passEnds = nullptr,
                 std::span<const float> coarseValues = {});

// Whether the residuals may end early: the first bytes of a stream (a file cut short, a download
// under way). The passes wholly present decode; every node of a later pass takes its prediction
// leaning fully on its neighbours (between its bracket: the coarser map, interpolated).
enum class NodeEnding { Whole, Prefix };

// Fills channel `channel` of `values` (layout.nodeCount × stride floats); returns the passes
// decoded (all of them but where a Prefix ends early); `coded` receives `q` with the coarse
// passes and leans the stream states. Throws subdfit::Error for malformed data, data that ends
// early (but a Prefix) or a residual that does not fit a float.
int decodeNodes(const surface::TexelLayout& layout, std::span<float> values, int stride, int channel,
                const ChannelQuantisation& q, ByteReader& in, NodeStream stream = NodeStream::LevelBlocks,
                NodeEnding ending = NodeEnding::Whole, ChannelQuantisation* coded = nullptr);

// The passes of a tile at resolution `resolution` (the corners, then two per level).
int passCount(int resolution);

// `values` (`stride` channels a node) as a decoder reads them back once each channel is coded at
// `bits` with the quantisation and leans a file's writer picks (quantisationFor, no embedded
// coding): what a fit of the coded asset draws.
std::vector<float> codedValues(const surface::TexelLayout& layout, std::span<const float> values, int stride, int bits);

}  // namespace subdfit::codec
