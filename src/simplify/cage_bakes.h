#pragma once
// The geometric maps the budget search bakes on one cage, by (map choice, resolution): each baked
// once, and one of them started ahead on a thread of its own. A bake is CPU ray-casting, judging a
// candidate is GL work on the calling thread: the map ladder's first rung is baked while the bare
// cage is judged, rather than after it. What a bake returns does not depend on where it ran.
#include <cstddef>
#include <future>
#include <map>
#include <utility>

#include "mesh/polygon_mesh.h"
#include "simplify/bake/bake.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {

class CageBakes {
public:
    // `cage` (normalised frame) and `reference` must outlive this.
    CageBakes(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference) : cage_(cage), reference_(reference) {}
    CageBakes(const CageBakes&) = delete;
    CageBakes& operator=(const CageBakes&) = delete;
    ~CageBakes();  // waits for a bake started ahead and never asked for

    // Starts baking `options` as the maps of `choice` on a thread of its own, unless it is under way or done.
    void startAhead(size_t choice, const BakeOptions& options);
    // The maps of `choice` at options.resolution: baked now, or waited for if started ahead.
    // Rethrows what baking threw (an interrupt among them).
    const surface::SurfaceMaps& at(size_t choice, const BakeOptions& options);

private:
    using Key = std::pair<size_t, int>;
    const mesh::PolygonMesh& cage_;
    const mesh::PolygonMesh& reference_;
    std::map<Key, std::shared_future<surface::SurfaceMaps>> bakes_;
};

}  // namespace subdfit::simplify
