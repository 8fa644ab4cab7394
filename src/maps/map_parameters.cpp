#include "maps/map_parameters.h"

#include <algorithm>
#include <array>

#include "bindings.h"
#include "subdiv/topology.h"
#include "util/error.h"

namespace subdfit::maps {
namespace {

optim::Adjacency uploadAdjacency(const surface::TexelLayout& layout) {
    if (layout.nodeCount == 0) return {gl::Buffer(sizeof(int)), gl::Buffer(sizeof(int)), 0};
    const auto graph = surface::nodeAdjacency(layout);
    return {gl::Buffer::fromVector(graph.offsets), gl::Buffer::fromVector(graph.neighbors), layout.nodeCount};
}

std::vector<int> concatenated(const std::vector<int>& a, const std::vector<int>& b, const std::vector<int>& c) {
    std::vector<int> out(a);
    out.insert(out.end(), b.begin(), b.end());
    out.insert(out.end(), c.begin(), c.end());
    return out;
}

// A kind's group on `layout`, each node at the kind's initial values.
std::unique_ptr<optim::ParameterGroup> makeGroup(const kinds::MapKindInfo& kind, const surface::TexelLayout& layout,
                                                 const optim::GroupSettings& settings) {
    std::vector<float> initial(size_t(layout.nodeCount) * size_t(kind.channels));
    for (size_t k = 0; k < initial.size(); ++k) initial[k] = kind.initial[k % size_t(kind.channels)];
    return std::make_unique<optim::ParameterGroup>(optim::GroupKind::Map, std::string(kind.name), initial, settings,
                                                   kind.seed);
}

const gl::Buffer& version(const optim::ParameterGroup& group, ParameterVersion v) {
    return v == ParameterVersion::Plus    ? group.thetaPlus
           : v == ParameterVersion::Minus ? group.thetaMinus
                                          : group.theta;
}

surface::TexelLayout appearanceLayoutFor(const mesh::PolygonMesh& cage, MapEffects effects,
                                         const MapSettings& settings) {
    if (!effects.appearance()) return {};
    if (settings.appearanceAtlas > 0) return surface::atlasLattice(settings.appearanceAtlas);
    return surface::buildTexelLayout(cage, settings.appearanceResolution);
}

}  // namespace

MapParameters::MapParameters(const mesh::PolygonMesh& cage, MapEffects effects, const MapSettings& settings)
    : effects_(effects),
      layout_(effects.geometric() ? surface::buildTexelLayout(cage, settings.resolution) : surface::TexelLayout{}),
      appearanceLayout_(appearanceLayoutFor(cage, effects, settings)),
      settings_(settings),
      faceNodes_(gl::Buffer::fromVector(concatenated(layout_.faceNodes, appearanceLayout_.faceNodes, layout_.halo))),
      appearanceUvs_(effects.appearance() && settings.appearanceAtlas > 0 ? 4 * size_t(subdiv::ptexFaceCount(cage))
                                                                          : 0),
      appearanceUvBuffer_(GLsizeiptr(std::max<size_t>(1, appearanceUvs_.size())) * GLsizeiptr(sizeof(glm::vec2)),
                          appearanceUvs_.empty() ? nullptr : appearanceUvs_.data()),
      faceNodesView_(faceNodes_, GL_R32I),
      appearanceUvView_(appearanceUvBuffer_, GL_RG32F),
      adjacency_(uploadAdjacency(layout_)),
      appearanceAdjacency_(uploadAdjacency(appearanceLayout_)),
      scratch_(GLsizeiptr(std::max({1, 2 * layout_.nodeCount, 3 * appearanceLayout_.nodeCount})) *
               GLsizeiptr(sizeof(float))) {
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds) {
        if (!effects.has(kind.kind)) continue;
        auto& g = groups_[size_t(kind.kind)];
        g = makeGroup(kind, kind.lattice == kinds::MapLattice::Appearance ? appearanceLayout_ : layout_,
                      settings.of(kind.kind));
        // The raster pass reads its kinds' nodes through views; the heights are read as storage.
        if (kind.rasterDefine.empty()) continue;
        views_.emplace(g.get(), NodeViews{gl::BufferTexture::ofFloats(g->theta, kind.channels),
                                          gl::BufferTexture::ofFloats(g->thetaPlus, kind.channels),
                                          gl::BufferTexture::ofFloats(g->thetaMinus, kind.channels)});
    }
}

MapKind MapParameters::kindOf(const optim::ParameterGroup& group) const {
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds)
        if (groups_[size_t(kind.kind)].get() == &group) return kind.kind;
    throw Error("map parameters: " + group.name() + " is not one of their groups");
}

bool MapParameters::inAppearance(const optim::ParameterGroup& group) const {
    return kinds::info(kindOf(group)).lattice == kinds::MapLattice::Appearance;
}

const gl::BufferTexture& MapParameters::viewOf(const optim::ParameterGroup& group, ParameterVersion v) const {
    const NodeViews& views = views_.at(&group);
    return v == ParameterVersion::Plus ? views.plus : v == ParameterVersion::Minus ? views.minus : views.current;
}

std::vector<optim::ParameterGroup*> MapParameters::groups() {
    std::vector<optim::ParameterGroup*> out;
    for (const auto& g : groups_)
        if (g) out.push_back(g.get());
    return out;
}

