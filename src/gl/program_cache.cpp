#include "gl/program_cache.h"

namespace subdfit::gl {

const Program& ProgramCache::get(const std::string& name, const std::vector<ShaderStage>& stages,
                                 const Defines& defines) {
    Defines all = global_;
    all.insert(defines.begin(), defines.end());
    std::string key = name;
    for (const auto& stage : stages) key += "|" + stage.file;
    key += "|" + defineBlock(all);
    auto& slot = programs_[key];
    if (!slot) {
        slot = std::make_unique<Program>(stages, all);
        ProgramVariant variant{name, {}, all};
        for (const auto& stage : stages) variant.files.push_back(stage.file);
        variants_.push_back(std::move(variant));
    }
    return *slot;
}

}  // namespace subdfit::gl
