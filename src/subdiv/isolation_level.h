#pragma once
// How deep OpenSubdiv isolates a cage's extraordinary vertices and creases: the GPU draws a
// cage at drawingIsolationLevel, and the CPU evaluates it there too (subdiv::LimitEvaluator).
#include "mesh/polygon_mesh.h"

namespace subdfit::subdiv {

inline constexpr int kIsolationLevel = 3;  // a light cage's, and any cage's unless told otherwise

// How deep a cage is isolated for drawing: kIsolationLevel, or shallower on a dense cage with no
// semi-sharp tag sharper than 2 (semi-sharp creases need one level per unit of sharpness to be
// drawn as OpenSubdiv evaluates them; infinitely sharp ones need none): 2 over kDenseCageFaces
// faces, 1 over kVeryDenseCageFaces. Each face of such a cage spans a few pixels at 256², where
// the shallower end caps move the surface by a fraction of one (docs/measurements.md), and it is
// drawn with half the segments per face edge (fit::CageFitter) and fewer, larger patches: a step
// several times faster.
inline constexpr int kDenseCageFaces = 2000;
inline constexpr int kVeryDenseCageFaces = 5000;
int drawingIsolationLevel(const mesh::PolygonMesh& cage);

}  // namespace subdfit::subdiv
