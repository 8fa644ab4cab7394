#include "fit/step_schedule.h"

#include <algorithm>
#include <numeric>

namespace subdfit::fit {

LossTrend lossTrend(const std::vector<double>& losses) {
    const size_t n = losses.size();
    if (n < 3) return {};
    double meanX = 0.0, meanY = 0.0;
    for (size_t k = 0; k < n; ++k) {
        meanX += double(k);
        meanY += losses[k];
    }
    meanX /= double(n);
    meanY /= double(n);
    double sxx = 0.0, sxy = 0.0;
    for (size_t k = 0; k < n; ++k) {
        sxx += (double(k) - meanX) * (double(k) - meanX);
        sxy += (double(k) - meanX) * (losses[k] - meanY);
    }
    const double slope = sxy / sxx;
    double residuals = 0.0;
    for (size_t k = 0; k < n; ++k) {
        const double r = losses[k] - (meanY + slope * (double(k) - meanX));
        residuals += r * r;
    }
    const double slopeError = std::sqrt(residuals / double(n - 2) / sxx);
    if (!(meanY > 0.0) || !std::isfinite(slope)) return {};
    // Over the span of the series, relative to its level.
    const double span = double(n - 1) / meanY;
    return {-slope * span, slopeError * span};
}

bool likelyImproving(const LossTrend& trend, double minFall, double confidence) {
    return std::isfinite(trend.standardError) && trend.fall + confidence * trend.standardError >= minFall;
}

namespace {

// A rise of kClearRise even at the losses' fall plus kProbationConfidence standard errors.
bool rose(const std::vector<double>& losses) {
    const LossTrend trend = lossTrend(losses);
    return std::isfinite(trend.standardError) &&
           trend.fall + StepSchedule::kProbationConfidence * trend.standardError < -StepSchedule::kClearRise;
}

}  // namespace

StepSchedule::Decision StepSchedule::record(double loss, int step) {
    const bool finite = std::isfinite(loss);
    const bool best = finite && loss < state_.bestLoss;
    if (best) {
        state_.bestLoss = loss;
        state_.bestStep = step;
    }
    if (state_.stageStart < 0) state_.stageStart = step;
    if (!finite) loss = state_.window.empty() ? 0.0 : state_.window.back();
    if (state_.stageLosses.size() < size_t(kWindow)) state_.stageLosses.push_back(loss);
    state_.window.push_back(loss);
    const size_t window = size_t(this->window());
    if (state_.window.size() > window) state_.window.erase(state_.window.begin());
    if (state_.window.size() < window) return {best, Action::Continue};
    const double minFall = kMinImprovement * double(window) / kWindow;
    if (likelyImproving(lossTrend(state_.window), minFall, kConfidence)) return {best, Action::Continue};
    state_.window.clear();
    if (state_.halvings >= kMaxHalvings) return {best, Action::Converged};
    ++state_.halvings;
    return {best, Action::Halve};
}

int StepSchedule::window() const { return kWindow << std::min(state_.halvings, windowDoublings_); }

bool StepSchedule::paying() const {
    // The trend, not the best: on a noisy loss the lowest of a few measurements is below the
    // first by chance.
    return likelyImproving(lossTrend(state_.stageLosses), kMinImprovement, kProbationConfidence);
}

StepSchedule::Verdict StepSchedule::probation() const {
    const auto& losses = state_.stageLosses;
    if (state_.probationAsksAGain) {
        // A gain that holds: the current window's mean below the start, not one early best that
        // the monitor's noise picked and every measurement since has stayed above.
        const std::vector<double>& recent = state_.window.empty() ? losses : state_.window;
        const double level =
            std::accumulate(recent.begin(), recent.end(), 0.0) / double(std::max<size_t>(recent.size(), 1));
        const bool fell = !losses.empty() && level < (1.0 - kMinImprovement) * losses.front();
        // A window a halving has just restarted says little: three noisy points make any fall likely.
        const bool falling = state_.window.size() >= size_t(kWindow / 2) &&
                             likelyImproving(lossTrend(state_.window), kMinImprovement, kProbationConfidence);
        return fell || falling ? Verdict::Paying : Verdict::NoGain;
    }
    if (state_.probationStopsOnlyARise) return rose(losses) ? Verdict::NoGain : Verdict::Paying;
    if (paying()) return Verdict::Paying;
    if (losses.empty()) return Verdict::NoGain;
    const bool fell = state_.bestLoss < (1.0 - kMinImprovement) * losses.front();
    const bool rebounding = losses.back() < (1.0 - kRebound) * *std::max_element(losses.begin(), losses.end());
    return (fell || rebounding) && state_.halvings < kMaxHalvings ? Verdict::StepTooLarge : Verdict::NoGain;
}

bool StepSchedule::clearlyRose() const {
    return state_.stageLosses.size() >= size_t(kWindow) && rose(state_.stageLosses);
}

void StepSchedule::halve() {
    ++state_.halvings;
    state_.window.clear();
}

void StepSchedule::retryFromBest(int step) {
    halve();
    state_.stageStart = step;
    state_.stageLosses = {state_.bestLoss};
    state_.startTheta = state_.bestTheta;
    state_.probationOver = false;
}

}  // namespace subdfit::fit
