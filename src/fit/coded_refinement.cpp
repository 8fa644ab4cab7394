#include "fit/coded_refinement.h"

#include <chrono>
#include <utility>

#include "codec/node_coding.h"
#include "fit/state_blend.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

// Refined heights are rougher and code larger: where `values` do not fit (`fits`, with the group
// holding them), they become the most of the way from `start` to them that fits, if any.
bool withinBudget(optim::ParameterGroup& heights, const std::vector<float>& start, std::vector<float>& values,
                  const std::function<bool()>& fits) {
    if (!fits) return true;
    heights.write(values);
    if (fits()) return true;
    const float t = furthestThatHolds(
        [&](float t) {
            heights.write(between(start, values, t));
            return fits();
        },
        kBudgetBisections);
    if (t == 0.0f) return false;
    values = between(start, values, t);
    return true;
}

}  // namespace

CodedRefinement refineAsCoded(FitRun& run, const CodedRefinementSettings& settings,
                              const std::function<double()>& judge, const std::function<bool()>& fits) {
    const auto began = std::chrono::steady_clock::now();
    CageFitter& fitter = run.fitter();
    optim::ParameterGroup* heights = fitter.maps() ? fitter.maps()->displacement() : nullptr;
    SUBDFIT_CHECK(heights && settings.steps >= 0 && settings.judgeEvery > 0);
    const surface::TexelLayout& layout = fitter.maps()->layout();
    const auto coded = [&](const std::vector<float>& values) {
        return codec::codedValues(layout, values, 1, settings.bits);
    };

    // Only the heights take turns, at a step that is a fraction of the coding's.
    std::vector<std::pair<optim::ParameterGroup*, bool>> turns;
    for (optim::ParameterGroup* group : fitter.groups()) {
        turns.emplace_back(group, fitter.optimised(*group));
        fitter.setOptimised(*group, group == heights);
    }
    const optim::GroupSettings rates = heights->settings();
    const float scale = fitter.learningRateScale();
    std::vector<float> fitted = heights->read();
    const std::vector<float> start = fitted;
    fitter.setRates(*heights, rates.epsilon,
                    settings.stepFraction * codec::quantisationFor(fitted, 1, 0, settings.bits).step);
    fitter.setLearningRateScale(1.0f);

    CodedRefinement result;
    heights->write(coded(fitted));
    result.startLoss = result.bestLoss = judge();
    std::vector<float> best = fitted;
    const int first = fitter.stepsTaken();
    for (int worse = 0; result.steps < settings.steps && worse < settings.judgedWorse;) {
        const auto views = viewsForStep(run.options(), first + result.steps);
        heights->write(coded(fitted));
        for (int sample = 0; sample < run.options().samplesPerStep; ++sample)
            fitter.accumulate(run.scene().training, views, false);
        heights->write(fitted);  // Adam moves the heights as fitted
        fitter.update();
        fitted = heights->read();
        if (++result.steps % settings.judgeEvery != 0) continue;
        if (!withinBudget(*heights, start, fitted, fits)) {
            ++result.overBudget;
            ++worse;
            continue;
        }
        heights->write(coded(fitted));
        if (const double loss = judge(); loss < result.bestLoss) {
            result.bestLoss = loss;
            result.bestStep = result.steps;
            best = fitted;
            worse = 0;
        } else {
            ++worse;
        }
    }
    heights->write(best);
    fitter.setRates(*heights, rates.epsilon, rates.learningRate);
    fitter.setLearningRateScale(scale);
    for (const auto& [group, on] : turns) fitter.setOptimised(*group, on);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    return result;
}

}  // namespace subdfit::fit
