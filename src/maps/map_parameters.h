#pragma once
// The optional texel parameter groups of a scene: a displacement map (one height per node) and
// a normal map (tangent-space x, y per node), on one surface::TexelLayout. Only the groups the scene
// asks for exist: a run without maps has no buffers, no shader defines and no passes for them.
#include <memory>
#include <string>
#include <vector>

#include "gl/program.h"
#include "maps/map_effects.h"
#include "surface/texel_layout.h"
#include "optim/parameter_group.h"
#include "optim/updates.h"
#include "render/patch_renderer.h"

namespace subdfit::maps {

struct MapSettings {
    int resolution = 8;  // cells per ptex-face edge
    // Heights in the normalised frame (scene radius 1); tangent offsets are dimensionless.
    optim::GroupSettings displacement{.epsilon = 0.004f, .learningRate = 0.003f};
    optim::GroupSettings normalMap{.epsilon = 0.05f, .learningRate = 0.01f};
    // (I + λL)⁻¹ on the node graph, as for the cage: texel estimates are noisy one by one.
    float smoothing = 2.0f;
    int smoothingIterations = 8;
};

// Which θ a raster pass reads: the current one, or a perturbed one.
enum class ParameterVersion { Current, Plus, Minus };

class MapParameters {
public:
    MapParameters(const mesh::PolygonMesh& cage, MapEffects effects, const MapSettings& settings);

    const surface::TexelLayout& layout() const { return layout_; }
    MapEffects effects() const { return effects_; }
    optim::ParameterGroup* displacement() { return displacement_.get(); }
    optim::ParameterGroup* normalMap() { return normalMap_.get(); }
    std::vector<optim::ParameterGroup*> groups();

    // The patch pass's maps: θ± of the group being perturbed (`perturbed`, may be null) and θ of
    // the others. Valid while this object lives.
    render::PatchMaps forRaster(ParameterVersion version, const optim::ParameterGroup* perturbed = nullptr) const;
    void bindForGradient() const;

    // Preconditions `group`'s gradient on the node graph and applies Adam to it at `learningRate`.
    void update(gl::ProgramCache& programs, optim::ParameterGroup& group, float learningRate);

private:
    MapEffects effects_;
    surface::TexelLayout layout_;
    MapSettings settings_;
    gl::Buffer faceNodes_;
    optim::Adjacency adjacency_;
    gl::Buffer scratch_;  // Jacobi ping-pong partner, sized for the largest group
    std::unique_ptr<optim::ParameterGroup> displacement_, normalMap_;
};

}  // namespace subdfit::maps