bool MapParameters::inAtlas(const optim::ParameterGroup& group) const {
    return inAppearance(group) && !appearanceUvs_.empty();
}

surface::AppearanceAtlas MapParameters::appearanceAtlas() const {
    if (appearanceUvs_.empty()) return {};
    return {.size = settings_.appearanceAtlas, .cornerUvs = appearanceUvs_};
}

void MapParameters::setAppearanceUvs(const std::vector<glm::vec2>& cornerUvs) {
    SUBDFIT_CHECK(!appearanceUvs_.empty() && cornerUvs.size() == appearanceUvs_.size());
    appearanceUvs_ = cornerUvs;
    appearanceUvBuffer_.upload(appearanceUvs_.data(), GLsizeiptr(appearanceUvs_.size() * sizeof(glm::vec2)));
}

void MapParameters::Carried::set(const std::vector<float>& v, int channels) {
    values = v;
    view.reset();  // before the buffer it views
    buffer = v.empty() ? nullptr : std::make_unique<gl::Buffer>(gl::Buffer::fromVector(v));
    if (buffer) view = std::make_unique<gl::BufferTexture>(gl::BufferTexture::ofFloats(*buffer, channels));
}

void MapParameters::setCarriedTextures(const surface::SurfaceMaps& maps) {
    SUBDFIT_CHECK(effects_.appearance() && (maps.normalTexture.empty() || !appearanceUvs_.empty()));
    const size_t texels = size_t(appearanceLayout_.nodeCount);
    SUBDFIT_CHECK(maps.normalTexture.empty() || maps.normalTexture.size() == 3 * texels);
    SUBDFIT_CHECK(maps.occlusion.empty() || maps.occlusion.size() == texels);
    SUBDFIT_CHECK(maps.emissive.empty() || maps.emissive.size() == 3 * texels);
    normalTexture_.set(maps.normalTexture, 3);
    occlusion_.set(maps.occlusion, 1);
    emissive_.set(maps.emissive, 3);
}

void MapParameters::readCarriedTextures(surface::SurfaceMaps& maps) const {
    maps.normalTexture = normalTexture_.values;
    maps.occlusion = occlusion_.values;
    maps.emissive = emissive_.values;
}

const surface::TexelLayout& MapParameters::layoutOf(const optim::ParameterGroup& group) const {
    return inAppearance(group) ? appearanceLayout_ : layout_;
}

int MapParameters::tableOffsetOf(const optim::ParameterGroup& group) const {
    return inAppearance(group) ? int(layout_.faceNodes.size()) : 0;
}

render::PatchMaps MapParameters::forRaster(ParameterVersion v, const optim::ParameterGroup* perturbed) const {
    auto bind = [this, v, perturbed] {
        auto of = [&](const optim::ParameterGroup& g) { return &g == perturbed ? v : ParameterVersion::Current; };
        bindFaceNodes();
        // Each kind's binding is where its glsl reads it (bindings.h).
        constexpr std::array<GLuint, kinds::kMapKindCount> kUnits{SUBDFIT_SSBO_DISPLACEMENT, SUBDFIT_UNIT_MAP_NORMAL,
                                                                  SUBDFIT_UNIT_MAP_BASE_COLOR,
                                                                  SUBDFIT_UNIT_MAP_METALLIC_ROUGHNESS};
        for (const kinds::MapKindInfo& kind : kinds::kMapKinds) {
            const optim::ParameterGroup* g = group(kind.kind);
            if (!g) continue;
            if (kind.rasterDefine.empty()) version(*g, of(*g)).bindStorage(kUnits[size_t(kind.kind)]);
            else viewOf(*g, of(*g)).bind(kUnits[size_t(kind.kind)]);
        }
        if (normalTexture_.view) normalTexture_.view->bind(SUBDFIT_UNIT_CARRIED_ATLAS_NORMAL);
        if (occlusion_.view) occlusion_.view->bind(SUBDFIT_UNIT_CARRIED_OCCLUSION);
        if (emissive_.view) emissive_.view->bind(SUBDFIT_UNIT_CARRIED_EMISSIVE);
    };
    return {.kinds = effects_,
            .limitShading = settings_.shadingNormal == surface::ShadingNormal::Limit,
            .resolution = std::max(layout_.resolution, 1),
            .appearanceResolution = std::max(appearanceLayout_.resolution, 1),
            .appearanceAtlas = !appearanceUvs_.empty(),
            .atlasNormal = normalTexture_.buffer != nullptr,
            .carriedOcclusion = occlusion_.buffer != nullptr,
            .carriedEmissive = emissive_.buffer != nullptr,
            .appearanceTable = int(layout_.faceNodes.size()),
            .haloTable = int(layout_.faceNodes.size() + appearanceLayout_.faceNodes.size()),
            .bind = bind};
}

void MapParameters::bindFaceNodes() const {
    faceNodesView_.bind(SUBDFIT_UNIT_FACE_NODES);
    if (!appearanceUvs_.empty()) appearanceUvView_.bind(SUBDFIT_UNIT_APPEARANCE_UVS);
}

void MapParameters::update(gl::ProgramCache& programs, optim::ParameterGroup& group, float learningRate) {
    optim::precondition(programs, group, inAppearance(group) ? appearanceAdjacency_ : adjacency_, settings_.smoothing,
                        settings_.smoothingIterations, scratch_);
    optim::adamStep(programs, group, group.gradientSmooth, learningRate);
}

}  // namespace subdfit::maps
