#pragma once
// A PolygonMesh turned into OpenSubdiv's base topology: faces, creases, corners, holes and the
// subdivision rules from the mesh's tags. Nothing is refined here.
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>

#include <memory>
#include <string>

#include "mesh/polygon_mesh.h"

namespace subdfit::subdiv {

using RefinerPtr = std::unique_ptr<OpenSubdiv::Far::TopologyRefiner>;

// The name errors about this mesh start with: its source path, or a stand-in for meshes built
// in code.
std::string meshName(const mesh::PolygonMesh& mesh);

OpenSubdiv::Sdc::Options sdcOptions(const mesh::SubdivisionTags& tags);

// Ptex faces of a cage, as Far::PtexIndices numbers them: one per quad, n per n-gon.
int ptexFaceCount(const mesh::PolygonMesh& mesh);

// Throws subdfit::Error naming mesh.sourcePath when the mesh is malformed (indices out of range,
// faces with fewer than 3 corners, ...) or OpenSubdiv rejects it; the message carries
// OpenSubdiv's own text. Non-manifold edges and repeated vertices in a face are accepted:
// OpenSubdiv handles both (it treats such vertices as sharp).
RefinerPtr buildTopologyRefiner(const mesh::PolygonMesh& mesh);

}  // namespace subdfit::subdiv
