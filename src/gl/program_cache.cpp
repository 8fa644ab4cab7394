#include "gl/program_cache.h"

#include "util/error.h"

namespace subdfit::gl {

const Program& ProgramCache::get(const ProgramSpec& spec, VariantBits variant, const Defines& values) {
    auto& slot = programs_[{spec.name, variant, values}];
    if (!slot) {
        SUBDFIT_CHECK(spec.flagDefines.size() >= 32 || (variant >> spec.flagDefines.size()) == 0);
        Defines all = global_;
        all.insert(values.begin(), values.end());
        for (size_t bit = 0; bit < spec.flagDefines.size(); ++bit)
            if (variant & (VariantBits(1) << bit)) all[spec.flagDefines[bit]] = "";
        slot = std::make_unique<Program>(spec.stages, all);
        ProgramVariant described{spec.name, {}, all};
        for (const auto& stage : spec.stages) described.files.push_back(stage.file);
        variants_.push_back(std::move(described));
    }
    return *slot;
}

}  // namespace subdfit::gl
