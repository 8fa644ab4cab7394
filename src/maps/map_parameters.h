#pragma once
// The optional texel parameter groups of a scene, each on a surface::TexelLayout: the geometric
// maps (a displacement, one height per node; a normal map, tangent-space x, y per node) on one
// lattice, and the appearance maps (base colour, sRGB RGB per node; roughness and metallic per
// node) on a finer one of their own. Only the groups the scene asks for exist: a run without
// maps has no buffers, no shader defines and no passes for them.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/program.h"
#include "gl/texture.h"
#include "maps/map_effects.h"
#include "surface/surface_maps.h"
#include "surface/texel_layout.h"
#include "optim/parameter_group.h"
#include "optim/updates.h"
#include "render/patch_renderer.h"

namespace subdfit::maps {

struct MapSettings {
    int resolution = 8;             // cells per ptex-face edge of the geometric maps
    int appearanceResolution = 16;  // ... of the appearance maps
    // Texels per side of an appearance atlas (surface/appearance_atlas.h); 0: per-face tiles.
    int appearanceAtlas = 0;
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;  // with a displacement
    // Each kind's perturbation and learning rate (kinds/map_kinds.h has the defaults and units).
    std::array<optim::GroupSettings, kinds::kMapKindCount> groups = [] {
        std::array<optim::GroupSettings, kinds::kMapKindCount> out;
        for (const kinds::MapKindInfo& i : kinds::kMapKinds)
            out[size_t(i.kind)] = {.epsilon = i.epsilon, .learningRate = i.learningRate};
        return out;
    }();
    optim::GroupSettings& of(MapKind kind) { return groups[size_t(kind)]; }
    const optim::GroupSettings& of(MapKind kind) const { return groups[size_t(kind)]; }
    // (I + λL)⁻¹ on the node graph, as for the cage: texel estimates are noisy one by one.
    float smoothing = 2.0f;
    int smoothingIterations = 8;
};

// Which θ a raster pass reads: the current one, or a perturbed one.
enum class ParameterVersion { Current, Plus, Minus };

class MapParameters {
public:
    MapParameters(const mesh::PolygonMesh& cage, MapEffects effects, const MapSettings& settings);

    // The geometric maps' lattice (resolution 0 when the scene has none), and the appearance
    // maps' (likewise).
    const surface::TexelLayout& layout() const { return layout_; }
    const surface::TexelLayout& appearanceLayout() const { return appearanceLayout_; }
    const surface::TexelLayout& layoutOf(const optim::ParameterGroup& group) const;
    // Whether `group` lives on an atlas's texel grid (placed by the corners' atlas coordinates).
    bool inAtlas(const optim::ParameterGroup& group) const;
    // With an atlas: its corners' coordinates, 4 per ptex face (what setAppearanceUvs was given;
    // all 0 until then).
    surface::AppearanceAtlas appearanceAtlas() const;
    void setAppearanceUvs(const std::vector<glm::vec2>& cornerUvs);
    // The reference's textures the appearance lattice carries unchanged (SurfaceMaps::occlusion,
    // emissive, and with an atlas normalTexture; empty ones are dropped), which the patch pass
    // then applies.
    void setCarriedTextures(const surface::SurfaceMaps& maps);
    // ... copied into `maps`.
    void readCarriedTextures(surface::SurfaceMaps& maps) const;
    // Where `group`'s lattice starts in the face-node table the shaders read.
    int tableOffsetOf(const optim::ParameterGroup& group) const;
    MapEffects effects() const { return effects_; }
    surface::ShadingNormal shadingNormal() const { return settings_.shadingNormal; }
    void setShadingNormal(surface::ShadingNormal s) { settings_.shadingNormal = s; }  // the next pass draws with it
    // The group of `kind`; null where the scene does not fit it.
    optim::ParameterGroup* group(MapKind kind) { return groups_[size_t(kind)].get(); }
    const optim::ParameterGroup* group(MapKind kind) const { return groups_[size_t(kind)].get(); }
    optim::ParameterGroup* displacement() { return group(MapKind::Displacement); }
    // The kind of one of this object's groups, and whether it lies on the appearance lattice.
    MapKind kindOf(const optim::ParameterGroup& group) const;
    bool inAppearance(const optim::ParameterGroup& group) const;
    std::vector<optim::ParameterGroup*> groups();

    // The patch pass's maps: θ± of the group being perturbed (`perturbed`, may be null) and θ of
    // the others. Valid while this object lives.
    render::PatchMaps forRaster(ParameterVersion version, const optim::ParameterGroup* perturbed = nullptr) const;
    // The face-node table (and an atlas's corner coordinates), for a pass that looks nodes up (G).
    void bindFaceNodes() const;

    // Preconditions `group`'s gradient on its node graph and applies Adam to it at `learningRate`.
    void update(gl::ProgramCache& programs, optim::ParameterGroup& group, float learningRate);

private:
    MapEffects effects_;
    surface::TexelLayout layout_, appearanceLayout_;
    MapSettings settings_;
    gl::Buffer faceNodes_;                  // layout_'s table, appearanceLayout_'s, then layout_'s halo
    std::vector<glm::vec2> appearanceUvs_;  // with an atlas: 4 per ptex face
    gl::Buffer appearanceUvBuffer_;
    gl::BufferTexture faceNodesView_, appearanceUvView_;  // as the passes read them (maps.glsl)
    // A carried texture's values, their buffer and its view as the patch pass reads it (none
    // while empty).
    struct Carried {
        std::vector<float> values;
        std::unique_ptr<gl::Buffer> buffer;
        std::unique_ptr<gl::BufferTexture> view;
        void set(const std::vector<float>& v, int channels);
    };
    Carried normalTexture_, occlusion_, emissive_;
    optim::Adjacency adjacency_, appearanceAdjacency_;
    gl::Buffer scratch_;  // Jacobi ping-pong partner, sized for the largest group
    std::array<std::unique_ptr<optim::ParameterGroup>, kinds::kMapKindCount> groups_;  // by kind; null: not fitted
    // θ, θ+ and θ− of each group the patch pass shades with, as it reads them: one fetch a node.
    struct NodeViews {
        gl::BufferTexture current, plus, minus;
    };
    std::map<const optim::ParameterGroup*, NodeViews> views_;
    const gl::BufferTexture& viewOf(const optim::ParameterGroup& group, ParameterVersion v) const;
};

}  // namespace subdfit::maps
