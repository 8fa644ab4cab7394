#pragma once
// One group of optimised parameters living on the GPU (e.g. the cage's control vertices):
// θ, the perturbed θ±, the gradient accumulator and Adam's moments, with the group's own ε
// and learning rate. Groups the scene does not optimise are never created.
#include <cstdint>
#include <string>
#include <vector>

#include "gl/buffer.h"

namespace subdfit::optim {

// What a group's parameters are: the cage's vertices, a map's texels (which map: its kind in
// kinds/map_kinds.h), or something else (a benchmark's). The fit tells its groups apart by this.
enum class GroupKind { Vertices, Map, Other };

struct GroupSettings {
    float epsilon = 0.01f;        // perturbation magnitude, in the group's units
    float learningRate = 0.002f;  // Adam step size before annealing, same units (the one source)
    float beta1 = 0.9f;
    float beta2 = 0.99f;
    // One Adam second moment for the whole group instead of one per parameter: keeps a
    // preconditioned (smoothed) gradient's step smooth. Used for cage vertices.
    bool sharedMoment = false;
    // c of the noise gate (glsl/adam.comp): the step shrinks where the gradient's running mean is
    // within c times its expected noise of 0; 0: plain Adam.
    float noiseGate = 0.0f;
};

class ParameterGroup {
public:
    // `seedSalt` (SUBDFIT_SEED_* in bindings.h) gives each group its own stream of signs.
    ParameterGroup(GroupKind kind, std::string name, const std::vector<float>& initial, GroupSettings settings,
                   std::uint32_t seedSalt = 0);

    GroupKind kind() const { return kind_; }
    const std::string& name() const { return name_; }
    std::uint32_t seedSalt() const { return seedSalt_; }
    int count() const { return count_; }
    const GroupSettings& settings() const { return settings_; }
    GroupSettings& settings() { return settings_; }

    gl::Buffer theta, thetaPlus, thetaMinus, gradient, gradientSmooth, moment1, moment2;
    gl::Buffer groupMoment2;  // one float: the second moment shared by the group (sharedMoment)
    // What G accumulates, in fixed point (glsl/fixed_point.glsl: two uints per parameter) so that
    // the sum does not depend on the order of the GPU's atomics; resolved into `gradient`.
    gl::Buffer gradientSum;
    int adamSteps = 0;

    std::vector<float> read() const { return theta.read<float>(); }
    // Replaces θ (count() values), e.g. with maps baked elsewhere.
    void write(const std::vector<float>& values);
    // How many times θ was written (write(), an Adam step, a pass that calls changed()): what
    // was computed from one version of θ holds while the version stays.
    std::uint64_t version() const { return version_; }
    void changed() { ++version_; }

private:
    GroupKind kind_;
    std::string name_;
    int count_;
    GroupSettings settings_;
    std::uint32_t seedSalt_;
    std::uint64_t version_ = 0;
};

}  // namespace subdfit::optim
