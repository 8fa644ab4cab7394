#pragma once
// The control cage inside a .subd file (its CAGE section, codec/subd_format.h): positions
// quantised over the cage's bounding cube, and the connectivity either
//  - through Draco (coding 1): the cage fan-triangulated, edgebreaker-coded with the quantised
//    positions as an integer attribute (parallelogram prediction), plus one byte per triangle
//    saying which of its edges lie inside a polygon; or
//  - plain (coding 0): the positions as they are and the face indices as deltas,
// whichever the encoder can use: Draco is taken only when the decoded cage is the same cage
// (a manifold one; two vertices on one grid cell would decode as one, so the later moves to a
// free neighbouring cell, a step away); it is 2-3x smaller on a decimated
// cage, whose vertex order the plain deltas cannot exploit. Draco renumbers vertices and faces
// and may start a polygon at another corner, so the encoder reports where everything went.
#include <span>
#include <string>
#include <vector>

#include "codec/byte_stream.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::codec {

// Where each vertex and face of the encoded cage is in the decoded one: decoded face face[f]'s
// corner k is decoded vertex vertex[cage corner (k + rotation[f]) mod n of face f].
struct CageCorrespondence {
    std::vector<int> vertex, face, rotation;
};

struct CodedCage {
    std::vector<unsigned char> bytes;  // the CAGE section's raw contents
    mesh::PolygonMesh decoded;         // what decodeCage will return
    CageCorrespondence correspondence;
};

// `positionBits` in 8..16.
CodedCage encodeCage(const mesh::PolygonMesh& cage, int positionBits);

// What a coded cage's bytes pay for, each part zstd-packed on its own as the section is whole
// (so that the parts add up to about the section's stored bytes): Draco's connectivity (its
// triangles over positions all equal), the positions (the rest of Draco's bytes), the marks of
// which triangle edges lie inside polygons, and the tags. A plain-coded cage's indices count as
// connectivity. For `subdfit-bench simplify`'s table of where the bytes go.
struct CageByteParts {
    bool draco = false;
    std::size_t connectivity = 0, positions = 0, polygonMarks = 0, tags = 0;
    std::size_t stored = 0;  // the whole section, zstd-packed as asset.subd stores it
};
CageByteParts cageByteParts(const mesh::PolygonMesh& cage, int positionBits);

// Reads a CAGE section; `positionBits`, if given, receives the bits its positions were coded at.
// Throws subdfit::Error (in.what(): problem) for anything that is not a sound cage.
mesh::PolygonMesh decodeCage(ByteReader& in, int* positionBits = nullptr);

}  // namespace subdfit::codec
