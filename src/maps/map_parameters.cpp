#include "maps/map_parameters.h"

#include <algorithm>
#include <sstream>

#include "bindings.h"
#include "util/error.h"

namespace subdfit::maps {

namespace {

optim::Adjacency uploadAdjacency(const surface::TexelLayout& layout) {
    const auto graph = surface::nodeAdjacency(layout);
    return {gl::Buffer::fromVector(graph.offsets), gl::Buffer::fromVector(graph.neighbors), layout.nodeCount};
}

}  // namespace

MapParameters::MapParameters(const mesh::PolygonMesh& cage, MapEffects effects, const MapSettings& settings)
    : effects_(effects),
      layout_(surface::buildTexelLayout(cage, settings.resolution)),
      settings_(settings),
      faceNodes_(gl::Buffer::fromVector(layout_.faceNodes)),
      adjacency_(uploadAdjacency(layout_)),
      scratch_(GLsizeiptr(std::max(1, layout_.nodeCount)) * 2 * GLsizeiptr(sizeof(float))) {
    if (effects.displacement)
        displacement_ = std::make_unique<optim::ParameterGroup>(optim::GroupKind::Displacement,
            "displacement", std::vector<float>(size_t(layout_.nodeCount), 0.0f), settings.displacement,
            SUBDFIT_SEED_DISPLACEMENT);
    if (effects.normalMap)
        normalMap_ = std::make_unique<optim::ParameterGroup>(optim::GroupKind::NormalMap,
            "normal_map", std::vector<float>(size_t(layout_.nodeCount) * 2, 0.0f), settings.normalMap,
            SUBDFIT_SEED_NORMAL_MAP);
}

std::vector<optim::ParameterGroup*> MapParameters::groups() {
    std::vector<optim::ParameterGroup*> out;
    if (displacement_) out.push_back(displacement_.get());
    if (normalMap_) out.push_back(normalMap_.get());
    return out;
}

namespace {

const gl::Buffer& version(const optim::ParameterGroup& group, ParameterVersion v) {
    return v == ParameterVersion::Plus ? group.thetaPlus : v == ParameterVersion::Minus ? group.thetaMinus : group.theta;
}

}  // namespace

render::PatchMaps MapParameters::forRaster(ParameterVersion v, const optim::ParameterGroup* perturbed) const {
    auto bind = [this, v, perturbed] {
        auto of = [&](const optim::ParameterGroup& g) { return &g == perturbed ? v : ParameterVersion::Current; };
        faceNodes_.bindStorage(SUBDFIT_SSBO_FACE_NODES);
        if (displacement_) version(*displacement_, of(*displacement_)).bindStorage(SUBDFIT_SSBO_DISPLACEMENT);
        if (normalMap_) version(*normalMap_, of(*normalMap_)).bindStorage(SUBDFIT_SSBO_NORMAL_MAP);
    };
    return {.displacement = effects_.displacement, .normalMap = effects_.normalMap, .resolution = layout_.resolution,
            .bind = bind};
}

void MapParameters::bindForGradient() const {
    faceNodes_.bindStorage(SUBDFIT_SSBO_FACE_NODES);
    if (displacement_) displacement_->gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_DISPLACEMENT);
    if (normalMap_) normalMap_->gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_NORMAL_MAP);
}

void MapParameters::update(gl::ProgramCache& programs, optim::ParameterGroup& group, float learningRate) {
    optim::precondition(programs, group, adjacency_, settings_.smoothing, settings_.smoothingIterations, scratch_);
    optim::adamStep(programs, group, group.gradientSmooth, learningRate);
}

}  // namespace subdfit::maps
