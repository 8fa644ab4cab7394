#pragma once
// Where an asset.subd's bytes go: each section as stored, and the cage's section split into
// connectivity, positions, polygon marks and tags (codec::cageByteParts), with the cage's
// shape (faces, quads, regular vertices) that its bytes and its surface depend on.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "codec/cage_coding.h"

namespace subdfit::bench {

struct SubdBytes {
    std::size_t file = 0;
    std::map<std::string, std::size_t> sections;  // tag -> stored bytes (header included)
    codec::CageByteParts cage;                    // at the bits the file codes the cage's positions at
    int faces = 0, quads = 0, vertices = 0, positionBits = 0;
    int regularVertices = 0;  // vertices with four quads around them and no other face
};

SubdBytes subdBytes(const std::filesystem::path& file);

}  // namespace subdfit::bench
