#include "simplify/compare/triangle_baseline.h"

#include <limits>

#include "fit/fit_scene.h"
#include "mesh/mesh_geometry.h"
#include "io/external_program.h"
#include "simplify/cage/decimate.h"
#include "simplify/compare/textured_baselines.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

// Both start from the welded reference, made once and shared.
class WeldedReference {
public:
    explicit WeldedReference(const fit::FitScene& scene) : scene_(scene) {}
    const mesh::PolygonMesh& get() const {
        if (!welded_) welded_ = std::make_shared<const mesh::PolygonMesh>(weldedTriangles(scene_.reference));
        return *welded_;
    }

private:
    const fit::FitScene& scene_;
    mutable std::shared_ptr<const mesh::PolygonMesh> welded_;
};

class Decimation final : public TriangleBaseline {
public:
    explicit Decimation(std::shared_ptr<const WeldedReference> welded) : welded_(std::move(welded)) {}
    std::string name() const override { return "decimation"; }
    std::string title() const override { return "decimation + Draco"; }
    Quality ship(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                 const BaselineSettings& settings) const override {
        if (shipsMaterials(scene)) return texturedDecimationBaseline(programs, scene, budget, settings);
        return decimationBaseline(programs, scene, welded_->get(), budget, settings, {decimate, "decimated.glb"});
    }
    // Every triangle holds the look where it ships normals (the reference's own: at every
    // triangle it ships the reference as it is where its normals split), or the reference is
    // flat and it ships none; textured, every texel too where its images are at full size.
    Holds holds(const fit::FitScene& scene, const Quality& shipped) const override {
        if (shipped.details.value("over_budget", true)) return Holds::Part;
        int wholeTriangles = scene.reference.faceCount();
        bool everyTexel = true;
        if (shipsMaterials(scene)) {
            everyTexel = shipped.details.value("texture_scale", 0.0) == 1.0;
        } else {
            const bool normals = shipped.details.value(nlohmann::json::json_pointer("/encoding/normals"), false);
            wholeTriangles =
                normals || shadedFlat(scene) ? welded_->get().faceCount() : std::numeric_limits<int>::max();
        }
        if (shipped.details.value("triangles", 0) < wholeTriangles) return Holds::Part;
        return everyTexel ? Holds::Whole : Holds::EveryTriangle;
    }

private:
    std::shared_ptr<const WeldedReference> welded_;
};

// What a pipeline that must reach a count whatever the topology runs: meshoptimizer's clustering
// (simplifySloppy) + Draco, searched as the decimation is. Untextured only: clusters ignore seams.
class Clustering final : public TriangleBaseline {
public:
    explicit Clustering(std::shared_ptr<const WeldedReference> welded) : welded_(std::move(welded)) {}
    std::string name() const override { return "clustering"; }
    std::string title() const override { return "clustering + Draco"; }
    Quality ship(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                 const BaselineSettings& settings) const override {
        return decimationBaseline(programs, scene, welded_->get(), budget, settings, {cluster, "clustered.glb"});
    }

private:
    std::shared_ptr<const WeldedReference> welded_;
};

class Gltfpack final : public TriangleBaseline {
public:
    explicit Gltfpack(std::shared_ptr<const WeldedReference> welded) : welded_(std::move(welded)) {}
    std::string name() const override { return "gltfpack"; }
    std::string title() const override { return "gltfpack"; }
    std::string unavailable() const override {
        return io::findProgram("gltfpack") ? "" : "gltfpack is not on PATH (Debian: apt-get install gltfpack)";
    }
    Quality ship(gl::ProgramCache& programs, const fit::FitScene& scene, std::uintmax_t budget,
                 const BaselineSettings& settings) const override {
        const std::optional<Quality> q = shipsMaterials(scene)
                                             ? texturedGltfpackBaseline(programs, scene, budget, settings)
                                             : gltfpackBaseline(programs, scene, welded_->get(), budget, settings);
        if (!q) throw Error("gltfpack: not on PATH");  // unavailable() said so first
        return *q;
    }

private:
    std::shared_ptr<const WeldedReference> welded_;
};

}  // namespace

bool shipsMaterials(const fit::FitScene& scene) {
    return scene.shading != render::ShadingModel::Geometry && scene.reference.materials != nullptr;
}

bool shadedFlat(const fit::FitScene& scene) {
    const mesh::PolygonMesh& r = scene.reference;
    if (r.vertexCount() != int(r.faceIndices.size())) return false;
    const std::vector<glm::vec3> normals = mesh::shadingNormals(r);
    for (size_t first = 0, f = 0; f < r.faceSizes.size(); first += size_t(r.faceSizes[f]), ++f) {
        if (r.faceSizes[f] != 3) return false;
        const glm::vec3 a = r.positions[size_t(r.faceIndices[first])],
                        b = r.positions[size_t(r.faceIndices[first + 1])],
                        c = r.positions[size_t(r.faceIndices[first + 2])];
        const glm::vec3 face = glm::cross(b - a, c - a);
        const float length = glm::length(face);
        if (!(length > 0.0f)) continue;  // a degenerate triangle covers no pixel
        for (size_t k = 0; k < 3; ++k)
            if (glm::dot(normals[size_t(r.faceIndices[first + k])], face / length) < 0.9999f) return false;
    }
    return true;
}

std::vector<std::unique_ptr<TriangleBaseline>> triangleBaselinesFor(const fit::FitScene& scene, CompareLevel level) {
    const auto welded = std::make_shared<const WeldedReference>(scene);
    std::vector<std::unique_ptr<TriangleBaseline>> baselines;
    baselines.push_back(std::make_unique<Decimation>(welded));
    if (level >= CompareLevel::Fast) baselines.push_back(std::make_unique<Gltfpack>(welded));
    if (level >= CompareLevel::All && !shipsMaterials(scene)) baselines.push_back(std::make_unique<Clustering>(welded));
    return baselines;
}

}  // namespace subdfit::simplify
