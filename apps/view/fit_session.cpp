#include "fit_session.h"

#include "fit/checkpoint.h"
#include "gl/platform_defines.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

namespace subdfit::view {
namespace {

using Clock = std::chrono::steady_clock;

// The knobs the viewer may have turned, carried from one fitter to its rebuilt successor.
struct Knobs {
    std::vector<float> epsilon, learningRate;
    std::vector<bool> optimised;
};

Knobs knobsOf(fit::CageFitter& fitter) {
    Knobs knobs;
    for (auto* g : fitter.groups()) {
        knobs.epsilon.push_back(g->settings().epsilon);
        knobs.learningRate.push_back(fitter.baseLearningRate(*g));
        knobs.optimised.push_back(fitter.optimised(*g));
    }
    return knobs;
}

void apply(const Knobs& knobs, fit::CageFitter& fitter) {
    const auto groups = fitter.groups();
    for (size_t k = 0; k < groups.size(); ++k) {
        fitter.setRates(*groups[k], knobs.epsilon[k], knobs.learningRate[k]);
        fitter.setOptimised(*groups[k], knobs.optimised[k]);
    }
}

}  // namespace

FitInputs loadFitInputs(const fit::FitOptions& options) {
    return {mesh::loadMesh(options.cage), mesh::loadMesh(options.reference)};
}

FitSession::FitSession(const fit::FitOptions& options, FitInputs inputs)
    : options_(options), programs_(gl::platformDefines()), started_(Clock::now()) {
    fit::validate(options_);
    scene_ = std::make_unique<fit::FitScene>(options_, programs_, std::move(inputs.cage), inputs.reference);
    fitter_ = std::make_unique<fit::CageFitter>(programs_, scene_->cage, fit::fitSettings(options_));

    // What runFit measures before its first step, for the report that save() writes.
    render::RenderTarget image(scene_->holdout.resolution(), scene_->holdout.resolution());
    fitter_->render(scene_->holdout.camera(0), image);
    history_.beforeImage = image.readColor();
    history_.trainBefore = fit::score(*fitter_, scene_->training);
    history_.holdoutBefore = fit::score(*fitter_, scene_->holdout);

    if (options_.resume) {
        const auto fingerprint = fit::checkpointFingerprint(options_, scene_->cage, scene_->reference);
        if (const auto saved = fit::readCheckpoint(options_.out / "checkpoint.bin", fingerprint)) {
            fitter_->restore(*saved);
            history_.firstStep = saved->steps;
        }
    }
}

void FitSession::step() {
    if (!anythingOptimised()) return;  // a step would only count itself
    const auto began = Clock::now();
    const auto views = fit::viewsForStep(options_, fitter_->stepsTaken());
    for (int sample = 0; sample < options_.samplesPerStep; ++sample) fitter_->accumulate(scene_->training, views, true);
    fitter_->update();
    // The readback waits for the step to finish, so the viewer's time budget sees its real cost.
    losses_.push_back(fitter_->takeMeanLoss());
    history_.fitSeconds += std::chrono::duration<double>(Clock::now() - began).count();
}

bool FitSession::anythingOptimised() {
    for (auto* g : fitter_->groups())
        if (fitter_->optimised(*g)) return true;
    return false;
}

void FitSession::setTessLevel(int level) {
    fit::FitOptions options = options_;
    options.tessLevel = level;
    fit::validate(options);
    const Knobs knobs = knobsOf(*fitter_);
    const auto state = fitter_->state();
    auto rebuilt = std::make_unique<fit::CageFitter>(programs_, scene_->cage, fit::fitSettings(options));
    rebuilt->restore(state);
    apply(knobs, *rebuilt);
    fitter_ = std::move(rebuilt);
    options_ = options;
}

nlohmann::json FitSession::save(const context::GlContext& context, const std::filesystem::path& out) {
    fit::FitOptions options = options_;
    options.out = out;
    // The report's settings say what the vertices were fitted with last, knobs included.
    auto& vertices = fitter_->vertexGroup();
    options.epsilon = vertices.settings().epsilon;
    options.learningRate = fitter_->baseLearningRate(vertices);
    fit::validate(options);
    fit::FitHistory history = history_;
    history.steps = fitter_->stepsTaken();
    history.seconds = std::chrono::duration<double>(Clock::now() - started_).count();
    auto report = fit::writeFitResults(options, programs_, context, *scene_, *fitter_, history);
    fit::writeCheckpoint(out / "checkpoint.bin", fit::checkpointFingerprint(options, scene_->cage, scene_->reference),
                         fitter_->state());
    return report;
}

}  // namespace subdfit::view
