#pragma once
// How much one input may ask of subdfit. A few hundred bytes of glTF can instance a mesh 2^30
// times, and one OBJ line can hold a 10 000-gon whose limit surface costs time growing with
// the cube of its size (OpenSubdiv's stencils around it): each is refused with a message that
// says which limit it met, before the work or the memory is spent.
#include <cstdint>

namespace subdfit::mesh {

// Triangles of a scene after instancing: a 1M-triangle reference fits well under 4 GB; this
// allows 32 times that. Vertices and face corners (OBJ faces may be n-gons) as many as that
// many unindexed triangles have.
inline constexpr std::int64_t kMaxTriangles = std::int64_t(1) << 25;
inline constexpr std::int64_t kMaxVertices = 3 * kMaxTriangles;
inline constexpr std::int64_t kMaxFaceCorners = 3 * kMaxTriangles;
// Node visits when a glTF scene's hierarchy is unfolded (nodes shared by several parents are
// visited once per path from the root).
inline constexpr std::int64_t kMaxNodeInstances = std::int64_t(1) << 20;
// A cage's largest face and highest vertex valence: OpenSubdiv's build time grows steeply past
// them (docs/measurements.md), and its own regression shapes stay well below.
inline constexpr int kMaxCageFaceSize = 128;
inline constexpr int kMaxCageValence = 128;

}  // namespace subdfit::mesh
