#include "sge/parameter_group.h"

namespace subdfit::sge {

ParameterGroup::ParameterGroup(std::string name, const std::vector<float>& initial, GroupSettings settings,
                               std::uint32_t seedSalt)
    : theta(gl::Buffer::fromVector(initial)),
      thetaPlus(theta.bytes()),
      thetaMinus(theta.bytes()),
      gradient(theta.bytes()),
      gradientSmooth(theta.bytes()),
      moment1(theta.bytes()),
      moment2(theta.bytes()),
      name_(std::move(name)),
      count_(int(initial.size())),
      settings_(settings),
      seedSalt_(seedSalt) {}

}  // namespace subdfit::sge
