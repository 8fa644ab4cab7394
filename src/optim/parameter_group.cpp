#include "optim/parameter_group.h"
#include "util/error.h"

namespace subdfit::optim {

ParameterGroup::ParameterGroup(GroupKind kind, std::string name, const std::vector<float>& initial,
                               GroupSettings settings, std::uint32_t seedSalt)
    : theta(gl::Buffer::fromVector(initial)),
      thetaPlus(theta.bytes()),
      thetaMinus(theta.bytes()),
      gradient(theta.bytes()),
      gradientSmooth(theta.bytes()),
      moment1(theta.bytes()),
      moment2(theta.bytes()),
      groupMoment2(sizeof(float)),
      gradientSum(2 * theta.bytes()),
      kind_(kind),
      name_(std::move(name)),
      count_(int(initial.size())),
      settings_(settings),
      seedSalt_(seedSalt) {}

void ParameterGroup::write(const std::vector<float>& values) {
    SUBDFIT_CHECK(int(values.size()) == count_);
    theta.upload(values.data(), GLsizeiptr(values.size() * sizeof(float)));
    changed();
}

}  // namespace subdfit::optim
